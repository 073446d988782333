#include "core/data/record_noise.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/util/relative_error.h"

namespace rrf {

double relativeNoise(const float mean[6], const float var[6]) {
    double worst = 0;
    for (int term = 0; term < 2; ++term) {
        double sum = 0;
        for (int c = 3 * term; c < 3 * term + 3; ++c) {
            if (!(var[c] >= 0.f)) return std::numeric_limits<double>::quiet_NaN();
            const double d = std::fabs(double(mean[c])) + kRelativeEpsilon;
            sum += double(var[c]) / (d * d);
        }
        worst = std::max(worst, std::sqrt(sum / 3.0));
    }
    return worst;
}

NoiseSummary summarizeNoise(const float* records, size_t count, int fpr, int targetOffset, int noiseOffset) {
    std::vector<double> r;
    r.reserve(count);
    for (size_t k = 0; k < count; ++k) {
        const float* rec = records + k * size_t(fpr);
        const double v = relativeNoise(rec + targetOffset, rec + noiseOffset);
        if (std::isfinite(v)) r.push_back(v);
    }
    NoiseSummary s;
    s.known = r.size();
    if (r.empty()) return s;
    // Nearest-rank quantiles: deterministic and exact for the sample at hand.
    auto quantile = [&](double q) {
        const size_t i = std::min(r.size() - 1, size_t(std::ceil(q * double(r.size()))) - (q > 0 ? 1 : 0));
        std::nth_element(r.begin(), r.begin() + long(i), r.end());
        return r[i];
    };
    s.median = quantile(0.5);
    s.p90 = quantile(0.9);
    return s;
}

}  // namespace rrf
