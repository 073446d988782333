#pragma once
/// The dense Adam step of the network weights (Kingma & Ba 2015, with decoupled weight decay as
/// AdamW), run by the MLP kernel in use (nn/mlp_kernel.h): the portable build's or the one compiled
/// for AVX2 + FMA or AVX-512 (nn/mlp_isa.h). The same expression in each; kernels differ by the
/// square root's rounding only (Eigen's fast square root per packet width).
///
/// Every entry's step depends on that entry alone, so the result does not depend on threads.

#include "core/nn/mlp.h"

namespace rrf {

/// One step's constants: the moments' decay rates, the bias corrections 1 − β₁ᵗ and 1 − β₂ᵗ of
/// step t, the learning rate, ε and the decoupled weight decay.
struct AdamStepParams {
    float beta1 = 0.9f, beta2 = 0.999f;
    float correction1 = 1.f, correction2 = 1.f;
    float learningRate = 1e-3f, epsilon = 1e-8f, weightDecay = 0.f;
};

/// m ← β₁m + (1 − β₁)g, v ← β₂v + (1 − β₂)g², w ← w − lr·((m/c₁)/(√(v/c₂) + ε) + λ·mask·w), entry
/// by entry. All vectors have the same size; `decayMask` is 1 on weights that decay, 0 elsewhere.
void adamStep(const AdamStepParams& p, const VecX<float>& grad, const VecX<float>& decayMask, VecX<float>& w,
              VecX<float>& m, VecX<float>& v);

}  // namespace rrf
