#include "core/nn/adam_step.h"

#include <stdexcept>

#include "core/nn/mlp_isa.h"
#include "core/nn/mlp_kernel.h"

namespace rrf {

void adamStep(const AdamStepParams& p, const VecX<float>& grad, const VecX<float>& decayMask, VecX<float>& w,
              VecX<float>& m, VecX<float>& v) {
    const Eigen::Index n = w.size();
    if (grad.size() != n || decayMask.size() != n || m.size() != n || v.size() != n)
        throw std::invalid_argument("adamStep: the gradient, mask and moments must have the weights' size " +
                                    std::to_string(n));
#ifdef RRF_MLP_ISA
    if (const MlpKernel k = mlpKernel(); k != MlpKernel::Portable) {
        const mlp_isa::AdamStep s{p.beta1, p.beta2, p.correction1, p.correction2, p.learningRate, p.epsilon,
                                  p.weightDecay};
        if (k == MlpKernel::Avx512)
            mlp_isa::avx512::adamStep(s, n, grad.data(), decayMask.data(), w.data(), m.data(), v.data());
        else
            mlp_isa::avx2::adamStep(s, n, grad.data(), decayMask.data(), w.data(), m.data(), v.data());
        return;
    }
#endif
    // The same expression as mlp_isa.inl's.
    const float b1 = p.beta1, b2 = p.beta2;
    m = b1 * m + (1.0f - b1) * grad;
    v = b2 * v + (1.0f - b2) * grad.cwiseAbs2();
    w.array() -= p.learningRate * ((m.array() / p.correction1) / ((v.array() / p.correction2).sqrt() + p.epsilon) +
                                   p.weightDecay * decayMask.array() * w.array());
}

}  // namespace rrf
