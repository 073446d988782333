// MLP passes against central finite differences, parameter layout, initialisation and scaling.
#include <gtest/gtest.h>

#include <cmath>

#include "core/nn/mlp.h"
#include "core/util/rng.h"

namespace test_nn_mlp {

using namespace rrf;

namespace {

MlpArch makeArch(int in, std::vector<int> hidden, int out, Activation act = Activation::Tanh) {
    MlpArch a;
    a.inputs = in;
    a.hidden = std::move(hidden);
    a.outputs = out;
    a.activation = act;
    return a;
}

MatX<double> randomInputs(int rows, int cols, uint64_t seed) {
    MatX<double> x(rows, cols);
    Rng rng(seed, 0);
    for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = 2.0 * rng.uniformDouble() - 1.0;
    return x;
}

std::vector<MlpArch> architectures() {
    return {makeArch(3, {5}, 3),                         // one hidden layer
            makeArch(4, {6, 5, 4}, 3),                   // three hidden layers
            makeArch(5, {20, 10}, 6),                    // default hidden sizes, joint 6 outputs
            makeArch(16, {20, 10}, 3),                   // the RRF default network
            makeArch(4, {7, 5}, 3, Activation::Relu)};   // ReLU (kinks avoided below)
}

/// Hidden-unit on/off pattern, to skip ReLU finite differences that straddle a kink.
std::vector<bool> reluPattern(const MlpArch& a, const VecX<double>& w, const MatX<double>& x) {
    std::vector<MatX<double>> acts;
    mlpForward<double>(a, w.data(), x, acts);
    std::vector<bool> p;
    for (size_t l = 0; l + 1 < acts.size(); ++l)
        for (Eigen::Index i = 0; i < acts[l].size(); ++i) p.push_back(acts[l].data()[i] > 0);
    return p;
}

}  // namespace

TEST(Mlp, ParameterLayoutCountsWeightsAndBiases) {
    const MlpArch a = makeArch(16, {20, 10}, 3);
    EXPECT_EQ(a.numParams(), 16 * 20 + 20 + 20 * 10 + 10 + 10 * 3 + 3);
    EXPECT_EQ(a.weightOffset(1), 16 * 20 + 20);
    EXPECT_EQ(a.biasOffset(0), 16 * 20);
    EXPECT_EQ(a.describe(), "16-20-10-3 tanh");
    EXPECT_THROW(makeArch(0, {20}, 3).validate(), std::invalid_argument);
    EXPECT_THROW(makeArch(3, {0}, 3).validate(), std::invalid_argument);
}

TEST(Mlp, GradientMatchesCentralDifferences) {
    int checked = 0;
    for (const MlpArch& a : architectures()) {
        const VecX<double> w0 = initialParams(a, 7);
        const MatX<double> x = randomInputs(a.inputs, 9, 3);
        const MatX<double> y = randomInputs(a.outputs, 9, 4);
        std::vector<MatX<double>> acts, deltas;
        auto loss = [&](const VecX<double>& w) {
            mlpForward<double>(a, w.data(), x, acts);
            return 0.5 * (acts.back() - y).squaredNorm();
        };
        loss(w0);
        const MatX<double> dOut = acts.back() - y;
        VecX<double> g(a.numParams());
        mlpBackward<double>(a, w0.data(), x, acts, dOut, deltas, g.data());
        const double h = 1e-6;
        const std::vector<bool> base = a.activation == Activation::Relu ? reluPattern(a, w0, x) : std::vector<bool>();
        for (Eigen::Index i = 0; i < a.numParams(); ++i) {
            VecX<double> wp = w0, wm = w0;
            wp[i] += h;
            wm[i] -= h;
            if (a.activation == Activation::Relu && (reluPattern(a, wp, x) != base || reluPattern(a, wm, x) != base))
                continue;
            const double fd = (loss(wp) - loss(wm)) / (2 * h);
            EXPECT_NEAR(g[i], fd, 1e-6 * std::max(1.0, std::abs(fd))) << a.describe() << " param " << i;
            ++checked;
        }
    }
    EXPECT_GT(checked, 1150);  // 1214 parameters in all; a few ReLU ones sit at kinks
}

TEST(Mlp, JacobianRowsMatchCentralDifferences) {
    for (const MlpArch& a : architectures()) {
        const VecX<double> w0 = initialParams(a, 11);
        const int n = 4;
        const MatX<double> x = randomInputs(a.inputs, n, 5);
        std::vector<MatX<double>> acts, deltas;
        mlpForward<double>(a, w0.data(), x, acts);
        MatX<double> jt;
        mlpJacobianT<double>(a, w0.data(), x, acts, deltas, jt);
        ASSERT_EQ(jt.rows(), a.numParams());
        ASSERT_EQ(jt.cols(), n * a.outputs);
        const double h = 1e-6;
        const std::vector<bool> base = a.activation == Activation::Relu ? reluPattern(a, w0, x) : std::vector<bool>();
        for (Eigen::Index i = 0; i < a.numParams(); ++i) {
            VecX<double> wp = w0, wm = w0;
            wp[i] += h;
            wm[i] -= h;
            if (a.activation == Activation::Relu && (reluPattern(a, wp, x) != base || reluPattern(a, wm, x) != base))
                continue;
            mlpForward<double>(a, wp.data(), x, acts);
            const MatX<double> op = acts.back();
            mlpForward<double>(a, wm.data(), x, acts);
            const MatX<double> fd = (op - acts.back()) / (2 * h);
            for (int k = 0; k < a.outputs; ++k)
                for (int s = 0; s < n; ++s)
                    EXPECT_NEAR(jt(i, k * n + s), fd(k, s), 1e-7 * std::max(1.0, std::abs(fd(k, s))))
                        << a.describe() << " param " << i << " output " << k << " sample " << s;
        }
    }
}

TEST(Mlp, FloatForwardAgreesWithDouble) {
    const MlpArch a = makeArch(16, {64, 64, 64}, 3);
    const VecX<double> w = initialParams(a, 3);
    const MatX<double> x = randomInputs(16, 100, 8);
    std::vector<MatX<double>> ad;
    std::vector<MatX<float>> af;
    mlpForward<double>(a, w.data(), x, ad);
    const VecX<float> wf = w.cast<float>();
    mlpForward<float>(a, wf.data(), x.cast<float>(), af);
    EXPECT_LT((af.back().cast<double>() - ad.back()).cwiseAbs().maxCoeff(), 1e-4);
}

TEST(Mlp, InitialParamsArePureFunctionsOfSeedAndStream) {
    const MlpArch a = makeArch(16, {20, 10}, 3);
    const VecX<double> p1 = initialParams(a, 5), p2 = initialParams(a, 5), p3 = initialParams(a, 6),
                       p4 = initialParams(a, 5, 1);
    EXPECT_EQ(p1, p2);
    EXPECT_NE(p1, p3);
    EXPECT_NE(p1, p4);
    EXPECT_TRUE(p1.allFinite());
    // Nguyen–Widrow: first-layer rows have norm 0.7·S^(1/R).
    Eigen::Map<const MatX<double>> W(p1.data(), 20, 16);
    EXPECT_NEAR(W.row(0).norm(), 0.7 * std::pow(20.0, 1.0 / 16), 1e-12);
}

TEST(MinMaxScaler, MapsToUnitRangeAndBack) {
    MatX<float> d(3, 4);
    d << 0, 1, 2, 4,       //
        5, 5, 5, 5,        // constant: maps to 0
        -1e4f, 1e-4f, 3, 1e4f;
    const MinMaxScaler s = MinMaxScaler::fit(d);
    MatX<double> n = d.cast<double>();
    s.apply(n);
    EXPECT_DOUBLE_EQ(n.row(0).minCoeff(), -1.0);
    EXPECT_DOUBLE_EQ(n.row(0).maxCoeff(), 1.0);
    EXPECT_EQ(n.row(1), Eigen::RowVectorXd::Zero(4));
    EXPECT_DOUBLE_EQ(n(2, 0), -1.0);
    EXPECT_DOUBLE_EQ(n(2, 3), 1.0);
    s.invert(n);
    EXPECT_LT((n - d.cast<double>()).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_TRUE(s.scale.allFinite());
}

TEST(MinMaxScaler, SingleSampleAndEmptyAreFinite) {
    MatX<float> one(2, 1);
    one << 3, -7;
    const MinMaxScaler s = MinMaxScaler::fit(one);
    MatX<float> n = one;
    s.apply(n);
    EXPECT_EQ(n(0, 0), 0.f);
    EXPECT_EQ(n(1, 0), 0.f);
    const MinMaxScaler e = MinMaxScaler::fit(MatX<float>(2, 0));
    EXPECT_EQ(e.scale, VecX<double>::Ones(2));
}

TEST(MinMaxScaler, RoundingNoiseIsNotStretched) {
    // The fixed coordinate of hit points on the wall x = -1 scatters by a few float ulps; it must
    // stay a (near-)constant input, not become a full-range one. A small but real range at small
    // magnitude (direct light ~1e-4 ± 1e-6) must still be scaled.
    MatX<float> d(2, 4);
    d << -1.f, std::nextafter(-1.f, 0.f), std::nextafter(-1.f, -2.f), -1.f,  //
        1.0e-4f, 1.02e-4f, 0.98e-4f, 1.01e-4f;
    const MinMaxScaler s = MinMaxScaler::fit(d);
    MatX<double> n = d.cast<double>();
    s.apply(n);
    EXPECT_LT(n.row(0).cwiseAbs().maxCoeff(), 1e-6);
    EXPECT_DOUBLE_EQ(n.row(1).minCoeff(), -1.0);
    EXPECT_DOUBLE_EQ(n.row(1).maxCoeff(), 1.0);
}

}  // namespace test_nn_mlp
