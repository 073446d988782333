// Levenberg–Marquardt and Adam: convergence, hard cases, determinism, cancel, config parsing.
#include <gtest/gtest.h>

#include <cmath>

#include <tbb/global_control.h>

#include "core/nn/trainer_config_json.h"
#include "core/util/error.h"
#include "core/nn/model.h"
#include "core/util/rng.h"

namespace test_nn_training {

using namespace rrf;

namespace {

MlpArch makeArch(int in, std::vector<int> hidden, int out) {
    MlpArch a;
    a.inputs = in;
    a.hidden = std::move(hidden);
    a.outputs = out;
    return a;
}

MatX<float> uniformInputs(int rows, int cols, uint64_t seed) {
    MatX<float> x(rows, cols);
    for (int c = 0; c < cols; ++c) {
        Rng rng(seed, uint64_t(c));
        for (int r = 0; r < rows; ++r) x(r, c) = 2.f * rng.uniform() - 1.f;
    }
    return x;
}

/// Outputs of a random "teacher" network of shape `a`.
MatX<float> teacherOutputs(const MlpArch& a, const MatX<float>& x, uint64_t seed) {
    const VecX<double> w = initialParams(a, seed, 77);
    std::vector<MatX<double>> acts;
    mlpForward<double>(a, w.data(), x.cast<double>(), acts);
    return acts.back().cast<float>();
}

TrainerConfig lmConfig(nlohmann::json extra = nlohmann::json::object()) {
    extra["type"] = "levenberg_marquardt";
    return trainerConfigFromJson(extra);
}

TrainerConfig adamConfig(nlohmann::json extra = nlohmann::json::object()) {
    extra["type"] = "adam";
    return trainerConfigFromJson(extra);
}

bool finiteModel(const NetworkModel& m) {
    return m.params.allFinite() && std::isfinite(m.training.trainLoss) && std::isfinite(m.errors.train);
}

}  // namespace

TEST(DataSplit, SeventyFifteenFifteenAndDeterministic) {
    const DataSplit a = splitSamples(1000, 3), b = splitSamples(1000, 3), c = splitSamples(1000, 4);
    EXPECT_EQ(a.train.size(), 700u);
    EXPECT_EQ(a.validation.size(), 150u);
    EXPECT_EQ(a.test.size(), 150u);
    EXPECT_EQ(a.train, b.train);
    EXPECT_EQ(a.test, b.test);
    EXPECT_NE(a.train, c.train);
    std::vector<int> seen(1000, 0);
    for (const auto* part : {&a.train, &a.validation, &a.test})
        for (uint32_t i : *part) ++seen[i];
    for (int s : seen) EXPECT_EQ(s, 1);
    const DataSplit one = splitSamples(1, 3);
    EXPECT_EQ(one.train.size(), 1u);
    EXPECT_TRUE(one.validation.empty() && one.test.empty());
}

TEST(TrainerConfig, DefaultsMatchTrainlmAndRoundTrip) {
    const TrainerConfig c = trainerConfigFromJson(nlohmann::json::object());
    EXPECT_EQ(c.type, TrainerType::LevenbergMarquardt);
    EXPECT_EQ(c.lm.mu, 1e-3);
    EXPECT_EQ(c.lm.muDec, 0.1);
    EXPECT_EQ(c.lm.muInc, 10.0);
    EXPECT_EQ(c.lm.muMax, 1e10);
    EXPECT_EQ(c.lm.maxEpochs, 1000);
    EXPECT_EQ(c.lm.minGrad, 1e-7);
    EXPECT_EQ(c.lm.maxFail, 6);
    const TrainerConfig a = adamConfig({{"loss", "relative_l2"}, {"schedule", "step"}, {"seed", 9}});
    EXPECT_EQ(toJson(trainerConfigFromJson(toJson(a))), toJson(a));
    EXPECT_EQ(toJson(trainerConfigFromJson(toJson(c))), toJson(c));
}

TEST(TrainerConfig, BadKeysAreNamed) {
    auto message = [](const nlohmann::json& j) {
        try {
            trainerConfigFromJson(j, "p.json");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message({{"type", "adam"}, {"learnig_rate", 1}}).find("/trainer/learnig_rate"), std::string::npos);
    EXPECT_NE(message({{"mu", "big"}}).find("/trainer/mu"), std::string::npos);
    EXPECT_NE(message({{"type", "sgd"}}).find("/trainer/type"), std::string::npos);
    EXPECT_NE(message({{"max_epochs", 2.5}}).find("max_epochs"), std::string::npos);
    EXPECT_NE(message({{"type", "adam"}, {"loss", "l1"}}).find("p.json"), std::string::npos);
    EXPECT_NE(message({{"mu_dec", 2}}).find("mu_dec"), std::string::npos);
}

TEST(LevenbergMarquardt, RecoversTeacherNetwork) {
    const MlpArch a = makeArch(3, {6, 4}, 3);
    const MatX<float> x = uniformInputs(3, 400, 1);
    const MatX<float> y = teacherOutputs(a, x, 5);
    const NetworkModel m = fitNetwork(a, lmConfig({{"goal", 1e-14}, {"error_goal", 0}, {"max_fail", 50}, {"max_epochs", 400}}), x, y);
    EXPECT_LT(m.training.testLoss, 1e-6) << m.training.stopReason << " after " << m.training.epochs;
    EXPECT_LT(m.training.trainLoss, 1e-6);
    // Matlab semantics: μ was adapted, losses recorded from epoch 0.
    ASSERT_GT(m.training.history.size(), 2u);
    EXPECT_EQ(m.training.history.front().epoch, 0);
    EXPECT_EQ(m.training.history.front().step, 1e-3);
}

TEST(LevenbergMarquardt, SingularJtJStaysFinite) {
    // Duplicated samples, a dead (constant) input and a constant target channel make JᵀJ singular.
    const MlpArch a = makeArch(4, {20, 10}, 3);
    MatX<float> x = uniformInputs(4, 40, 2);
    x.row(2).setConstant(0.5f);
    MatX<float> xd(4, 200), yd(3, 200);
    for (int c = 0; c < 200; ++c) xd.col(c) = x.col(c % 40);
    for (int c = 0; c < 200; ++c) {
        yd(0, c) = std::sin(3 * xd(0, c));
        yd(1, c) = 2.0f;
        yd(2, c) = xd(1, c) * xd(3, c);
    }
    const NetworkModel m = fitNetwork(a, lmConfig({{"max_epochs", 60}, {"error_goal", 0}}), xd, yd);
    EXPECT_TRUE(finiteModel(m));
    const MatX<float> pred = m.predict(xd);
    EXPECT_TRUE(pred.allFinite());
    EXPECT_LT((pred.row(1).array() - 2.0f).abs().maxCoeff(), 1e-3f);
}

TEST(LevenbergMarquardt, TargetsFromTinyToHugeStayFinite) {
    const MlpArch a = makeArch(2, {8}, 3);
    const MatX<float> x = uniformInputs(2, 300, 3);
    MatX<float> y(3, 300);
    for (int c = 0; c < 300; ++c) {
        y(0, c) = 1e-4f * (1.5f + x(0, c));
        y(1, c) = 1e4f * (1.5f + x(1, c) * x(0, c));
        y(2, c) = std::pow(10.f, 4.f * x(0, c));  // 1e-4 … 1e4 within one channel
    }
    for (const TrainerConfig& cfg : {lmConfig({{"max_epochs", 40}}), adamConfig({{"max_epochs", 20}}),
                                     adamConfig({{"max_epochs", 20}, {"loss", "relative_l2"}})}) {
        const NetworkModel m = fitNetwork(a, cfg, x, y);
        EXPECT_TRUE(finiteModel(m)) << cfg.typeName();
        EXPECT_TRUE(m.predict(x).allFinite());
        // The tiny channel is learned in normalised units, not drowned by the huge one.
        const MatX<float> p = m.predict(x);
        if (cfg.type == TrainerType::LevenbergMarquardt) {
            EXPECT_LT((p.row(0) - y.row(0)).cwiseAbs().maxCoeff(), 2e-6f);
        }
    }
}

TEST(LevenbergMarquardt, SubsamplesAndSaysSo) {
    const MlpArch a = makeArch(3, {5}, 3);
    const MatX<float> x = uniformInputs(3, 1000, 4);
    const MatX<float> y = teacherOutputs(a, x, 6);
    std::vector<std::string> notes;
    TrainObserver obs;
    obs.onMessage = [&](const std::string& m) { notes.push_back(m); };
    const NetworkModel m = fitNetwork(a, lmConfig({{"max_samples", 100}, {"max_epochs", 3}}), x, y, obs);
    EXPECT_EQ(m.training.trainSamples, 700);
    EXPECT_EQ(m.training.trainSamplesUsed, 100);
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("100 of 700"), std::string::npos);
}

TEST(LevenbergMarquardt, BitIdenticalForOneOrTwoThreads) {
    const MlpArch a = makeArch(6, {20, 10}, 3);
    const MatX<float> x = uniformInputs(6, 3000, 7);
    const MatX<float> y = teacherOutputs(makeArch(6, {9}, 3), x, 8);
    auto run = [&](int threads) {
        tbb::global_control gc(tbb::global_control::max_allowed_parallelism, size_t(threads));
        return fitNetwork(a, lmConfig({{"max_epochs", 4}}), x, y);
    };
    const NetworkModel m1 = run(1), m2 = run(2);
    EXPECT_EQ(m1.params, m2.params);
    EXPECT_EQ(m1.training.history.back().trainLoss, m2.training.history.back().trainLoss);
}

TEST(LevenbergMarquardt, CancelStopsBetweenEpochs) {
    const MlpArch a = makeArch(3, {10}, 3);
    const MatX<float> x = uniformInputs(3, 500, 9);
    const MatX<float> y = teacherOutputs(a, x, 10);
    std::atomic<bool> cancel{false};
    TrainObserver obs;
    obs.cancel = &cancel;
    obs.onEpoch = [&](const EpochRecord& r) {
        if (r.epoch == 3) cancel = true;
    };
    const NetworkModel m = fitNetwork(a, lmConfig({{"goal", 1e-30}, {"max_fail", 1000}}), x, y, obs);
    EXPECT_TRUE(m.training.cancelled);
    EXPECT_EQ(m.training.epochs, 3);
    EXPECT_EQ(m.training.stopReason, "cancelled");
    EXPECT_TRUE(finiteModel(m));
}

TEST(Adam, FitsSinTimesCos) {
    // y = sin(πx)·cos(πy) on [-1,1]²: test RMSE below 0.03 (amplitude 1).
    const MlpArch a = makeArch(2, {32, 32}, 1);
    const MatX<float> x = uniformInputs(2, 4000, 11);
    MatX<float> y(1, 4000);
    for (int c = 0; c < 4000; ++c) y(0, c) = std::sin(3.14159265f * x(0, c)) * std::cos(3.14159265f * x(1, c));
    const NetworkModel m = fitNetwork(a, adamConfig({{"max_epochs", 120}, {"batch_size", 64}}), x, y);
    EXPECT_LT(m.errors.test, 0.03) << m.training.stopReason << " epochs " << m.training.epochs;
    EXPECT_GT(m.training.history.size(), 10u);
}

TEST(Adam, BitIdenticalForOneOrTwoThreadsAndSeedMatters) {
    const MlpArch a = makeArch(4, {16, 8}, 3);
    const MatX<float> x = uniformInputs(4, 800, 12);
    const MatX<float> y = teacherOutputs(a, x, 13);
    auto run = [&](int threads, int seed) {
        tbb::global_control gc(tbb::global_control::max_allowed_parallelism, size_t(threads));
        return fitNetwork(a, adamConfig({{"max_epochs", 5}, {"seed", seed}, {"weight_decay", 1e-4}}), x, y);
    };
    const NetworkModel m1 = run(1, 1), m2 = run(2, 1), m3 = run(2, 2);
    EXPECT_EQ(m1.params, m2.params);
    EXPECT_NE(m1.params, m3.params);
}

TEST(Adam, CancelAndEarlyStop) {
    const MlpArch a = makeArch(3, {8}, 3);
    const MatX<float> x = uniformInputs(3, 300, 14);
    const MatX<float> y = teacherOutputs(a, x, 15);
    std::atomic<bool> cancel{false};
    TrainObserver obs;
    obs.cancel = &cancel;
    int calls = 0;
    obs.onEpoch = [&](const EpochRecord& r) {
        ++calls;
        EXPECT_GT(r.step, 0.0);
        if (r.epoch == 2) cancel = true;
    };
    const NetworkModel m = fitNetwork(a, adamConfig(), x, y, obs);
    EXPECT_TRUE(m.training.cancelled);
    EXPECT_EQ(m.training.epochs, 2);
    EXPECT_EQ(calls, 3);  // epochs 0, 1, 2

    // A learning rate that cannot improve validation stops after `patience` epochs.
    const NetworkModel s = fitNetwork(a, adamConfig({{"patience", 3}, {"learning_rate", 1e-12},
                                                     {"schedule", "constant"}, {"patience_lr_fraction", 1}}), x, y);
    EXPECT_EQ(s.training.stopReason, "validation stop");
    EXPECT_LT(s.training.epochs, 10);
}

}  // namespace test_nn_training
