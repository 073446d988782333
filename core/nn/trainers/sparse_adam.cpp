// Sparse Adam with per-entry step counts (see core/nn/trainers/sparse_adam.h).
#include "core/nn/trainers/sparse_adam.h"

#include <cmath>

namespace rrf {

SparseAdam::SparseAdam(Eigen::Index n)
    : grad(VecX<float>::Zero(n)), m(VecX<float>::Zero(n)), v(VecX<float>::Zero(n)), steps(size_t(n), 0u),
      done_(size_t(n), 0) {}

void SparseAdam::step(VecX<float>& params, float beta1, float beta2, float learningRate, float epsilon) {
    for (const int64_t i : touched) {
        if (done_[size_t(i)]) continue;
        done_[size_t(i)] = 1;
        const uint32_t t = ++steps[size_t(i)];
        // Bias corrections for this entry's own number of updates, in double as the dense step's.
        const float c1 = float(1.0 - std::pow(double(beta1), double(t)));
        const float c2 = float(1.0 - std::pow(double(beta2), double(t)));
        const float g = grad[i];
        m[i] = beta1 * m[i] + (1.0f - beta1) * g;
        v[i] = beta2 * v[i] + (1.0f - beta2) * g * g;
        params[i] -= learningRate * ((m[i] / c1) / (std::sqrt(v[i] / c2) + epsilon));
        grad[i] = 0.0f;
    }
    for (const int64_t i : touched) done_[size_t(i)] = 0;
    touched.clear();
}

}  // namespace rrf
