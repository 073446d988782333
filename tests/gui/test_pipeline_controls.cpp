// The pipeline bar and the preset estimates of the panels (panels/pipeline_controls.h) in a bare
// ImGui context: the Run button asks for the chosen preset, Stop for a cancel, and the estimates use
// the last render's speed and the last dataset's records per ray.
#include "panels/pipeline_controls.h"
#include "panels/project_io.h"
#include "tests/gui/imgui_fixture.h"

namespace rrf::test::test_pipeline_controls {

using namespace rrf::panels;

namespace {
const std::string kCornell = RRF_SOURCE_DIR "/projects/cornell-box/project.json";
}  // namespace

using PipelineControls = ImGuiFixture;

TEST_F(PipelineControls, RunButtonRequestsTheChosenPresetAndStopCancels) {
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, kCornell, error)) << error;
    s.pipeline.preset = "paper";
    // The bar alone at (0, 0): its first widget is the Run button.
    auto click = [&] {
        mouse(10, 8, false);
        frame([&] { drawPipelineBar(s); });
        mouse(10, 8, true);
        frame([&] { drawPipelineBar(s); });
        mouse(10, 8, false);
        frame([&] { drawPipelineBar(s); });
    };
    click();
    ASSERT_EQ(s.requests.size(), 1u);
    EXPECT_EQ(s.requests[0].command, Command::RunPipeline);
    EXPECT_EQ(s.requests[0].path, "paper");

    s.requests.clear();
    s.pipeline.running = true;  // the same place now holds "Stop pipeline"
    s.pipeline.stageIndex = 2;
    s.pipeline.fraction = 0.5;
    s.pipeline.etaSeconds = 30;
    click();
    ASSERT_EQ(s.requests.size(), 1u);
    EXPECT_EQ(s.requests[0].command, Command::CancelPipeline);
}

TEST_F(PipelineControls, RunButtonIsDisabledWithoutAProject) {
    WorkbenchState s;
    mouse(10, 8, false);
    frame([&] { drawPipelineBar(s); });
    mouse(10, 8, true);
    frame([&] { drawPipelineBar(s); });
    mouse(10, 8, false);
    frame([&] { drawPipelineBar(s); });
    EXPECT_TRUE(s.requests.empty());
}

TEST_F(PipelineControls, EstimatesUseTheLastRenderAndTheLastDataset) {
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, kCornell, error)) << error;
    EXPECT_FALSE(pathRateOf(s).measured) << "no render yet: the reference rate";
    s.render.samplesPerSecond = 2.5e6;
    EXPECT_TRUE(pathRateOf(s).measured);
    EXPECT_DOUBLE_EQ(pathRateOf(s).samplesPerSecond, 2.5e6);
    EXPECT_DOUBLE_EQ(recordsPerRayOf(s), 1.0) << "no dataset: the upper bound";
    // A 2x2x2 x 10 dataset that made 60 records: 0.75 records per ray.
    SamplingSettings made;
    made.nx = made.ny = made.nz = 2;
    made.directions = 10;
    s.dataset.madeWith = made;
    s.dataset.generator.records = 60;
    EXPECT_DOUBLE_EQ(recordsPerRayOf(s), 0.75);
    SamplingSettings next = made;
    next.nx = 4;
    next.spp = 10;
    next.maxSpp = 10;
    // 4·2·2 cells × 10 directions × 0.75 = 120 records × 10 paths at 2.5 M samples/s.
    EXPECT_DOUBLE_EQ(dataEstimate(s, next).low, 120.0 * 10 / 2.5e6);
    // The quick preset's stages are all estimated, the pipeline's in order render, generate, train, evaluate.
    const std::vector<StageEstimate> stages = pipelineEstimates(s, findPreset("quick"));
    ASSERT_EQ(stages.size(), 4u);
    for (const StageEstimate& e : stages) EXPECT_GT(e.high, 0.0);
    EXPECT_NE(stages[2].basis.find("epochs"), std::string::npos) << stages[2].basis;
}

}  // namespace rrf::test::test_pipeline_controls
