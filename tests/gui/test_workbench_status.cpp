// Honest status words and visible fallbacks (issue 14 items 1 and 8): a stopped training and a
// cancelled render are called what they are, a partial model set's unpredicted objects are drawn
// hatched magenta (never plain black), the coverage table says when it is stale, and a notice shows
// in the panel it concerns as well as in the Log.
#include <string>

#include <gtest/gtest.h>

#include "core/pipeline/run_recording.h"
#include "panels/panels.h"
#include "panels/project_io.h"
#include "panels/status_text.h"
#include "panels/view_model.h"
#include "tests/gui/imgui_fixture.h"

namespace rrf::test::test_workbench_status {

using namespace rrf::panels;

namespace {
const std::string kCornell = RRF_SOURCE_DIR "/projects/cornell-box/project.json";

ObjectNetworks networks(int id, std::initializer_list<const char*> targets) {
    ObjectNetworks n;
    n.objectId = id;
    for (const char* t : targets) n.byTarget[t] = PartitionedNetwork{};
    return n;
}
}  // namespace

TEST(StatusText, StoppedTrainingIsNamedWithItsEpochAndNetworks) {
    EXPECT_EQ(stoppedTrainingText(12, 2, 14), "stopped at epoch 12, 2 of 14 networks");
    EXPECT_EQ(stoppedTrainingText(3, 1, 0), "stopped at epoch 3, 1 network");
    TrainingInfo t;
    t.running = true;
    t.progress = 0.374;
    EXPECT_EQ(trainingProgressText(t), "37%");
    t.running = false;
    t.stopped = true;
    t.epoch = 12;
    t.networks = 2;
    t.plannedNetworks = 14;
    EXPECT_EQ(trainingProgressText(t), "stopped at epoch 12, 2 of 14 networks");
    t.stopped = false;
    t.networks = 14;
    EXPECT_EQ(trainingProgressText(t), "done, 14 networks");
}

TEST(StatusText, AStoppedTrainRunSaysSoInTheRunsTable) {
    rrf::Run run = beginRun({}, "train");
    TrainRecord r;
    r.modelsDir = "/p/runs/x/models";
    r.dataset = "/p/data/dataset.rrfd";
    r.curves = {LossCurve{0, "floor", "indirect", {{1, 1.0, 1.0, 0.0}, {7, 0.5, 0.6, 1.0}}}};
    r.networks = 2;
    r.plannedNetworks = 14;
    r.stopped = true;
    setTrainRun(run, "/p", r);
    EXPECT_TRUE(isStoppedTrainRun(run));
    EXPECT_EQ(trainRunStatusText(run), "stopped at epoch 7, 2 of 14 networks");
    r.stopped = false;
    r.networks = 14;
    setTrainRun(run, "/p", r);
    EXPECT_FALSE(isStoppedTrainRun(run));
    EXPECT_EQ(trainRunStatusText(run), "14 networks");
}

TEST(StatusText, CancelledRenderIsNotDone) {
    RenderProgress r;
    r.spp = 42;
    r.targetSpp = 64;
    r.running = true;
    EXPECT_EQ(renderProgressText(r), "42/64 spp");
    r.running = false;
    r.cancelled = true;
    EXPECT_EQ(renderProgressText(r), "cancelled at 42/64 spp");
    r.cancelled = false;
    r.spp = 64;
    EXPECT_EQ(renderProgressText(r), "64/64 spp done");
}

TEST(StatusText, CoverageIsStaleAfterACancelOrASettingsChange) {
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, kCornell, error)) << error;
    DatasetInfo& d = s.dataset;
    EXPECT_EQ(datasetStaleReason(d, s.project), "") << "no dataset: nothing to call stale";
    d.path = "/p/data/dataset.rrfd";
    d.madeWith = s.project.samplingOrDefault();
    d.sceneHash = s.project.scene.contentHash();
    EXPECT_EQ(datasetStaleReason(d, s.project), "");
    SamplingSettings changed = s.project.samplingOrDefault();
    changed.directions += 1;
    s.project.sampling = changed;
    EXPECT_NE(datasetStaleReason(d, s.project).find("sampling settings changed"), std::string::npos);
    s.project.sampling = *d.madeWith;
    d.sceneHash ^= 1;
    EXPECT_NE(datasetStaleReason(d, s.project).find("scene changed"), std::string::npos);
    d.sceneHash ^= 1;
    d.lastCancelled = true;
    EXPECT_NE(datasetStaleReason(d, s.project).find("cancelled"), std::string::npos);
}

TEST(PartialModels, ObjectsWithoutTheNetworksThePredictionNeedsAreListed) {
    // Ids in view: 0, 1, 2, 3 (and background -1). Exact direct light needs an indirect (or a
    // global / joint) network; learned direct light also a direct one.
    const std::vector<int> ids = {-1, 0, 1, 1, 2, 3, 3, -1};
    ModelSet models;
    models.objects = {networks(0, {"indirect"}), networks(1, {"direct"}), networks(3, {"global"})};
    PredictionSettings exact;
    exact.direct = PredictionSettings::Direct::Exact;
    EXPECT_EQ(objectsWithoutNetwork(ids, models, exact), (std::vector<int>{1, 2}));
    PredictionSettings learned;
    learned.direct = PredictionSettings::Direct::Network;
    EXPECT_EQ(objectsWithoutNetwork(ids, models, learned), (std::vector<int>{0, 1, 2}));
}

