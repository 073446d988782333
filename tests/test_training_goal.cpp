// Training that reaches its goal: the error-goal stop on the validation relative RMSE (noise-aware),
// validation rises within the targets' noise, LM on every record, Adam's patience gated by the
// learning rate, and the relative L2 loss's gradient.
#include <gtest/gtest.h>

#include <cmath>

#include "core/nn/model.h"
#include "core/nn/trainer_config_json.h"
#include "core/nn/training_loss.h"
#include "core/nn/validation_monitor.h"
#include "core/util/rng.h"

namespace test_training_goal {

using namespace rrf;

namespace {

MlpArch arch1d(std::vector<int> hidden) {
    MlpArch a;
    a.inputs = 1;
    a.hidden = std::move(hidden);
    a.outputs = 1;
    return a;
}

/// The closed-form function the networks learn: f(x) = 2 + sin(3x), values in [1, 3].
float truth(float x) { return 2.f + std::sin(3.f * x); }

MatX<float> inputs1d(int n, uint64_t seed) {
    MatX<float> x(1, n);
    for (int i = 0; i < n; ++i) x(0, i) = 2.f * Rng(seed, uint64_t(i)).uniform() - 1.f;
    return x;
}

/// Standard normal numbers from the counter-based Rng (Box–Muller), one per (seed, i).
float gaussian(uint64_t seed, uint64_t i) {
    Rng rng(seed, i);
    const double u1 = std::max(1e-12, double(rng.uniform())), u2 = rng.uniform();
    return float(std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2));
}

/// Relative RMSE of `model` against the closed form on the validation split of n samples.
double trueValidationError(const NetworkModel& m, const MatX<float>& x, uint64_t seed) {
    const DataSplit split = splitSamples(size_t(x.cols()), seed, 0);
    double sum = 0;
    for (uint32_t i : split.validation) {
        const MatX<float> xi = x.col(i);
        const double p = m.predict(xi)(0, 0), t = truth(x(0, i));
        sum += std::pow((p - t) / (std::fabs(t) + 0.01), 2);
    }
    return std::sqrt(sum / double(split.validation.size()));
}

TrainerConfig lm(nlohmann::json extra) {
    extra["type"] = "levenberg_marquardt";
    return trainerConfigFromJson(extra);
}

}  // namespace

TEST(TrainingGoal, StopsWhenTheValidationErrorReachesTheGoal) {
    const MatX<float> x = inputs1d(800, 3);
    MatX<float> y(1, x.cols());
    for (Eigen::Index i = 0; i < x.cols(); ++i) y(0, i) = truth(x(0, i));
    const double goal = 0.01;
    const NetworkModel m = fitNetwork(arch1d({8}), lm({{"error_goal", goal}, {"max_fail", 1000}, {"max_epochs", 300}}), x, y);
    ASSERT_EQ(m.training.stopReason, "error goal reached");
    EXPECT_TRUE(m.training.goalReached);
    EXPECT_EQ(m.training.bestEpoch, m.training.epochs) << "the epoch that met the goal is the one kept";
    // Independent check against the closed form (exact targets: no noise to subtract).
    EXPECT_LE(trueValidationError(m, x, 1), goal);
    // It fired at the first epoch that met the goal, not later.
    for (size_t e = 0; e + 1 < m.training.history.size(); ++e) EXPECT_GT(m.training.history[e].validationRelativeRmse, goal);
    // Without a goal the same run goes on (to a lower training error).
    const NetworkModel free = fitNetwork(arch1d({8}), lm({{"error_goal", 0}, {"max_fail", 1000}, {"max_epochs", 300}}), x, y);
    EXPECT_GT(free.training.epochs, m.training.epochs);
}

TEST(TrainingGoal, NoisyTargetsReachTheGoalOnlyWhenTheirNoiseIsKnown) {
    // Targets with 10 % relative Gaussian noise (twice the goal) and their known variance.
    const int n = 4000;
    const MatX<float> x = inputs1d(n, 5);
    MatX<float> y(1, n), v(1, n);
    const double rel = 0.1;
    for (int i = 0; i < n; ++i) {
        const double t = truth(x(0, i)), sigma = rel * t;
        y(0, i) = float(t + sigma * gaussian(9, uint64_t(i)));
        v(0, i) = float(sigma * sigma);
    }
    const TrainerConfig cfg = lm({{"error_goal", 0.05}, {"max_fail", 1000}, {"max_epochs", 150}});
    const NetworkModel aware = fitNetwork(arch1d({8}), cfg, x, y, v);
    EXPECT_EQ(aware.training.stopReason, "error goal reached");
    EXPECT_NEAR(aware.training.validationRelativeNoise, rel, 0.01) << "noise floor sqrt(mean v / (|y| + 0.01)^2)";
    // The corrected figure estimates the error against the truth: mean((n² − v)/y²) over 600 entries has a
    // standard deviation of about sqrt(2)·rel²/sqrt(600) = 5.8e-4, so 3σ above goal² bounds the truth.
    EXPECT_LE(trueValidationError(aware, x, 1), std::sqrt(0.05 * 0.05 + 3 * 5.8e-4));
    // Not knowing the noise, the raw figure cannot fall below the noise (≈ 0.1): the goal never fires.
    const NetworkModel blind = fitNetwork(arch1d({8}), cfg, x, y);
    EXPECT_NE(blind.training.stopReason, "error goal reached");
    EXPECT_GT(blind.training.validationRelativeRmse, 0.05);
}

