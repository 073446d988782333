// The blocked small-layer kernel of the float passes (core/nn/mlp_small.inl), which every dispatched
// kernel runs for networks up to 64 wide: against the portable passes to rounding, over the layer
// widths and batch sizes it blocks differently (tails of tiles and of row blocks); its gradients
// against central differences of an independent double-precision forward pass; and its forward
// results independent of how a batch is cut into calls.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/nn/mlp.h"
#include "core/nn/mlp_kernel.h"
#include "core/util/rng.h"

namespace rrf {
namespace {
// Named: the unity build puts other tests' helpers in the same translation unit.
namespace small_kernel_test {

MatX<float> uniformMatrix(Eigen::Index rows, Eigen::Index cols, uint64_t seed) {
    MatX<float> m(rows, cols);
    for (Eigen::Index c = 0; c < cols; ++c) {
        Rng rng(seed, uint64_t(c));
        for (Eigen::Index r = 0; r < rows; ++r) m(r, c) = 2.f * rng.uniform() - 1.f;
    }
    return m;
}

MlpArch network(int inputs, std::vector<int> hidden, int outputs, Activation act) {
    MlpArch a;
    a.inputs = inputs;
    a.hidden = std::move(hidden);
    a.outputs = outputs;
    a.activation = act;
    return a;
}

int widest(const MlpArch& a) {
    int w = 0;
    for (int l = 0; l < a.numLayers(); ++l) w = std::max({w, a.layerInputs(l), a.layerOutputs(l)});
    return w;
}

/// Rounding allowed between two float evaluations that order their sums differently: each layer's
/// dot products of up to `width` + 1 terms (the bias) add O((width + 1)·ε) relative error, compounded
/// over the depth; a gradient is in addition a sum over n samples, whose rounding grows as √n in the
/// typical case. 4 is the margin over these typical growths.
double roundingTolerance(const MlpArch& a, Eigen::Index samples) {
    const double eps = std::numeric_limits<float>::epsilon();
    return 4.0 * eps * (a.numLayers() * (widest(a) + 1.0) + std::sqrt(double(samples)));
}

/// max |a − b| / max(1, max |b|).
double scaledDifference(const MatX<float>& a, const MatX<float>& b) {
    EXPECT_EQ(a.rows(), b.rows());
    EXPECT_EQ(a.cols(), b.cols());
    if (a.rows() != b.rows() || a.cols() != b.cols()) return 1e30;
    if (a.size() == 0) return 0;
    return double((a - b).cwiseAbs().maxCoeff()) / std::max(1.0, double(b.cwiseAbs().maxCoeff()));
}

struct Passes {
    std::vector<MatX<float>> acts, deltas;
    MatX<float> grad, dInputs;
};

/// Forward and backward on rows [0, inputs) of `big` (a strided input), ∂loss/∂output = dOut.
Passes run(const MlpArch& a, const VecX<float>& w, const MatX<float>& big, const MatX<float>& dOut) {
    Passes p;
    const Eigen::Ref<const MatX<float>> x = big.topRows(a.inputs);
    mlpForward<float>(a, w.data(), x, p.acts);
    p.grad.setConstant(a.numParams(), 1, 7.f);  // overwritten, not added to
    mlpBackward<float>(a, w.data(), x, p.acts, dOut, p.deltas, p.grad.data(), &p.dInputs);
    return p;
}

TEST(MlpSmallKernel, MatchesThePortablePassesToRoundingOverWidthsAndTails) {
    const std::vector<MlpArch> nets = {
        network(16, {20, 10}, 3, Activation::Tanh),     network(16, {32, 32, 32}, 3, Activation::Tanh),
        network(16, {64, 64, 64}, 3, Activation::Relu), network(64, {64}, 64, Activation::Tanh),
        network(5, {7, 13}, 6, Activation::Relu),       network(1, {1}, 1, Activation::Tanh),
        network(16, {65}, 3, Activation::Tanh),  // too wide for the blocked kernel: the GEMM
    };
    for (const MlpArch& a : nets)
        for (Eigen::Index n : {Eigen::Index(1), Eigen::Index(63), Eigen::Index(130), Eigen::Index(517)}) {
            const VecX<float> w = initialParams(a, 5).cast<float>();
            const MatX<float> big = uniformMatrix(a.inputs + 3, n, 21);
            const MatX<float> dOut = uniformMatrix(a.outputs, n, 22);
            Passes portable;
            {
                ScopedMlpKernel k(MlpKernel::Portable);
                portable = run(a, w, big, dOut);
            }
            const double tol = roundingTolerance(a, n);
            for (MlpKernel kernel : supportedMlpKernels()) {
                if (kernel == MlpKernel::Portable) continue;
                SCOPED_TRACE(std::string(mlpKernelName(kernel)) + " " + a.describe() + " n=" + std::to_string(n));
                ScopedMlpKernel k(kernel);
                const Passes p = run(a, w, big, dOut);
                for (size_t l = 0; l < p.acts.size(); ++l) EXPECT_LT(scaledDifference(p.acts[l], portable.acts[l]), tol);
                for (size_t l = 0; l + 1 < p.deltas.size(); ++l)
                    EXPECT_LT(scaledDifference(p.deltas[l], portable.deltas[l]), tol) << "deltas " << l;
                EXPECT_LT(scaledDifference(p.grad, portable.grad), tol);
                EXPECT_LT(scaledDifference(p.dInputs, portable.dInputs), tol);
            }
        }
}

/// loss = Σ dOut ⊙ output in double on the portable passes: the independent estimator.
double doubleLoss(const MlpArch& a, const VecX<double>& w, const MatX<double>& x, const MatX<double>& dOut) {
    std::vector<MatX<double>> acts;
    mlpForward<double>(a, w.data(), x, acts);
    return acts.back().cwiseProduct(dOut).sum();
}

TEST(MlpSmallKernel, GradientsMatchCentralDifferencesOfADoubleForwardPass) {
    for (Activation act : {Activation::Tanh, Activation::Relu})
        for (const MlpArch& a : {network(16, {20, 10}, 3, act), network(9, {24, 17}, 6, act)}) {
            const Eigen::Index n = 67;  // a tile's tail
            // Weights and inputs exactly representable in float, so both passes see the same network.
            const VecX<float> wf = initialParams(a, 9).cast<float>();
            const MatX<float> xf = uniformMatrix(a.inputs, n, 31), dOutF = uniformMatrix(a.outputs, n, 32);
            const VecX<double> w = wf.cast<double>();
            const MatX<double> x = xf.cast<double>(), dOut = dOutF.cast<double>();
            VecX<double> fd(a.numParams());
            MatX<double> fdInputs(a.inputs, n);
            {
                ScopedMlpKernel k(MlpKernel::Portable);
                const double h = 1e-6;
                for (Eigen::Index i = 0; i < w.size(); ++i) {
                    VecX<double> wp = w, wm = w;
                    wp(i) += h;
                    wm(i) -= h;
                    fd(i) = (doubleLoss(a, wp, x, dOut) - doubleLoss(a, wm, x, dOut)) / (2 * h);
                }
                for (Eigen::Index c = 0; c < n; ++c)
                    for (Eigen::Index r = 0; r < a.inputs; ++r) {
                        MatX<double> xp = x.col(c), xm = x.col(c);
                        xp(r) += h;
                        xm(r) -= h;
                        fdInputs(r, c) = (doubleLoss(a, w, xp, dOut.col(c)) - doubleLoss(a, w, xm, dOut.col(c))) / (2 * h);
                    }
            }
            // The float gradient's rounding (roundingTolerance) dominates the differences' O(h²) and
            // O(ε_double / h) errors by orders of magnitude.
            const double tol = roundingTolerance(a, n);
            for (MlpKernel kernel : supportedMlpKernels()) {
                SCOPED_TRACE(std::string(mlpKernelName(kernel)) + " " + a.describe());
                ScopedMlpKernel k(kernel);
                const Passes p = run(a, wf, xf, dOutF);
                EXPECT_LT(scaledDifference(p.grad, fd.cast<float>()), tol);
                EXPECT_LT(scaledDifference(p.dInputs, fdInputs.cast<float>()), tol);
            }
        }
}

TEST(MlpSmallKernel, ForwardResultsDoNotDependOnHowTheBatchIsCut) {
    // Threads, shards and ranks evaluate different slices of one batch: every sample's outputs must
    // be the same bits in any slice, wherever it lands in the kernel's tiles.
    const MlpArch a = network(16, {32, 32, 32}, 3, Activation::Tanh);
    const VecX<float> w = initialParams(a, 3).cast<float>();
    const MatX<float> x = uniformMatrix(16, 700, 41);
    // The blocked kernel's property: the portable passes' GEMM treats a product's last columns
    // differently, so there an output's bits may depend on the cut.
    if (supportedMlpKernels().size() < 2) GTEST_SKIP() << "this CPU has no AVX2 or AVX-512 kernel";
    for (MlpKernel kernel : supportedMlpKernels()) {
        if (kernel == MlpKernel::Portable) continue;
        ScopedMlpKernel k(kernel);
        std::vector<MatX<float>> whole, part;
        mlpForward<float>(a, w.data(), x, whole);
        for (Eigen::Index c0 : {Eigen::Index(0), Eigen::Index(1), Eigen::Index(37), Eigen::Index(129)}) {
            const Eigen::Index nc = std::min<Eigen::Index>(201, x.cols() - c0);
            mlpForward<float>(a, w.data(), x.middleCols(c0, nc), part);
            for (size_t l = 0; l < whole.size(); ++l)
                EXPECT_TRUE(part[l] == whole[l].middleCols(c0, nc)) << mlpKernelName(kernel) << " layer " << l << " at " << c0;
        }
    }
}

}  // namespace small_kernel_test
}  // namespace
}  // namespace rrf
