// The preset table (core/pipeline/presets.h) and the stage time estimates (core/pipeline/time_estimate.h).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "core/nn/network_settings.h"
#include "core/pipeline/presets.h"
#include "core/project/project.h"
#include "core/project/project_file.h"
#include "project_builders.h"
#include "core/pipeline/time_estimate.h"
#include "tests/training_builders.h"

namespace test_presets {

using namespace rrf;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {
/// The Cornell box project with `sections` added (tests/project_builders.h), in this file's directory.
Project cornellWith(const std::string& name, const json& sections) {
    return rrf::test::cornellProjectWith("rrf_presets_tests", name, sections);
}

const PipelinePreset& preset(const char* name) {
    const PipelinePreset* p = findPreset(name);
    if (!p) throw std::runtime_error(std::string("no preset ") + name);
    return *p;
}
}  // namespace

TEST(Presets, TableListsQuickPaperDefaultBest) {
    EXPECT_EQ(presetNames(), "quick|paper|default|best");
    ASSERT_EQ(pipelinePresets().size(), 4u);
    EXPECT_EQ(findPreset("paper"), &pipelinePresets()[1]);
    EXPECT_EQ(findPreset("fast"), nullptr);
}

TEST(Presets, QuickShrinksSizesAndKeepsTheNetwork) {
    const Project p = cornellWith("quick.json", {{"network", {{"hidden", {8, 4}}}},
                                                 {"trainer", {{"type", "lm"}, {"max_epochs", 7}}},
                                                 {"sampling", {{"max_spp", 256}, {"seed", 9}}}});
    const SamplingSettings s = presetSampling(p, preset("quick"));
    EXPECT_EQ(s.nx, 5);
    EXPECT_EQ(s.nz, 5);
    EXPECT_EQ(s.directions, 150);
    EXPECT_EQ(s.spp, 16);
    EXPECT_EQ(s.maxSpp, 256) << "quick changes sizes only";
    EXPECT_EQ(s.seed, 9u);
    const ObjectTrainingOptions o = presetNetwork(p, preset("quick"));
    EXPECT_EQ(o.hidden, (std::vector<int>{8, 4}));
    EXPECT_EQ(o.trainer.type, TrainerType::LevenbergMarquardt);
    EXPECT_EQ(o.trainer.maxEpochs(), 50);
    EXPECT_EQ(preset("quick").evaluation.groundTruthSpp, 32);
    EXPECT_EQ(preset("quick").evaluation.width, 128);
    EXPECT_EQ(preset("quick").evaluation.referenceSppCap, 1024);
}

TEST(Presets, PaperIsTheSeedReportsSetting) {
    const Project p = cornellWith("paper.json", {{"network", {{"hidden", {8, 4}}, {"partition", {{"max_leaves", 4}}}}},
                                                 {"sampling", {{"grid", {3, 3, 3}}, {"seed", 5}}}});
    const SamplingSettings s = presetSampling(p, preset("paper"));
    EXPECT_EQ(s.nx, 15);
    EXPECT_EQ(s.ny, 15);
    EXPECT_EQ(s.directions, 1200);
    EXPECT_EQ(s.spp, 64);
    EXPECT_FALSE(s.adaptive()) << "a fixed path count per record";
    EXPECT_EQ(s.seed, 5u) << "the seed is the user's";
    const ObjectTrainingOptions o = presetNetwork(p, preset("paper"));
    EXPECT_EQ(o.hidden, (std::vector<int>{20, 10}));
    EXPECT_EQ(o.activation, Activation::Tanh);
    EXPECT_EQ(o.trainer.type, TrainerType::LevenbergMarquardt);
    EXPECT_EQ(o.trainer.maxEpochs(), 1000);
    EXPECT_EQ(o.partition.maxLeaves, 1) << "one network per object and target";
}

TEST(Presets, DefaultIsTheProjectDefaults) {
    const Project p = cornellWith("default.json", {{"network", {{"hidden", {8}}}},
                                                   {"trainer", {{"type", "lm"}}},
                                                   {"prediction", {{"direct_samples", 7}}},
                                                   {"sampling", {{"grid", {3, 3, 3}}, {"directions", 7}}}});
    const SamplingSettings s = presetSampling(p, preset("default"));
    EXPECT_EQ(s.nx, 8);
    EXPECT_EQ(s.directions, 300);
    EXPECT_EQ(s.maxSpp, 1024);
    const ObjectTrainingOptions o = presetNetwork(p, preset("default"));
    EXPECT_EQ(o.hidden, (std::vector<int>{32, 16}));
    EXPECT_EQ(o.trainer.type, TrainerType::Adam);
    EXPECT_EQ(o.trainer.adam.loss, AdamLoss::RelativeL2);
    EXPECT_EQ(o.trainer.maxEpochs(), 600);
    EXPECT_EQ(o.partition.maxLeaves, 16);
    EXPECT_EQ(presetPrediction(p, preset("default")).directSamples, 64);
}

TEST(Presets, BestIsTheMostAccurateSettingMeasured) {
    const Project p = cornellWith("best.json", {{"network", {{"hidden", {8}}}},
                                                {"trainer", {{"type", "lm"}}},
                                                {"prediction", {{"direct", "network"}, {"direct_samples", 7}, {"seed", 3}}},
                                                {"sampling", {{"grid", {3, 3, 3}}, {"directions", 7}, {"seed", 4}}}});
    // The README's "best preset" table: the values measured there.
    const SamplingSettings s = presetSampling(p, preset("best"));
    EXPECT_EQ(s.nx, 10);
    EXPECT_EQ(s.nz, 10);
    EXPECT_EQ(s.directions, 1200);
    EXPECT_EQ(s.spp, 64);
    EXPECT_EQ(s.maxSpp, 256);
    EXPECT_EQ(s.seed, 4u) << "the seed is the user's";
    const ObjectTrainingOptions o = presetNetwork(p, preset("best"));
    EXPECT_EQ(o.hidden, (std::vector<int>{32, 32, 32}));
    EXPECT_EQ(o.ensemble, 4) << "four networks per object, merged";
    EXPECT_EQ(o.activation, Activation::Tanh);
    EXPECT_EQ(o.trainer.type, TrainerType::Adam);
    EXPECT_EQ(o.trainer.adam.loss, AdamLoss::RelativeL2);
    EXPECT_TRUE(o.trainer.adam.debiasTargets);
    EXPECT_EQ(o.trainer.adam.errorGoal, 0.0);
    EXPECT_EQ(o.trainer.adam.patience, 0) << "no early stop";
    EXPECT_EQ(o.trainer.adam.learningRate, 3e-3);
    EXPECT_EQ(o.trainer.maxEpochs(), 400);
    EXPECT_EQ(o.partition.maxLeaves, 1);
    const PredictionSettings pr = presetPrediction(p, preset("best"));
    EXPECT_EQ(pr.directSamples, 256);
    EXPECT_EQ(pr.direct, PredictionSettings::Direct::Exact) << "exact direct light beside the networks";
    EXPECT_EQ(o.targets, TargetMode::Indirect) << "networks for indirect light only, though the project learned direct light";
    EXPECT_EQ(pr.seed, 3u) << "only the samples change";
}

TEST(Presets, AppliedPresetIsRecognisedAndOthersAreNot) {
    Project p = cornellWith("apply.json", json::object());
    // A project without sections runs the defaults: that is "default".
    EXPECT_EQ(matchingSamplingPreset(p), findPreset("default"));
    EXPECT_EQ(matchingNetworkPreset(p), findPreset("default"));
    applySamplingPreset(p, preset("paper"));
    EXPECT_EQ(matchingSamplingPreset(p), findPreset("paper"));
    EXPECT_EQ(matchingNetworkPreset(p), findPreset("default")) << "the halves are applied separately";
    applyNetworkPreset(p, preset("paper"));
    EXPECT_EQ(matchingNetworkPreset(p), findPreset("paper"));
    ASSERT_TRUE(p.trainer.has_value());
    EXPECT_EQ(p.trainer->type, TrainerType::LevenbergMarquardt);
    p.sampling->directions = 1199;
    EXPECT_EQ(matchingSamplingPreset(p), nullptr) << "an edited setting is no preset";
    applyNetworkPreset(p, preset("best"));
    EXPECT_EQ(p.prediction.directSamples, 256) << "the network half carries the prediction's settings";
    EXPECT_EQ(matchingNetworkPreset(p), findPreset("best"));
    p.prediction.directSamples = 64;
    EXPECT_EQ(matchingNetworkPreset(p), nullptr) << "best's networks with the default's direct light are no preset";
}

TEST(Presets, BothHalvesMatchingNameThePresetWhoseExpectationApplies) {
    Project p = cornellWith("matching.json", json::object());
    EXPECT_EQ(matchingPreset(p), findPreset("default")) << "a project without sections runs the default preset's settings";
    applySamplingPreset(p, preset("best"));
    EXPECT_EQ(matchingPreset(p), nullptr) << "best's data with the default's networks is no preset";
    applyNetworkPreset(p, preset("best"));
    EXPECT_EQ(matchingPreset(p), findPreset("best"));
    // The glossy box's own sections (a reflected input on one object) are custom settings.
    const Project glossy = loadProjectOrScene(RRF_SOURCE_DIR "/projects/cornell-glossy/project.json");
    EXPECT_EQ(matchingPreset(glossy), nullptr);
}

TEST(Presets, EveryPresetSaysWhatToExpectAndQuickThatItIsASmokeTest) {
    for (const PipelinePreset& p : pipelinePresets()) {
        EXPECT_GT(std::string(p.expectation).size(), 20u) << p.name;
        EXPECT_FALSE(std::string(p.expectationShort).empty()) << p.name;
    }
    EXPECT_NE(std::string(preset("quick").expectation).find("smoke test"), std::string::npos);
    EXPECT_NE(std::string(preset("quick").expectationShort).find("smoke test"), std::string::npos);
    EXPECT_EQ(std::string(preset("default").expectation).find("smoke test"), std::string::npos);
}

TEST(TimeEstimate, GenerateIsRecordsTimesPathsOverRate) {
    SamplingSettings s;
    s.nx = 2, s.ny = 3, s.nz = 4;
    s.directions = 10;
    s.spp = 4;
    s.maxSpp = 16;
    const PathRate rate = PathRate::of(1000, 2);
    const StageEstimate e = estimateGenerate(s, rate);
    EXPECT_DOUBLE_EQ(e.low, 240 * 4 / 1000.0);
    EXPECT_DOUBLE_EQ(e.high, 240 * 16 / 1000.0);
    EXPECT_DOUBLE_EQ(estimateGenerate(s, rate, 0.5).high, 120 * 16 / 1000.0) << "measured records per ray";
    // No measured rate: the reference machine's per-thread rate times the threads.
    EXPECT_DOUBLE_EQ(PathRate::of(0, 3).samplesPerSecond, 3 * kReferencePathRate);
    s.maxSpp = 4;
    EXPECT_DOUBLE_EQ(estimateGenerate(s, rate).high, estimateGenerate(s, rate).low) << "fixed paths: one figure";
}

TEST(TimeEstimate, LevenbergMarquardtCostsThreeNPSquaredPerEpoch) {
    ObjectTrainingOptions o = test::plainTraining();
    o.hidden = {5};
    o.targets = TargetMode::Indirect;
    o.trainer = TrainerConfig().withType(TrainerType::LevenbergMarquardt);
    o.trainer.lm.maxEpochs = 10;
    o.trainer.lm.maxEpochGflop = 0;
    // 3 inputs -> 5 -> 3: P = 4·5 + 6·3 = 38; 700 records over 7 objects: N = 100 per network.
    const double epoch = 3.0 * 100 * 38 * 38 / kLmFlopsPerThread;
    const StageEstimate e = estimateTraining(o, 700, 7, 3, 2);
    EXPECT_NEAR(e.low, 10 * epoch * 7 / 2, 1e-15);
    EXPECT_DOUBLE_EQ(e.high, e.low) << "no kd-tree";
    // The GFLOP bound caps N at floor(bound / (3 P²)): a bound of 50.5 records' flops leaves 50.
    o.trainer.lm.maxEpochGflop = 3.0 * 50.5 * 38 * 38 / 1e9;
    EXPECT_NEAR(estimateTraining(o, 700, 7, 3, 2).low, 10 * (3.0 * 50 * 38 * 38 / kLmFlopsPerThread) * 7 / 2, 1e-15);
    // Separate targets: two networks per object; 16 leaves at depth <= 8: up to 5 levels.
    o.targets = TargetMode::Separate;
    o.trainer.lm.maxEpochGflop = 0;
    o.partition.maxLeaves = 16;
    const StageEstimate t = estimateTraining(o, 700, 7, 3, 2);
    EXPECT_NEAR(t.low, 10 * epoch * 14 / 2, 1e-15);
    EXPECT_NEAR(t.high, 5 * t.low, 1e-15);
    // An ensemble of 3 trains every network's three members in turn.
    o.ensemble = 3;
    EXPECT_NEAR(estimateTraining(o, 700, 7, 3, 2).low, 3 * t.low, 1e-12);
    EXPECT_NE(estimateTraining(o, 700, 7, 3, 2).basis.find("3 members"), std::string::npos);
}

TEST(TimeEstimate, AdamCostsNPPerEpoch) {
    ObjectTrainingOptions o = test::plainTraining();
    o.hidden = {5};
    o.targets = TargetMode::Joint;  // 6 outputs: P = 4·5 + 6·6 = 56
    o.trainer = TrainerConfig().withType(TrainerType::Adam);
    o.trainer.adam.maxEpochs = 20;
    const StageEstimate e = estimateTraining(o, 900, 3, 3, 8);
    // 3 networks (one per object) on 8 threads: all in parallel.
    EXPECT_NEAR(e.low, 20 * (300.0 * 56 / kAdamWeightSamplesPerThread) * 3 / 3, 1e-15);
}

TEST(TimeEstimate, DurationsReadAsAPersonWouldSayThem) {
    EXPECT_EQ(durationText(0.3), "< 1 s");
    EXPECT_EQ(durationText(12.4), "12 s");
    EXPECT_EQ(durationText(150), "2.5 min");
    EXPECT_EQ(durationText(2 * 3600), "2.0 h");
    StageEstimate e;
    e.low = 30;
    e.high = 600;
    EXPECT_EQ(rangeText(e), "30 s to 10.0 min");
}

TEST(Presets, PipelineCommandRefusesAnUnknownPreset) {
    const auto r = rrf::test::runCli("pipeline " + std::string(RRF_SOURCE_DIR) +
                                     "/projects/cornell-box/project.json --preset fastest --out " +
                                     (fs::path(::testing::TempDir()) / "rrf_presets_unknown").string());
    EXPECT_NE(r.code, 0);
    EXPECT_NE(r.output.find("--preset"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("quick"), std::string::npos) << "the allowed names are listed: " << r.output;
    EXPECT_FALSE(fs::exists(fs::path(::testing::TempDir()) / "rrf_presets_unknown"));
}

}  // namespace test_presets
