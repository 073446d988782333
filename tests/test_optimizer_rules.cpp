// The optimisers' arithmetic and stop rules against hand computations: Adam's first two steps
// (bias-corrected moments) from finite-difference gradients, decoupled weight decay on weights only,
// the learning-rate schedules in closed form; Levenberg–Marquardt's goal, min_grad, mu_max and
// max_fail stops on constructed problems, and the failure counter on constructed outcome sequences.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/nn/mlp.h"
#include "core/nn/trainer.h"
#include "core/nn/validation_monitor.h"
#include "core/util/rng.h"

namespace test_optimizer_rules {

using namespace rrf;

namespace {

MlpArch smallArch() {
    MlpArch a;
    a.inputs = 2;
    a.hidden = {3};
    a.outputs = 1;
    return a;
}

/// N samples of y = 0.8 sin(2x₀) x₁ − 0.1 on [-1, 1]², normalised units.
void makeData(int n, uint64_t seed, MatX<float>& x, MatX<float>& y, double sign = 1.0) {
    x.resize(2, n);
    y.resize(1, n);
    for (int j = 0; j < n; ++j) {
        Rng rng(seed, uint64_t(j));
        x(0, j) = 2 * rng.uniform() - 1;
        x(1, j) = 2 * rng.uniform() - 1;
        y(0, j) = float(sign * (0.8 * std::sin(2.0 * x(0, j)) * x(1, j) - 0.1));
    }
}

/// Mean squared error of the network on (x, y), in double.
double mse(const MlpArch& a, const VecX<double>& w, const MatX<float>& x, const MatX<float>& y) {
    std::vector<MatX<double>> acts;
    const MatX<double> xd = x.cast<double>();
    mlpForward<double>(a, w.data(), xd, acts);
    return (acts.back() - y.cast<double>()).squaredNorm() / double(y.size());
}

/// Central finite-difference gradient of mse (independent of mlpBackward).
VecX<double> fdGradient(const MlpArch& a, const VecX<double>& w, const MatX<float>& x, const MatX<float>& y) {
    VecX<double> g(w.size());
    const double h = 1e-6;
    for (Eigen::Index i = 0; i < w.size(); ++i) {
        VecX<double> wp = w, wm = w;
        wp[i] += h;
        wm[i] -= h;
        g[i] = (mse(a, wp, x, y) - mse(a, wm, x, y)) / (2 * h);
    }
    return g;
}

/// One full-batch Adam run of `epochs` epochs (one step each) from w0; returns the weights.
VecX<double> adamSteps(const MlpArch& a, AdamConfig c, const MatX<float>& x, const MatX<float>& y,
                       const VecX<double>& w0, int epochs) {
    c.maxEpochs = epochs;
    c.batchSize = int(x.cols());
    TrainingData d;
    d.xTrain = x;
    d.yTrain = y;
    VecX<double> w = w0;
    const TrainResult r = trainAdam(a, c, d, MinMaxScaler::identity(1), w);
    EXPECT_EQ(r.epochs, epochs);
    return w;
}

AdamConfig constantRate(double lr) {
    AdamConfig c;
    c.schedule = LrSchedule::Constant;
    c.learningRate = lr;
    c.errorGoal = 0;
    c.patience = 0;
    return c;
}

}  // namespace

TEST(AdamUpdate, FirstTwoStepsMatchTheHandComputedBiasCorrectedUpdate) {
    const MlpArch a = smallArch();
    MatX<float> x, y;
    makeData(32, 3, x, y);
    // Start from float-representable weights: the trainer works in float.
    const VecX<double> w0 = initialParams(a, 5).cast<float>().cast<double>();
    const AdamConfig c = constantRate(0.01);
    const double b1 = c.beta1, b2 = c.beta2, eps = c.epsilon, lr = c.learningRate;

    // Step 1: m̂ = g, v̂ = g², so Δ = −η g / (|g| + ε) ≈ −η sign(g) (without the bias correction it
    // would be √(1 − β2)/(1 − β1) ≈ 0.32 times that).
    const VecX<double> g1 = fdGradient(a, w0, x, y);
    VecX<double> w1(w0.size());
    for (Eigen::Index i = 0; i < w0.size(); ++i) w1[i] = w0[i] - lr * g1[i] / (std::fabs(g1[i]) + eps);
    const VecX<double> got1 = adamSteps(a, c, x, y, w0, 1);
    // Step 2 from the hand-computed w1, with m and v carried over and corrected by 1 − β^2.
    const VecX<double> g2 = fdGradient(a, w1, x, y);
    VecX<double> w2(w0.size());
    for (Eigen::Index i = 0; i < w0.size(); ++i) {
        const double m = b1 * (1 - b1) * g1[i] + (1 - b1) * g2[i];
        const double v = b2 * (1 - b2) * g1[i] * g1[i] + (1 - b2) * g2[i] * g2[i];
        w2[i] = w1[i] - lr * (m / (1 - b1 * b1)) / (std::sqrt(v / (1 - b2 * b2)) + eps);
    }
    const VecX<double> got2 = adamSteps(a, c, x, y, w0, 2);
    int checked = 0;
    for (Eigen::Index i = 0; i < w0.size(); ++i) {
        // A gradient within float rounding of 0 has no reliable sign; every other entry must match.
        if (std::fabs(g1[i]) < 1e-4 || std::fabs(g2[i]) < 1e-4) continue;
        ++checked;
        EXPECT_NEAR(got1[i], w1[i], 2e-3 * lr) << "step 1, parameter " << i;
        EXPECT_NEAR(got2[i], w2[i], 2e-3 * lr) << "step 2, parameter " << i;
    }
    EXPECT_GE(checked, int(w0.size()) - 2);
}

TEST(AdamUpdate, WeightDecayShrinksWeightsButNotBiases) {
    const MlpArch a = smallArch();
    MatX<float> x, y;
    makeData(32, 4, x, y);
    const VecX<double> w0 = initialParams(a, 6).cast<float>().cast<double>();
    AdamConfig c = constantRate(0.01);
    c.weightDecay = 0.5;
    const VecX<double> g = fdGradient(a, w0, x, y);
    const VecX<double> got = adamSteps(a, c, x, y, w0, 1);
    // Parameter layout: per layer, the weight matrix [weightOffset, biasOffset) then the biases.
    std::vector<bool> isWeight(size_t(w0.size()), false);
    for (int l = 0; l < a.numLayers(); ++l)
        for (Eigen::Index i = a.weightOffset(l); i < a.biasOffset(l); ++i) isWeight[size_t(i)] = true;
    int weights = 0, biases = 0;
    for (Eigen::Index i = 0; i < w0.size(); ++i) {
        if (std::fabs(g[i]) < 1e-4) continue;
        const double adamStep = g[i] / std::fabs(g[i]);
        const double decay = isWeight[size_t(i)] ? c.weightDecay * w0[i] : 0.0;
        EXPECT_NEAR(got[i], w0[i] - c.learningRate * (adamStep + decay), 2e-3 * c.learningRate)
            << (isWeight[size_t(i)] ? "weight " : "bias ") << i;
        ++(isWeight[size_t(i)] ? weights : biases);
    }
    EXPECT_GE(weights, 6);
    EXPECT_GE(biases, 2);
}

TEST(AdamSchedule, RatesFollowTheirClosedForms) {
    AdamConfig c;
    c.learningRate = 0.02;
    c.minLearningRate = 0.002;
    c.maxEpochs = 11;
    c.schedule = LrSchedule::Constant;
    for (int e = 1; e <= 11; ++e) EXPECT_DOUBLE_EQ(adamLearningRate(c, e), 0.02);
    // Step: η γ^⌊(e − 1)/k⌋: epochs 1–3 at η, 4–6 at ηγ, 7–9 at ηγ², 10–11 at ηγ³.
    c.schedule = LrSchedule::Step;
    c.stepEpochs = 3;
    c.stepGamma = 0.5;
    const double step[] = {0.02, 0.02, 0.02, 0.01, 0.01, 0.01, 0.005, 0.005, 0.005, 0.0025, 0.0025};
    for (int e = 1; e <= 11; ++e) EXPECT_DOUBLE_EQ(adamLearningRate(c, e), step[e - 1]) << "epoch " << e;
    // Cosine: η at the first epoch, η_min at the last, their mean half-way (epoch 6 of 11).
    c.schedule = LrSchedule::Cosine;
    EXPECT_DOUBLE_EQ(adamLearningRate(c, 1), 0.02);
    EXPECT_NEAR(adamLearningRate(c, 6), 0.011, 1e-15);
    EXPECT_NEAR(adamLearningRate(c, 11), 0.002, 1e-15);
    for (int e = 2; e <= 11; ++e) EXPECT_LT(adamLearningRate(c, e), adamLearningRate(c, e - 1));
}

TEST(FailureCounter, CountsConstructedOutcomeSequences) {
    using O = ValidationOutcome;
    const std::vector<O> seq = {O::Failed, O::Failed, O::Improved, O::Failed, O::Unchanged,
                                O::FailedWithinNoise, O::Failed, O::Failed};
    auto stopIndex = [&](FailureCounter f) {
        for (size_t i = 0; i < seq.size(); ++i)
            if (f.update(seq[i], 0.0)) return int(i);
        return -1;
    };
    // trainlm's max_fail ignores ties: F F I F U N F F counts 1 2 0 1 1 1 2 3.
    EXPECT_EQ(stopIndex(FailureCounter(3, false)), 7);
    // Adam's patience counts ties: 1 2 0 1 2 2 3.
    EXPECT_EQ(stopIndex(FailureCounter(3, true)), 6);
    EXPECT_EQ(stopIndex(FailureCounter(2, false)), 1);
    EXPECT_EQ(stopIndex(FailureCounter(0, true)), -1) << "limit 0 never stops";
    // Failures count only at rates ≤ the bound.
    FailureCounter bounded(1, true, 0.1);
    EXPECT_FALSE(bounded.update(O::Failed, 0.2));
    EXPECT_TRUE(bounded.update(O::Failed, 0.1));
}

namespace {

/// LM on 60 training and 20 validation samples of the test function; validation targets negated
/// when `opposed`, so fitting the training set makes the validation loss rise.
TrainResult runLm(const LevenbergMarquardtConfig& cfg, bool opposed, VecX<double>* out = nullptr) {
    const MlpArch a = smallArch();
    TrainingData d;
    makeData(60, 7, d.xTrain, d.yTrain);
    makeData(20, 8, d.xValidation, d.yValidation, opposed ? -1.0 : 1.0);
    VecX<double> w = initialParams(a, 9);
    const TrainResult r = trainLevenbergMarquardt(a, cfg, d, w);
    if (out) *out = w;
    return r;
}

LevenbergMarquardtConfig lmConfig() {
    LevenbergMarquardtConfig c;
    c.maxEpochs = 200;
    c.errorGoal = 0;
    return c;
}

}  // namespace

TEST(LevenbergMarquardtStops, MaxFailStopsAtTheCountedFailure) {
    // Replay trainlm's rule on the recorded validation losses: a failure is a loss above the best so
    // far (ties do not count), an improvement resets; the run must stop exactly when the count
    // reaches max_fail.
    for (const int maxFail : {2, 4}) {
        LevenbergMarquardtConfig c = lmConfig();
        c.maxFail = maxFail;
        const TrainResult r = runLm(c, true);
        ASSERT_EQ(r.stopReason, "validation stop") << "max_fail " << maxFail;
        double best = r.history[0].validationLoss;
        int count = 0, stopAt = -1;
        for (size_t e = 1; e < r.history.size() && stopAt < 0; ++e) {
            const double v = r.history[e].validationLoss;
            if (v < best) {
                best = v;
                count = 0;
            } else if (v > best && ++count == maxFail) {
                stopAt = int(e);
            }
        }
        EXPECT_EQ(r.epochs, stopAt) << "max_fail " << maxFail;
        EXPECT_EQ(int(r.history.size()), stopAt + 1);
    }
}

TEST(LevenbergMarquardtStops, GoalStopsAtTheFirstEpochThatMeetsIt) {
    LevenbergMarquardtConfig c = lmConfig();
    c.maxFail = 0;
    const TrainResult free = runLm(c, false);
    ASSERT_GE(free.history.size(), 6u);
    // A goal between the training MSE of epochs 2 and 3 of the unconstrained run.
    c.goal = std::sqrt(free.history[2].trainLoss * free.history[3].trainLoss);
    ASSERT_LT(free.history[3].trainLoss, c.goal);
    ASSERT_GT(free.history[2].trainLoss, c.goal);
    const TrainResult r = runLm(c, false);
    EXPECT_EQ(r.stopReason, "performance goal met");
    EXPECT_EQ(r.epochs, 3);
    EXPECT_LE(r.history.back().trainLoss, c.goal);
}

TEST(LevenbergMarquardtStops, MinGradStopsWhenTheGradientIsBelowIt) {
    // ‖Jᵀe‖ at the initial weights, with e the residuals of the training set: ½∇SSE = Jᵀe.
    const MlpArch a = smallArch();
    MatX<float> x, y;
    makeData(60, 7, x, y);
    const VecX<double> w0 = initialParams(a, 9);
    const double jte = 0.5 * double(x.cols()) * fdGradient(a, w0, x, y).norm();
    LevenbergMarquardtConfig c = lmConfig();
    c.maxFail = 0;
    c.minGrad = 10 * jte;
    TrainResult r = runLm(c, false);
    EXPECT_EQ(r.stopReason, "minimum gradient reached");
    EXPECT_EQ(r.epochs, 0);
    c.minGrad = 0.1 * jte;
    r = runLm(c, false);
    EXPECT_GE(r.epochs, 1) << "the initial gradient is above this bound";
}

TEST(LevenbergMarquardtStops, MuMaxStopsBeforeAnyStep) {
    // μ0 above mu_max: trainlm stops before the first epoch and keeps the initial weights.
    LevenbergMarquardtConfig c = lmConfig();
    c.maxFail = 0;
    c.mu = 1e-3;
    c.muMax = 1e-4;
    VecX<double> w;
    const TrainResult r = runLm(c, false, &w);
    EXPECT_EQ(r.stopReason, "maximum mu reached");
    EXPECT_EQ(r.epochs, 0);
    EXPECT_EQ(w, initialParams(smallArch(), 9));
}

}  // namespace test_optimizer_rules