TEST(PartialModels, UnpredictedPixelsAreHatchedMagentaNotBlack) {
    // A 4x2 image, all black (what a missing network predicts); object 5 has no network.
    const std::vector<int> ids = {5, 5, 5, 5, 7, 7, 5, -1};
    std::vector<uint8_t> rgba(4 * ids.size(), 0);
    hatchWithoutNetwork(ids, {5}, 4, rgba);
    auto magenta = [&](size_t i) { return rgba[4 * i] == 255 && rgba[4 * i + 1] == 0 && rgba[4 * i + 2] == 255; };
    // Stripes: (x + y) mod 4 < 2 is magenta. Row 0: x = 0, 1 magenta, 2, 3 not; row 1: x = 2 → 3 mod 4.
    EXPECT_TRUE(magenta(0));
    EXPECT_TRUE(magenta(1));
    EXPECT_FALSE(magenta(2));
    EXPECT_FALSE(magenta(3));
    EXPECT_FALSE(magenta(4)) << "object 7 has a network";
    EXPECT_FALSE(magenta(6)) << "(2, 1): between stripes";
    EXPECT_FALSE(magenta(7)) << "background";
    size_t hatched = 0;
    for (size_t i = 0; i < ids.size(); ++i) hatched += magenta(i);
    EXPECT_EQ(hatched, 2u);
}

using StatusPanelTest = ImGuiFixture;

TEST_F(StatusPanelTest, ThePartialModelsAreOfferedNotShown) {
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, kCornell, error)) << error;
    s.project.runs.push_back(beginRun({}, "train"));
    s.training.stopped = true;
    s.training.epoch = 4;
    s.training.networks = 2;
    s.training.plannedNetworks = 14;
    s.training.partialRun = 0;
    s.training.modelsDir = "/p/runs/complete/models";
    // The panel's rows at (0, 0): toolbar, then the stopped line with its button at its right end.
    // Find the button by clicking along the line until a request appears.
    frame([&] { drawTrainingPanel(trainingPanelView(s)); });  // sizes (the font) are known from the first frame on
    ASSERT_TRUE(s.requests.empty());
    bool clicked = false;
    for (float x = 0; x < 1600 && !clicked; x += 8) {
        mouse(x, 1.5f * ImGui::GetFontSize() + 12, false);
        frame([&] { drawTrainingPanel(trainingPanelView(s)); });
        mouse(x, 1.5f * ImGui::GetFontSize() + 12, true);
        frame([&] { drawTrainingPanel(trainingPanelView(s)); });
        mouse(x, 1.5f * ImGui::GetFontSize() + 12, false);
        frame([&] { drawTrainingPanel(trainingPanelView(s)); });
        clicked = !s.requests.empty();
    }
    ASSERT_TRUE(clicked) << "the stopped line offers 'Use the partial models'";
    ASSERT_EQ(s.requests.size(), 1u);
    EXPECT_EQ(s.requests[0].command, Command::CompareRun);
    EXPECT_EQ(s.requests[0].index, 0);
}

TEST_F(StatusPanelTest, ANoticeShowsInItsPanelAndInTheLogUntilDismissed) {
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, kCornell, error)) << error;
    const size_t before = s.log.errorCount();
    s.notify(LogLevel::Error, "Training", "train: no dataset yet; generate one in the Sampling panel");
    EXPECT_EQ(s.log.errorCount(), before + 1) << "the Log keeps it too";
    ASSERT_TRUE(s.notice.has_value());
    // The notice's Dismiss button is the first widget under the Training toolbar: click along the
    // second row until the notice is gone (nothing else on that row changes the state).
    frame([&] { drawTrainingPanel(trainingPanelView(s)); });  // sizes (the font) are known from the first frame on
    ASSERT_TRUE(s.notice.has_value()) << "drawing alone does not dismiss";
    for (float x = 0; x < 200 && s.notice; x += 4) {
        const float y = ImGui::GetFrameHeightWithSpacing() + 0.5f * ImGui::GetFrameHeight();
        mouse(x, y, false);
        frame([&] { drawTrainingPanel(trainingPanelView(s)); });
        mouse(x, y, true);
        frame([&] { drawTrainingPanel(trainingPanelView(s)); });
        mouse(x, y, false);
        frame([&] { drawTrainingPanel(trainingPanelView(s)); });
    }
    EXPECT_FALSE(s.notice.has_value()) << "Dismiss removes the notice";
    EXPECT_TRUE(s.requests.empty()) << "dismissing asks for nothing";
}

}  // namespace rrf::test::test_workbench_status