TEST(TrainingGoal, ValidationRisesWithinTheNoiseAreNotFailures) {
    // 100 targets t = 1 with noise ±s (alternating, so it sums to 0) and variance s². The best network
    // predicts t; a network predicting t + δ has Δloss = δ² and the noise term's standard deviation
    // σ = 2 δ s / sqrt(N), so the rise is within the noise (Δ ≤ 2σ) exactly when δ ≤ 4 s / sqrt(N) = 0.04.
    const int n = 100;
    const double s = 0.1;
    MatX<float> y(1, n), v(1, n);
    for (int i = 0; i < n; ++i) {
        y(0, i) = float(1.0 + (i % 2 ? s : -s));
        v(0, i) = float(s * s);
    }
    const MinMaxScaler identity = MinMaxScaler::identity(1);
    auto outcome = [&](double delta, bool noiseKnown) {
        ValidationMonitor mon(AdamLoss::Mse, identity, y, noiseKnown ? v : MatX<float>(), 0.0);
        mon.observe(MatX<double>::Constant(1, n, 1.0));
        return mon.observe(MatX<double>::Constant(1, n, 1.0 + delta)).outcome;
    };
    EXPECT_EQ(outcome(0.03, true), ValidationOutcome::FailedWithinNoise);
    EXPECT_EQ(outcome(0.05, true), ValidationOutcome::Failed);
    EXPECT_EQ(outcome(0.03, false), ValidationOutcome::Failed) << "unknown noise: every rise counts";
    EXPECT_EQ(outcome(-0.0, true), ValidationOutcome::Unchanged);

    FailureCounter lmRule(2, /*countUnchanged=*/false);
    EXPECT_FALSE(lmRule.update(ValidationOutcome::FailedWithinNoise, 0));
    EXPECT_FALSE(lmRule.update(ValidationOutcome::FailedWithinNoise, 0));
    EXPECT_FALSE(lmRule.update(ValidationOutcome::Unchanged, 0));
    EXPECT_EQ(lmRule.count(), 0);
    EXPECT_FALSE(lmRule.update(ValidationOutcome::Failed, 0));
    EXPECT_TRUE(lmRule.update(ValidationOutcome::Failed, 0));
}

TEST(TrainingGoal, LmUsesEveryRecordUnlessABoundAppliesAndSaysWhich) {
    const MatX<float> x = inputs1d(30000, 7);
    MatX<float> y(1, x.cols());
    for (Eigen::Index i = 0; i < x.cols(); ++i) y(0, i) = truth(x(0, i));
    std::vector<std::string> notes;
    TrainObserver obs;
    obs.onMessage = [&](const std::string& m) { notes.push_back(m); };
    const NetworkModel all = fitNetwork(arch1d({6}), lm({{"max_epochs", 1}, {"error_goal", 0}}), x, y, obs);
    EXPECT_EQ(all.training.trainSamples, 21000);
    EXPECT_EQ(all.training.trainSamplesUsed, 21000) << "no max_samples and far below the GFLOP budget";
    EXPECT_TRUE(notes.empty());

    // P = 19 weights: 3·P² = 1083 flops per sample; a budget of 1e-5 GFLOP = 10 000 flops allows 9 samples.
    const NetworkModel bounded =
        fitNetwork(arch1d({6}), lm({{"max_epochs", 1}, {"error_goal", 0}, {"max_epoch_gflop", 1e-5}}), x, y, obs);
    EXPECT_EQ(bounded.training.trainSamplesUsed, 9);
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("9 of 21000"), std::string::npos) << notes[0];
    EXPECT_NE(notes[0].find("max_epoch_gflop"), std::string::npos) << notes[0];
}

