// The one training orchestration (core/nn/training_run.h) used by rrf train, the workbench and the
// sweeps: the same networks as trainObjects, per-network curves in a fixed order, progress and counts.
#include <gtest/gtest.h>

#include <filesystem>

#include <unistd.h>

#include "core/nn/model_set.h"
#include "core/nn/network_settings_json.h"
#include "core/nn/trainer_config_json.h"
#include "core/nn/training_run.h"
#include "core/util/json_reader.h"
#include "tests/synthetic_samples.h"
#include "tests/training_builders.h"

namespace test_training_run {

using namespace rrf;

TEST(TrainingRun, SameNetworksAsTrainObjectsWithOrderedCurves) {
    const std::vector<ObjectSamples> objs = {syntheticObject(2, 120), syntheticObject(0, 80), syntheticObject(1, 0)};
    ObjectTrainingOptions o = test::plainTraining();
    o.hidden = {5};
    o.targets = TargetMode::Separate;
    o.trainer = trainerConfigFromJson({{"type", "levenberg_marquardt"}, {"max_epochs", 4}});
    TrainingProgress progress;
    const TrainingRun run = trainNetworks(objs, o, {}, &progress);
    const std::vector<ObjectModel> direct = trainObjects(objs, o);
    ASSERT_EQ(run.models.size(), direct.size());
    for (size_t i = 0; i < direct.size(); ++i) {
        EXPECT_EQ(run.models[i].skipped, direct[i].skipped);
        if (direct[i].skipped) continue;
        EXPECT_TRUE(run.models[i].model.leaves[0].params == direct[i].model.leaves[0].params) << "network " << i << " differs";
    }
    EXPECT_EQ(run.networks, 4);
    EXPECT_EQ(run.skipped, 2) << "object 1 has no samples: both of its targets are skipped";
    ASSERT_EQ(run.curves.size(), 4u);
    EXPECT_EQ(run.curves[0].objectId, 0);
    EXPECT_EQ(run.curves[0].target, "direct");
    EXPECT_EQ(run.curves[1].target, "indirect");
    EXPECT_EQ(run.curves[2].objectId, 2);
    EXPECT_EQ(run.curves[2].object, "object2");
    for (const NetworkCurve& c : run.curves) {
        ASSERT_FALSE(c.epochs.empty());
        for (size_t e = 0; e < c.epochs.size(); ++e) EXPECT_EQ(c.epochs[e].epoch, int(e)) << "epoch 0 is the initial loss";
    }
    EXPECT_DOUBLE_EQ(progress.epochBudget.load(), 3.0 * 2 * 4);
    EXPECT_GT(progress.fraction(), 0.0);
    EXPECT_LE(progress.fraction(), 1.0);
    EXPECT_FALSE(run.cancelled);
    EXPECT_GT(run.seconds, 0.0);
}

TEST(TrainingRun, CancelledBeforeStartTrainsNothing) {
    const std::vector<ObjectSamples> objs = {syntheticObject(0, 50)};
    ObjectTrainingOptions o = test::plainTraining();
    o.hidden = {3};
    std::atomic<bool> cancel{true};
    ObjectTrainingObserver observer;
    observer.cancel = &cancel;
    const TrainingRun run = trainNetworks(objs, o, observer);
    EXPECT_TRUE(run.cancelled);
    EXPECT_EQ(run.networks, 0);
    EXPECT_TRUE(run.curves.empty());
}

TEST(TrainingRun, SavedModelSetRecordsWhereTheRunCameFrom) {
    ObjectTrainingOptions o = test::plainTraining();
    o.hidden = {3};
    o.trainer = trainerConfigFromJson({{"type", "levenberg_marquardt"}, {"max_epochs", 2}});
    const TrainingRun run = trainNetworks({syntheticObject(0, 60)}, o);
    NetworkSettings settings;
    settings.options = o.network();
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("rrf_training_run_" + std::to_string(::getpid()));
    std::vector<std::string> layout;
    for (int i = 0; i < 14; ++i) layout.push_back("in" + std::to_string(i));
    saveTrainingRun(dir.string(), run, o, 0x1234, layout, {"data/dataset.rrfd", "project.json"});
    const ModelSet set = loadModelSet(dir.string(), 0x1234);
    EXPECT_EQ(set.inputLayout, layout);
    const nlohmann::json index = readJsonFile((dir / "models.json").string());
    EXPECT_EQ(index.at("dataset"), "data/dataset.rrfd");
    EXPECT_EQ(index.at("project"), "project.json");
    EXPECT_EQ(index.at("network"), toJson(settings));
    EXPECT_EQ(index.at("trainer"), toJson(o.trainer));
    EXPECT_EQ(index.at("seconds").get<double>(), run.seconds);
    EXPECT_EQ(index.at("cancelled"), false);
    std::filesystem::remove_all(dir);
}

}  // namespace test_training_run
