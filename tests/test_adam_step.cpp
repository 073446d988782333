// The dense Adam step (nn/adam_step.h) on every kernel: its first step against the closed form
// lr·g/(|g| + ε) + lr·λ·mask·w (moments from zero, bias corrections 1 − β), and later steps of the
// dispatched kernels against the portable one to rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/nn/adam_step.h"
#include "core/nn/mlp_kernel.h"
#include "core/util/rng.h"

namespace rrf {
namespace {
// Named: the unity build puts other tests' helpers in the same translation unit.
namespace adam_step_test {

VecX<float> uniformVector(Eigen::Index n, uint64_t seed, float scale) {
    VecX<float> x(n);
    Rng rng(seed, 0);
    for (Eigen::Index i = 0; i < n; ++i) x(i) = scale * (2.f * rng.uniform() - 1.f);
    return x;
}

TEST(AdamStep, FirstStepIsTheClosedFormOnEveryKernel) {
    const Eigen::Index n = 583;  // the 16-20-10-3 network's parameters: not a multiple of any packet
    const VecX<float> g = uniformVector(n, 1, 2.f), w0 = uniformVector(n, 2, 1.f);
    VecX<float> mask(n);
    for (Eigen::Index i = 0; i < n; ++i) mask(i) = float(i % 3 != 0);
    AdamStepParams p;
    p.beta1 = 0.9f;
    p.beta2 = 0.999f;
    p.correction1 = 1.f - p.beta1;
    p.correction2 = 1.f - p.beta2;
    p.learningRate = 0.01f;
    p.epsilon = 1e-8f;
    p.weightDecay = 0.1f;
    for (MlpKernel kernel : supportedMlpKernels()) {
        ScopedMlpKernel k(kernel);
        VecX<float> w = w0, m = VecX<float>::Zero(n), v = VecX<float>::Zero(n);
        adamStep(p, g, mask, w, m, v);
        for (Eigen::Index i = 0; i < n; ++i) {
            const double gi = g(i), expected = w0(i) - 0.01 * (gi / (std::abs(gi) + 1e-8) + 0.1 * mask(i) * w0(i));
            // A step of at most lr·(1 + λ) in float: a few ulps of w and of the step.
            EXPECT_NEAR(w(i), expected, 8 * std::numeric_limits<float>::epsilon() * (std::abs(expected) + 0.011))
                << mlpKernelName(kernel) << " entry " << i;
        }
    }
}

TEST(AdamStep, DispatchedStepsMatchThePortableOnesToRounding) {
    const Eigen::Index n = 1001;
    const VecX<float> w0 = uniformVector(n, 3, 1.f), mask = VecX<float>::Ones(n);
    AdamStepParams p;
    p.learningRate = 0.003f;
    p.weightDecay = 0.01f;
    auto run = [&](MlpKernel kernel) {
        ScopedMlpKernel k(kernel);
        VecX<float> w = w0, m = VecX<float>::Zero(n), v = VecX<float>::Zero(n);
        for (int t = 1; t <= 20; ++t) {
            p.correction1 = 1.f - std::pow(p.beta1, float(t));
            p.correction2 = 1.f - std::pow(p.beta2, float(t));
            adamStep(p, uniformVector(n, 100 + uint64_t(t), 0.5f), mask, w, m, v);
        }
        return w;
    };
    const VecX<float> portable = run(MlpKernel::Portable);
    // 20 steps of at most lr·(1 + λ) each, every one rounded to a few ulps of its size.
    const double tol = 20 * 8 * std::numeric_limits<float>::epsilon() * 0.003 * 1.01 +
                       20 * 2 * std::numeric_limits<float>::epsilon() * (w0.cwiseAbs().maxCoeff() + 0.1);
    for (MlpKernel kernel : supportedMlpKernels())
        EXPECT_LT((run(kernel) - portable).cwiseAbs().maxCoeff(), tol) << mlpKernelName(kernel);
}

TEST(AdamStep, MismatchedSizesAreNamed) {
    AdamStepParams p;
    VecX<float> w(4), m(4), v(3), g(4), mask(4);
    EXPECT_THROW(adamStep(p, g, mask, w, m, v), std::invalid_argument);
}

}  // namespace adam_step_test
}  // namespace
}  // namespace rrf
