// The stages of core/pipeline as the front ends call them: the whole pipeline writes every stage's
// files and times each stage; the training stage records what it trained (records, networks, the
// dataset) and reads its models back; a cancelled generation leaves an older dataset whole; a
// training share trains only its objects and only the saving process writes; a cancelled training
// is recorded as stopped.
#include <atomic>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>

#include <gtest/gtest.h>

#include "core/data/dataset_file.h"
#include "core/pipeline/experiment.h"
#include "core/pipeline/generate_stage.h"
#include "core/pipeline/pipeline.h"
#include "core/pipeline/train_stage.h"
#include "tests/project_builders.h"
#include "tests/test_dirs.h"
#include "tests/training_builders.h"

namespace test_pipeline_stages {

using namespace rrf;
using rrf::test::contains;
using rrf::test::freshTestDir;

namespace {
namespace fs = std::filesystem;

/// A few hundred records of the Cornell box: enough for a network per object in a second.
SamplingSettings tinySampling() {
    SamplingSettings s;
    s.nx = s.ny = s.nz = 3;
    s.directions = 24;
    s.spp = 4;
    s.maxSpp = 4;
    return s;
}

ObjectTrainingOptions tinyTraining() {
    ObjectTrainingOptions o = test::plainTraining();
    o.hidden = {8};
    o.trainer.adam.maxEpochs = o.trainer.lm.maxEpochs = 4;
    return o;
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

/// A share that owns object 0 only and never saves (a rank other than 0).
class FirstObjectShare : public TrainingShare {
public:
    ObjectTrainingOptions mine(const std::vector<ObjectSamples>&, const ObjectTrainingOptions& options) override {
        ObjectTrainingOptions o = options;
        o.objects = {0};
        return o;
    }
    TrainingRun join(TrainingRun run, const ObjectTrainingOptions&) override {
        ++joins;
        return run;
    }
    bool saves() const override { return false; }
    int joins = 0;
};
}  // namespace

TEST(PipelineStages, RunPipelineWritesEveryStageAndTimesIt) {
    const fs::path dir = freshTestDir("pipeline_stages");
    const Project p = rrf::test::cornellProjectWith("pipeline_stages_project", "project.json", nlohmann::json::object());
    PipelineRequest r;
    r.sampling = tinySampling();
    r.training = tinyTraining();
    r.prediction = p.prediction;
    RenderSettings rs = p.render;
    rs.spp = 4;
    rs.width = rs.height = 16;
    r.groundTruth = renderOptionsFor(p.scene, rs, 4);
    r.heldOutLights = 2;
    r.referenceTarget.sppCap = 8;
    r.out = (dir / "out").string();
    r.projectFile = p.path;
    ReferenceStore store((dir / "references").string());
    std::mutex m;
    std::string notes;
    StageObserver observer;
    observer.message = [&](const std::string& line) {
        std::lock_guard<std::mutex> lock(m);
        notes += line + "\n";
    };
    std::vector<std::string> stagesRun;
    const StageRunner runner = [&](const std::string& label, const std::function<void(const StageObserver&)>& stage) {
        stagesRun.push_back(label);
        stage(observer);
    };
    const PipelineOutcome out = runPipeline(p, r, store, runner, observer);

    ASSERT_EQ(out.stageSeconds.size(), 4u);
    EXPECT_EQ(out.stageSeconds[0].first, "ground truth");
    EXPECT_EQ(out.stageSeconds[1].first, "generate");
    EXPECT_EQ(out.stageSeconds[2].first, "train");
    EXPECT_EQ(out.stageSeconds[3].first, "evaluate");
    for (const auto& s : out.stageSeconds) EXPECT_GT(s.second, 0.0) << s.first;
    // Every stage ran under the runner, the held-out references one each.
    EXPECT_EQ(stagesRun, (std::vector<std::string>{"ground truth", "generate", "train", "reference 1/2", "reference 2/2"}));
    for (const char* f : {"ground_truth/global.exr", "ground_truth/render.json", "ground_truth/variance_global.exr",
                          "dataset.rrfd", "models/models.json", "evaluation/evaluation.json", "held_out/held_out.json",
                          "held_out/light_1/evaluation.json"})
        EXPECT_TRUE(fs::exists(dir / "out" / f)) << f;
    ASSERT_EQ(out.atGroundTruth.size(), 1u);
    EXPECT_EQ(out.heldOut.size(), 2u);
    EXPECT_FALSE(out.cancelled);
    EXPECT_TRUE(contains(notes, "[3/4] train: ")) << notes;
    EXPECT_TRUE(contains(notes, "held-out lights: spread over 2 positions")) << notes;
    // The models were saved with where they came from.
    const std::string index = slurp(dir / "out" / "models" / "models.json");
    EXPECT_TRUE(contains(index, "dataset.rrfd")) << index;
}

TEST(PipelineStages, TrainFromDatasetRecordsWhatItTrainedAndReadsTheModelsBack) {
    const fs::path dir = freshTestDir("pipeline_stages");
    const Project p = rrf::test::cornellProjectWith("pipeline_stages_train", "project.json", nlohmann::json::object());
    const DataGenerator generator(p.scene, tinySampling());
    GenerateRequest g;
    g.datasetPath = (dir / "data" / "dataset.rrfd").string();
    const GenerateOutcome generated = generateStage(generator, g, {});
    ASSERT_TRUE(generated.written);

    const Dataset data(g.datasetPath, true, p.scene.contentHash());
    TrainRequest t;
    t.options = tinyTraining();
    t.sampling = tinySampling();
    t.sceneHash = p.scene.contentHash();
    t.modelsDir = (dir / "models").string();
    t.provenance = {g.datasetPath, p.path};
    t.readBack = true;
    std::atomic<int> epochs{0};
    StageObserver observer;
    observer.epoch = [&](int, const std::string&, const EpochRecord&) { ++epochs; };
    const TrainOutcome out = trainFromDataset(data, t, observer);

    ASSERT_GT(out.run.networks, 0);
    EXPECT_TRUE(out.saved);
    ASSERT_TRUE(out.models);
    EXPECT_TRUE(fs::exists(dir / "models" / "models.json"));
    EXPECT_GT(epochs.load(), 0);
    // The record is what was trained: every record of the file, every network, this dataset.
    EXPECT_EQ(out.record.records, int64_t(data.totalRecords()));
    EXPECT_EQ(out.records, int64_t(data.totalRecords()));
    EXPECT_EQ(out.record.networks, out.run.networks);
    EXPECT_EQ(out.record.plannedNetworks, out.run.networks);
    EXPECT_EQ(out.record.curves.size(), out.run.curves.size());
    EXPECT_EQ(out.record.dataset, g.datasetPath);
    EXPECT_EQ(out.record.modelsDir, t.modelsDir);
    EXPECT_FALSE(out.record.stopped);
    ASSERT_TRUE(out.record.sampling.has_value());
    EXPECT_EQ(out.record.sampling->nx, 3);
}

TEST(PipelineStages, CancelledGenerationLeavesTheOldDatasetWhole) {
    const fs::path dir = freshTestDir("pipeline_stages");
    const Project p = rrf::test::cornellProjectWith("pipeline_stages_cancel", "project.json", nlohmann::json::object());
    const fs::path file = dir / "dataset.rrfd";
    std::ofstream(file) << "the old dataset";
    const DataGenerator generator(p.scene, tinySampling());
    GenerateRequest g;
    g.datasetPath = file.string();
    std::atomic<bool> cancel{true};
    StageObserver observer;
    observer.cancel = &cancel;
    const GenerateOutcome out = generateStage(generator, g, observer);
    EXPECT_TRUE(out.data.cancelled);
    EXPECT_FALSE(out.written);
    EXPECT_EQ(slurp(file), "the old dataset");
}

TEST(PipelineStages, ShareTrainsOnlyItsObjectsAndOnlyTheSaverWrites) {
    const fs::path dir = freshTestDir("pipeline_stages");
    const Project p = rrf::test::cornellProjectWith("pipeline_stages_share", "project.json", nlohmann::json::object());
    const DataGenerator generator(p.scene, tinySampling());
    const GenerateOutcome generated = generateStage(generator, {}, {});
    EXPECT_FALSE(generated.written);  // no path: kept in memory
    const std::vector<ObjectSamples> samples = samplesFromGenerated(generated.data, p.scene, generator.layout());
    FirstObjectShare share;
    TrainRequest t;
    t.options = tinyTraining();
    t.sceneHash = p.scene.contentHash();
    t.modelsDir = (dir / "models").string();
    t.share = &share;
    const TrainOutcome out = trainStage(samples, t, {});
    EXPECT_EQ(share.joins, 1);
    EXPECT_GT(out.run.networks, 0);
    for (const ObjectModel& m : out.run.models) {
        if (!m.skipped) {
            EXPECT_EQ(m.objectId, 0);
        }
    }
    EXPECT_FALSE(out.saved);
    EXPECT_FALSE(fs::exists(dir / "models"));
}

TEST(PipelineStages, CancelledTrainingIsRecordedAsStopped) {
    const Project p = rrf::test::cornellProjectWith("pipeline_stages_stop", "project.json", nlohmann::json::object());
    const DataGenerator generator(p.scene, tinySampling());
    const GenerateOutcome generated = generateStage(generator, {}, {});
    const std::vector<ObjectSamples> samples = samplesFromGenerated(generated.data, p.scene, generator.layout());
    std::atomic<bool> cancel{true};
    StageObserver observer;
    observer.cancel = &cancel;
    TrainRequest t;
    t.options = tinyTraining();
    const TrainOutcome out = trainStage(samples, t, observer);
    EXPECT_TRUE(out.run.cancelled);
    EXPECT_TRUE(out.record.stopped);
    EXPECT_LT(out.record.networks, out.record.plannedNetworks);
}

}  // namespace test_pipeline_stages
