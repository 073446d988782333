#include "core/predict/member_spread.h"

#include <cmath>

namespace rrf {

bool memberSpread(const std::vector<SpreadTerm>& terms, const Eigen::Ref<const MatX<float>>& x, MatX<float>& sd) {
    if (terms.empty()) return false;
    for (const SpreadTerm& t : terms)
        if (!t.net || t.net->spreadMembers() == 0) return false;
    MatX<double> var = MatX<double>::Zero(3, x.cols());
    std::vector<bool> done(terms.size(), false);
    for (size_t a = 0; a < terms.size(); ++a) {
        if (done[a]) continue;
        // Terms of one network sum member by member (a joint network's direct and indirect rows).
        const std::vector<MatX<float>> members = terms[a].net->predictMembers(x);
        const double k = double(members.size());
        MatX<double> sum = MatX<double>::Zero(3, x.cols()), sumSq = MatX<double>::Zero(3, x.cols());
        for (const MatX<float>& m : members) {
            MatX<double> s = MatX<double>::Zero(3, x.cols());
            for (size_t b = a; b < terms.size(); ++b)
                if (terms[b].net == terms[a].net) s += m.middleRows(terms[b].row, 3).cast<double>();
            sum += s;
            sumSq += s.cwiseProduct(s);
        }
        for (size_t b = a; b < terms.size(); ++b)
            if (terms[b].net == terms[a].net) done[b] = true;
        const MatX<double> mean = sum / k;
        var += (sumSq / k - mean.cwiseProduct(mean)).cwiseMax(0.0);
    }
    sd = var.cwiseSqrt().cast<float>();
    return true;
}

}  // namespace rrf
