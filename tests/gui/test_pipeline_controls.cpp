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

/// The bar alone at (0, 0), clicked where its first widget (Run / Stop pipeline) is.
class PipelineControls : public ImGuiFixture {
protected:
    void clickRunButton(WorkbenchState& s) {
        for (bool down : {false, true, false}) {
            mouse(10, 8, down);
            frame([&] { drawPipelineBar(pipelineBarView(s)); });
        }
    }
};

TEST_F(PipelineControls, RunButtonRequestsTheChosenPresetAndStopCancels) {
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, kCornell, error)) << error;
    s.pipeline.preset = "paper";
    clickRunButton(s);
    ASSERT_EQ(s.requests.size(), 1u);
    EXPECT_EQ(s.requests[0].command, Command::RunPipeline);
    EXPECT_EQ(s.requests[0].path, "paper");

    s.requests.clear();
    s.pipeline.running = true;  // the same place now holds "Stop pipeline"
    s.pipeline.stageIndex = 2;
    s.pipeline.fraction = 0.5;
    s.pipeline.etaSeconds = 30;
    clickRunButton(s);
    ASSERT_EQ(s.requests.size(), 1u);
    EXPECT_EQ(s.requests[0].command, Command::CancelPipeline);
}

TEST_F(PipelineControls, DefaultRunsTheProjectSettingsAndSaysWhatToExpect) {
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, kCornell, error)) << error;
    // Nothing changed, as a new user starts it: the project's settings run (not a smoke-test preset).
    EXPECT_EQ(s.pipeline.preset, "");
    EXPECT_EQ(pipelineChoiceLabel(s.pipeline.preset), "project settings");
    clickRunButton(s);
    ASSERT_EQ(s.requests.size(), 1u);
    EXPECT_EQ(s.requests[0].command, Command::RunPipeline);
    EXPECT_EQ(s.requests[0].path, "");
    // The bundled Cornell box's settings are the default preset's, so its figure is what to expect.
    EXPECT_EQ(pipelineExpectation(s.project, "", true), findPreset("default")->expectationShort);
    EXPECT_NE(pipelineExpectation(s.project, "quick", true).find("smoke test"), std::string::npos);
    EXPECT_NE(pipelineExpectation(s.project, "quick", false).find("not a result"), std::string::npos);
    // An edited setting is custom: no preset's figure is claimed for it.
    s.project.sampling = s.project.samplingOrDefault();
    s.project.sampling->directions = 299;
    EXPECT_EQ(pipelineExpectation(s.project, "", true), "custom settings");
    EXPECT_NE(pipelineExpectation(s.project, "", false).find("no preset's figures apply"), std::string::npos);
}

TEST_F(PipelineControls, RunIsRefusedAtTheButtonWhenTheDataCannotFit) {
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, kCornell, error)) << error;
    s.availableMemory = uint64_t(64) << 20;  // 64 MiB
    SamplingSettings huge = s.project.samplingOrDefault();
    huge.nx = huge.ny = huge.nz = 1000;
    const std::string why = generateRefusal(estimateInputs(s), huge);
    EXPECT_NE(why.find("1000000000 cells"), std::string::npos) << why;
    EXPECT_NE(why.find("64 MiB"), std::string::npos) << why;
    EXPECT_EQ(generateRefusal(estimateInputs(s), s.project.samplingOrDefault()), "") << "the default's 8^3 x 300 records fit in 64 MiB";
    s.project.sampling = huge;
    clickRunButton(s);
    EXPECT_TRUE(s.requests.empty()) << "Run pipeline is disabled while the data cannot fit";
}

TEST_F(PipelineControls, RunButtonIsDisabledWithoutAProject) {
    WorkbenchState s;
    clickRunButton(s);
    EXPECT_TRUE(s.requests.empty());
}

TEST_F(PipelineControls, EstimatesUseTheLastRenderAndTheLastDataset) {
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, kCornell, error)) << error;
    EXPECT_FALSE(pathRateOf(s.render).measured) << "no render yet: the reference rate";
    s.render.samplesPerSecond = 2.5e6;
    EXPECT_TRUE(pathRateOf(s.render).measured);
    EXPECT_DOUBLE_EQ(pathRateOf(s.render).samplesPerSecond, 2.5e6);
    EXPECT_DOUBLE_EQ(recordsPerRayOf(s.dataset), 1.0) << "no dataset: the upper bound";
    // A 2x2x2 x 10 dataset that made 60 records: 0.75 records per ray.
    SamplingSettings made;
    made.nx = made.ny = made.nz = 2;
    made.directions = 10;
    s.dataset.madeWith = made;
    s.dataset.generator.records = 60;
    EXPECT_DOUBLE_EQ(recordsPerRayOf(s.dataset), 0.75);
    SamplingSettings next = made;
    next.nx = 4;
    next.spp = 10;
    next.maxSpp = 10;
    // 4·2·2 cells × 10 directions × 0.75 = 120 records × 10 paths at 2.5 M samples/s.
    EXPECT_DOUBLE_EQ(dataEstimate(estimateInputs(s), next).low, 120.0 * 10 / 2.5e6);
    // The quick preset's stages are all estimated, the pipeline's in order render, generate, train, evaluate.
    const std::vector<StageEstimate> stages = pipelineEstimates(estimateInputs(s), findPreset("quick"));
    ASSERT_EQ(stages.size(), 4u);
    for (const StageEstimate& e : stages) EXPECT_GT(e.high, 0.0);
    EXPECT_NE(stages[2].basis.find("epochs"), std::string::npos) << stages[2].basis;
}

}  // namespace rrf::test::test_pipeline_controls