TEST(AdamSchedule, PatienceCannotStopWhileTheRateIsHigh) {
    AdamConfig c;
    c.maxEpochs = 100;
    c.learningRate = 1e-2;
    c.minLearningRate = 1e-4;
    c.schedule = LrSchedule::Cosine;
    c.patience = 5;
    c.patienceLrFraction = 0.2;
    // First epoch whose cosine rate is ≤ 0.2 η, from the closed form
    // η_min + ½(η − η_min)(1 + cos(π t)) ≤ 0.2 η  ⇔  t ≥ acos(2(0.2η − η_min)/(η − η_min) − 1)/π, t = (e−1)/99.
    const double tMin = std::acos(2 * (0.2 * c.learningRate - c.minLearningRate) / (c.learningRate - c.minLearningRate) - 1) /
                        3.141592653589793;
    const int firstLow = int(std::ceil(tMin * 99.0)) + 1;
    ASSERT_GT(adamLearningRate(c, firstLow - 1), 0.2 * c.learningRate);
    ASSERT_LE(adamLearningRate(c, firstLow), 0.2 * c.learningRate);

    // A loss sequence that never improves after epoch 0: every epoch fails.
    FailureCounter patience(c.patience, true, c.patienceLrFraction * c.learningRate);
    int stoppedAt = -1;
    for (int e = 1; e <= c.maxEpochs && stoppedAt < 0; ++e)
        if (patience.update(ValidationOutcome::Failed, adamLearningRate(c, e))) stoppedAt = e;
    EXPECT_EQ(stoppedAt, firstLow + c.patience - 1);

    // The trainer itself: a rate too small to improve anything stops only after the rate decayed.
    MlpArch a;
    a.inputs = 1;
    a.hidden = {4};
    a.outputs = 1;
    const MatX<float> x = inputs1d(200, 2);
    MatX<float> y(1, x.cols());
    for (Eigen::Index i = 0; i < x.cols(); ++i) y(0, i) = truth(x(0, i));
    TrainerConfig cfg = trainerConfigFromJson({{"type", "adam"}, {"max_epochs", 100}, {"learning_rate", 1e-12},
                                                 {"min_learning_rate", 1e-14}, {"patience", 5}, {"error_goal", 0}});
    const NetworkModel m = fitNetwork(a, cfg, x, y);
    EXPECT_EQ(m.training.stopReason, "validation stop");
    const double lrAtStop = m.training.history.back().step;
    EXPECT_LE(lrAtStop, 0.2 * 1e-12);
    EXPECT_GE(m.training.epochs, 5);
}

TEST(RelativeL2, ValueAndGradientMatchClosedFormAndFiniteDifferences) {
    MlpArch a;
    a.inputs = 2;
    a.hidden = {5};
    a.outputs = 3;
    const VecX<double> w0 = initialParams(a, 4, 0);
    MatX<double> x(2, 7), y(3, 7);
    for (int j = 0; j < 7; ++j) {
        Rng rng(11, uint64_t(j));
        x(0, j) = 2 * rng.uniform() - 1;
        x(1, j) = 2 * rng.uniform() - 1;
        for (int k = 0; k < 3; ++k) y(k, j) = 2 * rng.uniform() - 1;
    }
    MinMaxScaler out;
    out.offset = VecX<double>::Constant(3, 0.3);
    out.scale = (VecX<double>(3) << 2.0, 0.5, 8.0).finished();
    const TrainingLoss<double> loss(AdamLoss::RelativeL2, out);
    std::vector<MatX<double>> acts, deltas;
    auto value = [&](const VecX<double>& w, MatX<double>* dOut) {
        mlpForward<double>(a, w.data(), x, acts);
        return loss.evaluate(acts.back(), y, dOut, double(y.size()));
    };
    // Closed form in raw units: Σ (p − y)² / (|y| + 0.01)², raw = normalised / scale + offset.
    mlpForward<double>(a, w0.data(), x, acts);
    double expected = 0;
    for (int j = 0; j < 7; ++j)
        for (int k = 0; k < 3; ++k) {
            const double p = acts.back()(k, j) / out.scale[k] + out.offset[k], t = y(k, j) / out.scale[k] + out.offset[k];
            expected += std::pow(p - t, 2) / std::pow(std::fabs(t) + 0.01, 2);
        }
    EXPECT_NEAR(value(w0, nullptr), expected, 1e-12 * expected);

    MatX<double> dOut;
    value(w0, &dOut);
    VecX<double> grad(a.numParams());
    mlpBackward<double>(a, w0.data(), x, acts, dOut, deltas, grad.data());
    const double h = 1e-6;
    for (Eigen::Index i = 0; i < w0.size(); ++i) {
        VecX<double> wp = w0, wm = w0;
        wp[i] += h;
        wm[i] -= h;
        const double fd = (value(wp, nullptr) - value(wm, nullptr)) / (2 * h) / double(y.size());
        EXPECT_NEAR(grad[i], fd, 1e-6 * std::max(1.0, std::fabs(fd))) << "parameter " << i;
    }
}

}  // namespace test_training_goal
