// The instruction-set builds of the MLP passes (nn/mlp_isa.h, nn/mlp_kernel.h) against the portable
// passes, to rounding: activations, parameter gradients and input gradients, for tanh and ReLU, with
// a strided input. The finite-difference checks of tests/test_nn_mlp.cpp run on the kernel chosen at
// start, so the dispatched passes are also checked against an independent derivative.
#include <gtest/gtest.h>

#include <stdexcept>

#include "core/nn/mlp.h"
#include "core/nn/mlp_kernel.h"
#include "core/util/rng.h"

namespace rrf {
namespace {

template <typename S>
MatX<S> randomMatrix(Eigen::Index rows, Eigen::Index cols, uint64_t seed) {
    MatX<S> m(rows, cols);
    for (Eigen::Index c = 0; c < cols; ++c) {
        Rng rng(seed, uint64_t(c));
        for (Eigen::Index r = 0; r < rows; ++r) m(r, c) = S(2 * rng.uniform() - 1);
    }
    return m;
}

/// Largest |a − b| over max(1, max|b|): the passes' outputs are O(1), their gradients sums over N.
template <typename S>
double scaledDifference(const MatX<S>& a, const MatX<S>& b) {
    EXPECT_EQ(a.rows(), b.rows());
    EXPECT_EQ(a.cols(), b.cols());
    if (a.size() == 0 || a.rows() != b.rows() || a.cols() != b.cols()) return a.size() == b.size() ? 0 : 1e30;
    const double scale = std::max(1.0, double(b.cwiseAbs().maxCoeff()));
    return double((a - b).cwiseAbs().maxCoeff()) / scale;
}

struct Passes {
    std::vector<MatX<float>> acts;
    VecX<float> grad;
    MatX<float> dInputs;
};

/// Forward and backward of `a` on the first 16 rows of a 20-row matrix (column stride 20).
Passes run(const MlpArch& a, const VecX<float>& w, const MatX<float>& big, const MatX<float>& dOut) {
    Passes p;
    const Eigen::Ref<const MatX<float>> x = big.topRows(a.inputs);
    EXPECT_EQ(x.outerStride(), big.rows());
    mlpForward<float>(a, w.data(), x, p.acts);
    std::vector<MatX<float>> deltas;
    p.grad.setZero(a.numParams());
    mlpBackward<float>(a, w.data(), x, p.acts, dOut, deltas, p.grad.data(), &p.dInputs);
    return p;
}

TEST(MlpKernel, DispatchedPassesMatchThePortableOnesToRounding) {
    const std::vector<MlpKernel> kernels = supportedMlpKernels();
    ASSERT_FALSE(kernels.empty());
    EXPECT_EQ(kernels.front(), MlpKernel::Portable);
    for (Activation act : {Activation::Tanh, Activation::Relu})
        for (const std::vector<int>& hidden : {std::vector<int>{20, 10}, std::vector<int>{32, 32, 32}}) {
            MlpArch a;
            a.inputs = 16;
            a.hidden = hidden;
            a.outputs = 3;
            a.activation = act;
            const VecX<float> w = initialParams(a, 7).cast<float>();
            const MatX<float> big = randomMatrix<float>(20, 517, 11);  // 517: not a multiple of any packet
            const MatX<float> dOut = randomMatrix<float>(3, 517, 12);
            Passes portable;
            {
                ScopedMlpKernel k(MlpKernel::Portable);
                portable = run(a, w, big, dOut);
            }
            for (MlpKernel kernel : kernels) {
                if (kernel == MlpKernel::Portable) continue;
                SCOPED_TRACE(std::string(mlpKernelName(kernel)) + " " + a.describe());
                ScopedMlpKernel k(kernel);
                const Passes p = run(a, w, big, dOut);
                ASSERT_EQ(p.acts.size(), portable.acts.size());
                for (size_t l = 0; l < p.acts.size(); ++l) EXPECT_LT(scaledDifference(p.acts[l], portable.acts[l]), 2e-6);
                EXPECT_LT(scaledDifference<float>(p.grad, portable.grad), 2e-6);
                EXPECT_LT(scaledDifference(p.dInputs, portable.dInputs), 2e-6);
                // Not the same code: a dispatch that silently ran the portable passes would be exact.
                EXPECT_NE(scaledDifference<float>(p.grad, portable.grad), 0.0);
            }
        }
}

TEST(MlpKernel, DoublePassesMatchThePortableOnes) {
    MlpArch a;
    a.inputs = 16;
    a.hidden = {20, 10};
    const VecX<double> w = initialParams(a, 3);
    const MatX<double> x = randomMatrix<double>(16, 300, 5), dOut = randomMatrix<double>(3, 300, 6);
    auto pass = [&](MlpKernel kernel) {
        ScopedMlpKernel k(kernel);
        std::vector<MatX<double>> acts, deltas;
        mlpForward<double>(a, w.data(), x, acts);
        VecX<double> g = VecX<double>::Zero(a.numParams());
        mlpBackward<double>(a, w.data(), x, acts, dOut, deltas, g.data());
        return std::make_pair(acts.back(), g);
    };
    const auto portable = pass(MlpKernel::Portable);
    for (MlpKernel kernel : supportedMlpKernels()) {
        const auto p = pass(kernel);
        EXPECT_LT(scaledDifference(p.first, portable.first), 1e-13) << mlpKernelName(kernel);
        EXPECT_LT(scaledDifference<double>(p.second, portable.second), 1e-13) << mlpKernelName(kernel);
    }
}

TEST(MlpKernel, EmptyBatchesPassThrough) {
    MlpArch a;
    a.inputs = 16;
    const VecX<float> w = initialParams(a, 1).cast<float>();
    for (MlpKernel kernel : supportedMlpKernels()) {
        ScopedMlpKernel k(kernel);
        std::vector<MatX<float>> acts, deltas;
        const MatX<float> x(16, 0), dOut(3, 0);
        mlpForward<float>(a, w.data(), x, acts);
        ASSERT_EQ(acts.back().cols(), 0);
        VecX<float> g = VecX<float>::Constant(a.numParams(), 5.f);
        mlpBackward<float>(a, w.data(), x, acts, dOut, deltas, g.data());
        EXPECT_EQ(g.cwiseAbs().maxCoeff(), 0.f) << mlpKernelName(kernel);  // a sum over no samples
    }
}

TEST(MlpKernel, NamesParseAndUnknownNamesAreNamed) {
    for (MlpKernel k : {MlpKernel::Portable, MlpKernel::Avx2, MlpKernel::Avx512})
        EXPECT_EQ(parseMlpKernel(mlpKernelName(k), "RRF_MLP_KERNEL"), k);
    try {
        parseMlpKernel("sse9", "RRF_MLP_KERNEL");
        FAIL() << "sse9 parsed";
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(), "RRF_MLP_KERNEL=sse9: expected portable, avx2 or avx512");
    }
    EXPECT_TRUE(mlpKernelSupported(MlpKernel::Portable));
    EXPECT_TRUE(mlpKernelSupported(mlpKernel()));
}

}  // namespace
}  // namespace rrf
