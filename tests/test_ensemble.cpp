// Ensembles merged into one network (core/nn/ensemble.h): the merged network is exactly the mean of
// its members for any input, the ensemble trainer trains exactly the members it documents, and the
// setting reaches training through the project, the progress budget and the refusals.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>

#include "core/nn/encoding_settings_json.h"
#include "core/nn/network_settings_json.h"
#include "core/nn/trainer_config_json.h"
#include "core/pipeline/sweep.h"
#include "core/pipeline/sweep_values.h"
#include "core/nn/ensemble.h"
#include "core/nn/encoding_presets.h"
#include "core/nn/model.h"
#include "core/nn/network_settings.h"
#include "core/nn/training_run.h"
#include "core/util/error.h"
#include "core/util/rng.h"
#include "tests/synthetic_samples.h"
#include "tests/training_builders.h"

namespace test_ensemble {

using namespace rrf;

/// Raw network outputs (outputs × N) of `params` on normalised inputs `x`, in double.
MatX<double> forward(const MlpArch& arch, const VecX<double>& params, const MatX<double>& x) {
    std::vector<MatX<double>> acts;
    mlpForward<double>(arch, params.data(), x, acts);
    return acts.back();
}

/// `n` columns of `rows` uniform numbers in [-1, 1).
MatX<double> randomInputs(int rows, int n, uint64_t seed) {
    MatX<double> x(rows, n);
    Rng rng(seed, 7);
    for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = 2 * rng.uniformDouble() - 1;
    return x;
}

/// A smooth 2-input function with an edge, the truth the learning test measures against.
double truth(double a, double b) { return 0.6 * std::sin(2.5 * a) * std::cos(1.5 * b) + 0.3 * std::tanh(4 * (a - b)); }

/// Training data for one 2-input, 1-output network: `n` records of truth() plus Gaussian-like noise
/// of standard deviation `noise`, split 70/15/15 in the order drawn (already normalised: inputs and
/// targets lie in [-1, 1]).
TrainingData noisyData(int n, double noise, uint64_t seed) {
    const MatX<double> x = randomInputs(2, n, seed);
    MatX<float> y(1, n);
    Rng rng(seed, 9);
    for (int i = 0; i < n; ++i) {
        // Sum of three uniforms: mean 0, variance 1/4 per unit of half-width; scaled to `noise`.
        const double z = (rng.uniformDouble() + rng.uniformDouble() + rng.uniformDouble() - 1.5) * 2.0;
        y(0, i) = float(truth(x(0, i), x(1, i)) + noise * z);
    }
    const MatX<float> xf = x.cast<float>();
    const int nt = n * 70 / 100, nv = n * 15 / 100;
    TrainingData d;
    d.xTrain = xf.leftCols(nt);
    d.yTrain = y.leftCols(nt);
    d.xValidation = xf.middleCols(nt, nv);
    d.yValidation = y.middleCols(nt, nv);
    d.xTest = xf.rightCols(n - nt - nv);
    d.yTest = y.rightCols(n - nt - nv);
    return d;
}

/// A 2-input, 1-output network with two tanh layers of `width`.
MlpArch twoLayers(int width) {
    MlpArch arch;
    arch.inputs = 2;
    arch.hidden = {width, width};
    arch.outputs = 1;
    return arch;
}

TrainerConfig adam(int epochs) {
    return trainerConfigFromJson({{"type", "adam"}, {"max_epochs", epochs}, {"learning_rate", 1e-2},
                                    {"batch_size", 64}, {"error_goal", 0}, {"patience", 0}});
}

TEST(Ensemble, MergedNetworkPredictsTheMeanOfItsMembers) {
    for (const Activation act : {Activation::Tanh, Activation::Relu})
        for (const std::vector<int>& hidden :
             {std::vector<int>{}, std::vector<int>{6}, std::vector<int>{7, 4}, std::vector<int>{5, 3, 4}}) {
            MlpArch member;
            member.inputs = 5;
            member.hidden = hidden;
            member.outputs = 3;
            member.activation = act;
            std::vector<VecX<double>> params;
            for (int m = 0; m < 3; ++m) {
                VecX<double> p = initialParams(member, 11, uint64_t(m));
                p.array() += 0.3 * randomInputs(int(p.size()), 1, 40 + uint64_t(m)).array();  // biases non-zero too
                params.push_back(p);
            }
            const MatX<double> x = randomInputs(5, 200, 3);
            MatX<double> mean = MatX<double>::Zero(3, 200);
            for (const VecX<double>& p : params) mean += forward(member, p, x) / 3.0;

            const MlpArch merged = ensembleArch(member, 3);
            for (size_t l = 0; l < hidden.size(); ++l) EXPECT_EQ(merged.hidden[l], 3 * hidden[l]);
            const VecX<double> w = mergeEnsemble(member, params);
            ASSERT_EQ(w.size(), merged.numParams());
            EXPECT_LE((forward(merged, w, x) - mean).cwiseAbs().maxCoeff(), 1e-12) << merged.describe();
            // One member merges into itself.
            EXPECT_TRUE(mergeEnsemble(member, {params[0]}) == params[0]);
        }
}

TEST(Ensemble, RefusesMembersOfAnotherShape) {
    MlpArch a;
    a.inputs = 4;
    a.hidden = {3};
    MlpArch b = a;
    b.hidden = {5};
    EXPECT_THROW(mergeEnsemble(a, {initialParams(a, 1), initialParams(b, 1)}), std::invalid_argument);
    EXPECT_THROW(mergeEnsemble(a, {}), std::invalid_argument);
    EXPECT_THROW(ensembleArch(a, 0), std::invalid_argument);
}

TEST(Ensemble, TrainsTheDocumentedMembersOnOneSplit) {
    const TrainingData d = noisyData(400, 0.05, 5);
    const MlpArch arch = twoLayers(6);
    const MinMaxScaler scaler = MinMaxScaler::identity(1);
    const TrainerConfig cfg = adam(15);
    const uint64_t stream = 3;

    // Members trained one by one as the header says: member 0 from the given weights with cfg,
    // member 1 from initialParams(s1, stream) with every trainer seed s1.
    VecX<double> p0 = initialParams(arch, cfg.seed(), stream);
    trainNetwork(arch, cfg, d, scaler, p0);
    const uint64_t s1 = ensembleMemberSeed(cfg.seed(), 1);
    EXPECT_NE(s1, cfg.seed());
    EXPECT_EQ(ensembleMemberSeed(cfg.seed(), 0), cfg.seed()) << "member 0 is the single network";
    TrainerConfig c1 = cfg;
    c1.adam.seed = c1.lm.seed = s1;
    VecX<double> p1 = initialParams(arch, s1, stream);
    trainNetwork(arch, c1, d, scaler, p1);

    MlpArch a = arch;
    VecX<double> w = initialParams(arch, cfg.seed(), stream);
    int epochsSeen[2] = {0, 0};
    TrainObserver obs;
    obs.onEpoch = [&](const EpochRecord& r) { epochsSeen[r.member] += 1; };
    const TrainResult r = trainEnsemble(a, cfg, d, scaler, w, 2, stream, obs);
    EXPECT_EQ(a, ensembleArch(arch, 2));
    EXPECT_TRUE(w == mergeEnsemble(arch, {p0, p1}));
    EXPECT_EQ(r.members, 2);
    EXPECT_EQ(r.memberEpochs, 30);
    EXPECT_EQ(epochsSeen[0], 16) << "epoch 0 and 15 epochs, marked member 0";
    EXPECT_EQ(epochsSeen[1], 16);
    ASSERT_FALSE(r.messages.empty());
    EXPECT_NE(r.messages.back().find("ensemble of 2"), std::string::npos) << r.messages.back();

    // One member: exactly the single network.
    MlpArch one = arch;
    VecX<double> single = initialParams(arch, cfg.seed(), stream);
    const TrainResult r1 = trainEnsemble(one, cfg, d, scaler, single, 1, stream);
    EXPECT_TRUE(single == p0);
    EXPECT_EQ(one, arch);
    EXPECT_EQ(r1.members, 1);
    EXPECT_EQ(r1.memberEpochs, 15);
}

TEST(Ensemble, CancelDuringALaterMemberKeepsTheFinishedOnesAndSaysSo) {
    const TrainingData d = noisyData(300, 0.05, 6);
    const MlpArch arch = twoLayers(4);
    const TrainerConfig cfg = adam(10);
    std::atomic<bool> cancel{false};
    std::vector<std::string> notes;
    TrainObserver obs;
    obs.cancel = &cancel;
    obs.onEpoch = [&](const EpochRecord& r) {
        if (r.member == 2 && r.epoch == 3) cancel = true;  // the third member is cut short
    };
    obs.onMessage = [&](const std::string& m) { notes.push_back(m); };
    MlpArch a = arch;
    VecX<double> w = initialParams(arch, cfg.seed(), 0);
    const TrainResult r = trainEnsemble(a, cfg, d, MinMaxScaler::identity(1), w, 4, 0, obs);
    EXPECT_EQ(r.members, 2) << "members 0 and 1 finished; 2 was cut short and is left out";
    EXPECT_EQ(a, ensembleArch(arch, 2));
    EXPECT_TRUE(r.cancelled);
    EXPECT_EQ(r.stopReason, "cancelled");
    bool said = false;
    for (const std::string& m : notes) said = said || m.find("2 of 4 ensemble members") != std::string::npos;
    EXPECT_TRUE(said) << "the log says how many members the kept network averages";
}

TEST(Ensemble, MeanOfNoisyFitsIsCloserToTheTruthThanItsMembers) {
    // Tiny networks fitted to noisy records land in different minima; their mean is closer to the
    // noise-free function than the members are on average (strictly: the members differ).
    const TrainingData d = noisyData(1500, 0.15, 21);
    const MlpArch arch = twoLayers(8);
    const MinMaxScaler scaler = MinMaxScaler::identity(1);
    const TrainerConfig cfg = adam(60);
    const MatX<double> x = randomInputs(2, 2000, 77);
    MatX<double> t(1, x.cols());
    for (Eigen::Index i = 0; i < x.cols(); ++i) t(0, i) = truth(x(0, i), x(1, i));
    auto rmse = [&](const MlpArch& a, const VecX<double>& w) {
        return std::sqrt((forward(a, w, x) - t).squaredNorm() / double(x.cols()));
    };

    double memberMean = 0;
    const int k = 4;
    for (int m = 0; m < k; ++m) {
        TrainerConfig c = cfg;
        c.adam.seed = ensembleMemberSeed(cfg.seed(), m);
        VecX<double> p = initialParams(arch, c.adam.seed, 0);
        trainNetwork(arch, c, d, scaler, p);
        memberMean += rmse(arch, p) / k;
    }
    MlpArch a = arch;
    VecX<double> w = initialParams(arch, cfg.seed(), 0);
    trainEnsemble(a, cfg, d, scaler, w, k, 0);
    const double ensemble = rmse(a, w);
    EXPECT_LT(ensemble, 0.97 * memberMean) << "ensemble " << ensemble << ", members on average " << memberMean;
}

TEST(Ensemble, ProjectSettingTrainsMergedNetworksWithTheirBudget) {
    const NetworkSettings s = networkSettingsFromJson(
        JsonReader(nlohmann::json{{"hidden", {4}}, {"ensemble", 3}}, "project.json", "/network"), NetworkSettings());
    EXPECT_EQ(s.options.ensemble, 3);
    EXPECT_EQ(toJson(s).at("ensemble"), 3);
    EXPECT_EQ(toJson(NetworkSettings()).at("ensemble"), 1) << "one network unless asked";

    ObjectTrainingOptions o(s.options, TrainerConfig::projectDefault());
    o.partition.maxLeaves = 1;
    o.trainer = trainerConfigFromJson({{"type", "adam"}, {"max_epochs", 5}, {"patience", 0}, {"error_goal", 0}});
    TrainingProgress progress;
    const TrainingRun run = trainNetworks({syntheticObject(0, 150), syntheticObject(1, 90)}, o, {}, &progress);
    ASSERT_EQ(run.models.size(), 2u);
    for (const ObjectModel& m : run.models) {
        ASSERT_FALSE(m.skipped);
        EXPECT_EQ(m.model.arch().hidden, std::vector<int>{12});
        EXPECT_EQ(m.model.leaves[0].training.members, 3);
    }
    EXPECT_DOUBLE_EQ(progress.epochBudget.load(), 2.0 * 3 * 5);
    EXPECT_DOUBLE_EQ(progress.fraction(), 1.0) << "every member's epochs are counted";
    for (const NetworkCurve& c : run.curves) EXPECT_EQ(c.epochs.size(), 6u) << "the curve is the first member's";
}

TEST(Ensemble, SweepsVaryTheMembers) {
    EXPECT_EQ(defaultSweepValues("ensemble"), (std::vector<std::string>{"1", "2", "4"}));
    SweepOptions o;
    o.what = "ensemble";
    o.values = {"1", "3"};
    o.training.hidden = {8};
    const std::vector<SweepPoint> points = sweepPoints(o);
    ASSERT_EQ(points.size(), 2u);
    EXPECT_EQ(points[0].training.ensemble, 1);
    EXPECT_EQ(points[1].training.ensemble, 3);
    EXPECT_EQ(points[1].training.hidden, std::vector<int>{8}) << "the layers are the training settings'";
    for (const char* bad : {"0", "17", "two", "2,2"}) {
        o.values = {bad};
        EXPECT_THROW(sweepPoints(o), SettingError) << bad;
    }
}

TEST(Ensemble, RefusalsNameTheSetting) {
    for (const nlohmann::json& bad : {nlohmann::json(0), nlohmann::json(kMaxEnsembleMembers + 1), nlohmann::json("two")}) {
        try {
            networkSettingsFromJson(JsonReader(nlohmann::json{{"ensemble", bad}}, "project.json", "/network"),
                                      NetworkSettings());
            ADD_FAILURE() << "accepted ensemble " << bad;
        } catch (const std::exception& e) {
            EXPECT_NE(std::string(e.what()).find("ensemble"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("project.json"), std::string::npos) << e.what();
        }
    }
    // A trainable encoding cannot be shared by the members of one merged network: sweeps (either
    // kind) and training refuse it, naming the setting. A project file may hold the pair (the panel
    // edits one setting at a time), as it may hold a hash grid under Levenberg–Marquardt.
    EXPECT_NO_THROW(networkSettingsFromJson(
        JsonReader(nlohmann::json{{"ensemble", 2}, {"encoding", encodingSettingsJson(encodingPresetSettings("hash_grid"))}}, "project.json", "/network"),
        NetworkSettings()));
    SweepOptions sweep;
    sweep.what = "ensemble";
    sweep.values = {"2"};
    sweep.training.encoding = encodingPresetSettings("hash_grid");
    EXPECT_THROW(sweepPoints(sweep), SettingError);
    SweepOptions encodings;
    encodings.what = "encoding";
    encodings.values = {"hash_grid"};
    encodings.training.trainer = TrainerConfig().withType(TrainerType::Adam);
    encodings.training.ensemble = 2;
    EXPECT_THROW(sweepPoints(encodings), SettingError);
    ObjectTrainingOptions o = test::plainTraining();
    o.hidden = {4};
    o.ensemble = 2;
    o.encoding = encodingPresetSettings("hash_grid");
    o.trainer = trainerConfigFromJson({{"type", "adam"}, {"max_epochs", 1}});
    try {
        trainObjects({syntheticObject(0, 40)}, o);
        ADD_FAILURE() << "an ensemble with a trainable encoding trained";
    } catch (const SettingError& e) {
        EXPECT_NE(std::string(e.what()).find("network.ensemble"), std::string::npos) << e.what();
    }
}

}  // namespace test_ensemble
