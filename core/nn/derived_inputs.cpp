#include "core/nn/derived_inputs.h"

#include <stdexcept>

namespace rrf {

std::vector<std::string> DerivedInputs::rowNames() const {
    if (!reflected) return {};
    return {"reflected_x", "reflected_y", "reflected_z"};
}

std::string DerivedInputs::describe() const { return reflected ? "reflected" : ""; }

template <typename S>
void DerivedInputs::append(const Eigen::Ref<const MatX<S>>& record, MatX<S>& out) const {
    const Eigen::Index rows = record.rows();
    if (any() && rows < kNormalInput + 3)
        throw std::invalid_argument("derived inputs: records of " + std::to_string(rows) +
                                    " inputs have no view direction and normal (12 geometric inputs)");
    out.resize(rows + count(), record.cols());
    out.topRows(rows) = record;
    if (!reflected) return;
    for (Eigen::Index c = 0; c < record.cols(); ++c) {
        const S v[3] = {record(kViewInput, c), record(kViewInput + 1, c), record(kViewInput + 2, c)};
        const S n[3] = {record(kNormalInput, c), record(kNormalInput + 1, c), record(kNormalInput + 2, c)};
        S r[3];
        reflectAboutNormal(v, n, r);
        for (int i = 0; i < 3; ++i) out(rows + i, c) = r[i];
    }
}

template void DerivedInputs::append<float>(const Eigen::Ref<const MatX<float>>&, MatX<float>&) const;
template void DerivedInputs::append<double>(const Eigen::Ref<const MatX<double>>&, MatX<double>&) const;

}  // namespace rrf
