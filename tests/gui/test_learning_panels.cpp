// The learning panels (Network, Training, Objects, Cost) in a bare ImGui context: edits change the
// project's network settings as expected, the loss plot maps known losses onto the log axis where
// they belong and its hover finds them, the Objects table sorts, nothing crashes without data, and
// network settings and training runs survive save -> reopen.
#include <cmath>
#include <filesystem>
#include <limits>

#include <unistd.h>

#include "core/project/runs_json.h"
#include "core/nn/network_settings_json.h"
#include "core/nn/trainer_config_json.h"
#include "panels/panels.h"
#include "panels/plot.h"
#include "panels/project_io.h"
#include "tests/gui/imgui_fixture.h"

namespace rrf::test::test_learning_panels {

namespace fs = std::filesystem;
using namespace rrf::panels;

namespace {
const std::string kCornell = RRF_SOURCE_DIR "/projects/cornell-box/project.json";
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void loadCornell(WorkbenchState& s) {
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, kCornell, error)) << error;
}

void drawLearningPanels(WorkbenchState& s) {
    ImGui::BeginChild("net", ImVec2(400, 500));
    drawNetworkPanel(networkPanelView(s));
    ImGui::EndChild();
    ImGui::BeginChild("train", ImVec2(900, 300));
    drawTrainingPanel(trainingPanelView(s));
    ImGui::EndChild();
    ImGui::BeginChild("objects", ImVec2(900, 200));
    drawObjectsPanel(objectsPanelView(s));
    ImGui::EndChild();
    ImGui::BeginChild("cost", ImVec2(900, 300));
    drawCostPanel(costPanelView(s));
    ImGui::EndChild();
}

LossCurve decadeCurve() {
    LossCurve c;
    c.objectId = 2;
    c.object = "floor";
    c.target = "global";
    // Train loss falls one decade per epoch: 1, 0.1, 0.01, 0.001; no validation set.
    for (int e = 0; e < 4; ++e) c.points.push_back({e, std::pow(10.0, -e), kNaN, 0.5 * e});
    return c;
}

ObjectErrorRow row(int id, const std::string& name, double rmse, uint64_t pixels) {
    ObjectErrorRow r;
    r.objectId = id;
    r.name = name;
    r.stats.rmse = rmse;
    r.stats.relativeRmse = rmse * 2;
    r.stats.pixels = pixels;
    r.samples = 100 * uint64_t(id + 1);
    return r;
}
}  // namespace

using LearningPanelTest = ImGuiFixture;

TEST_F(LearningPanelTest, NoCrashWithoutProjectOrData) {
    WorkbenchState s;
    for (int i = 0; i < 3; ++i) frame([&] { drawLearningPanels(s); });
    loadCornell(s);
    for (int i = 0; i < 3; ++i) frame([&] { drawLearningPanels(s); });
    EXPECT_TRUE(s.requests.empty()) << "idle frames must not ask for anything";
    EXPECT_FALSE(s.dirty) << "idle frames must not edit the project";
    EXPECT_FALSE(s.project.network.has_value()) << "drawing must not write default sections";
    EXPECT_FALSE(s.project.trainer.has_value()) << "drawing must not write default sections";
}

TEST_F(LearningPanelTest, NetworkEditsChangeTheProjectSettings) {
    WorkbenchState s;
    loadCornell(s);
    ASSERT_EQ(s.project.networkOrDefault().options.hidden, (std::vector<int>{32, 16}));
    ASSERT_TRUE(addHiddenLayer(networkPanelView(s)));
    EXPECT_TRUE(s.dirty);
    EXPECT_EQ(s.project.networkOrDefault().options.hidden, (std::vector<int>{32, 16, 16}));
    ASSERT_TRUE(resizeHiddenLayer(networkPanelView(s), 0, 24));
    ASSERT_TRUE(removeHiddenLayer(networkPanelView(s), 1));
    EXPECT_EQ(s.project.networkOrDefault().options.hidden, (std::vector<int>{24, 16}));
    EXPECT_FALSE(resizeHiddenLayer(networkPanelView(s), 5, 8)) << "no such layer";
    EXPECT_TRUE(resizeHiddenLayer(networkPanelView(s), 1, 100000)) << "sizes are clamped, not refused";
    EXPECT_EQ(s.project.networkOrDefault().options.hidden[1], 4096);
    ASSERT_TRUE(s.notice.has_value()) << "a clamp is said, not silent";
    EXPECT_EQ(s.notice->panel, "Network");
    EXPECT_NE(s.notice->text.find("1 ... 4096; 100000 was set to 4096"), std::string::npos) << s.notice->text;
    s.notice.reset();
    ASSERT_TRUE(resizeHiddenLayer(networkPanelView(s), 1, 0));
    EXPECT_EQ(s.project.networkOrDefault().options.hidden[1], 1);
    ASSERT_TRUE(s.notice.has_value());
    EXPECT_NE(s.notice->text.find("0 was set to 1"), std::string::npos) << s.notice->text;
    ASSERT_TRUE(removeHiddenLayer(networkPanelView(s), 1));
    EXPECT_FALSE(removeHiddenLayer(networkPanelView(s), 0)) << "a network keeps at least one hidden layer";

    EXPECT_EQ(s.project.networkOrDefault().options.ensemble, 1) << "one network unless asked";
    ASSERT_TRUE(setEnsemble(networkPanelView(s), 3));
    EXPECT_FALSE(setEnsemble(networkPanelView(s), 3)) << "no change, nothing stored";
    EXPECT_EQ(s.project.networkOrDefault().options.ensemble, 3);
    EXPECT_EQ(toJson(*s.project.network).at("ensemble"), 3);
    EXPECT_TRUE(setEnsemble(networkPanelView(s), 1000)) << "clamped, not refused";
    EXPECT_EQ(s.project.networkOrDefault().options.ensemble, kMaxEnsembleMembers);
    ASSERT_TRUE(setEnsemble(networkPanelView(s), 1));

    EXPECT_EQ(s.project.trainerOrDefault().type, TrainerType::Adam) << "the project default";
    ASSERT_TRUE(setTrainerType(networkPanelView(s), TrainerType::LevenbergMarquardt));
    EXPECT_FALSE(setTrainerType(networkPanelView(s), TrainerType::LevenbergMarquardt)) << "no change, nothing stored";
    ASSERT_TRUE(s.project.trainer.has_value()) << "switching the trainer stores the trainer section";
    EXPECT_EQ(toJson(*s.project.trainer)["type"], "levenberg_marquardt");
    ASSERT_TRUE(setTrainerType(networkPanelView(s), TrainerType::Adam));
    const NetworkSettings n = s.project.networkOrDefault();
    EXPECT_EQ(s.project.trainerOrDefault().type, TrainerType::Adam);
    EXPECT_EQ(toJson(*s.project.trainer)["type"], "adam");
    EXPECT_EQ(s.project.trainerOrDefault().adam.batchSize, AdamConfig().batchSize) << "Adam starts from its defaults";
    // The project default (exact direct light, networks for the indirect light) is kept by the edits.
    EXPECT_EQ(n.options.targets, TargetMode::Indirect) << "the project default is kept by the edits";

    // The panel draws the edited settings (Adam parameters, one layer) without asking for anything.
    for (int i = 0; i < 2; ++i) frame([&] { drawNetworkPanel(networkPanelView(s)); });
    EXPECT_TRUE(s.requests.empty());
    EXPECT_EQ(s.project.networkOrDefault().options.hidden, (std::vector<int>{24}));
}

TEST_F(LearningPanelTest, LossPlotPutsKnownLossesOnTheirDecades) {
    WorkbenchState s;
    loadCornell(s);
    s.training.curves.push_back(decadeCurve());
    s.trainingView.showValidation = false;
    frame([&] { drawTrainingPanel(trainingPanelView(s)); });
    const TrainingView& v = s.trainingView;
    ASSERT_LT(v.plotMinY, v.plotMaxY);
    EXPECT_DOUBLE_EQ(v.yLo, -3.0) << "0.001 starts the axis on its decade";
    EXPECT_DOUBLE_EQ(v.yHi, 0.0);
    // 1e-2 is one decade above the bottom of three: one third of the way up.
    const PlotAxis y = logAxis(1e-3, 1.0, v.plotMaxY, v.plotMinY);
    const float expected = v.plotMaxY - (v.plotMaxY - v.plotMinY) / 3.f;
    EXPECT_NEAR(y.toPixel(1e-2), expected, 1e-3);
    EXPECT_NEAR(y.toValue(expected), 1e-2, 1e-6) << "pixels are floats: a relative 1e-4 is their precision";
    EXPECT_NEAR(y.toPixel(1.0), v.plotMinY, 1e-3);
    EXPECT_TRUE(std::isnan(y.toPixel(0.0))) << "zero has no place on a log axis";

    // Hovering the point of epoch 2 (loss 0.01) reports that network and epoch.
    const PlotAxis x = linearAxis(0, 3, v.plotMinX, v.plotMaxX);
    mouse(x.toPixel(2), expected + 1.f, false);
    for (int i = 0; i < 3; ++i) frame([&] { drawTrainingPanel(trainingPanelView(s)); });
    EXPECT_EQ(s.trainingView.hoverCurve, 0);
    EXPECT_EQ(s.trainingView.hoverEpoch, 2);
    mouse(5, 5, false);
    frame([&] { drawTrainingPanel(trainingPanelView(s)); });
    EXPECT_EQ(s.trainingView.hoverCurve, -1);

    // A constant target's loss of 1e-30 must not squash the other curves into the top decades.
    s.training.curves.push_back(decadeCurve());
    s.training.curves.back().points.push_back({4, 1e-30, kNaN, 2.0});
    frame([&] { drawTrainingPanel(trainingPanelView(s)); });
    EXPECT_DOUBLE_EQ(s.trainingView.yHi, 0.0);
    EXPECT_DOUBLE_EQ(s.trainingView.yLo, -8.0) << "at most eight decades below the largest loss";

    s.trainingView.aggregate = true;
    for (int i = 0; i < 2; ++i) frame([&] { drawTrainingPanel(trainingPanelView(s)); });
    EXPECT_TRUE(s.requests.empty());
}

TEST(LossAggregate, StoppedNetworksKeepTheirLastValue) {
    LossCurve a, b;
    a.points = {{0, 1.0, 2.0, 0.1}, {1, 0.5, 1.0, 0.2}, {2, 0.25, 0.5, 0.3}};
    b.points = {{0, 3.0, kNaN, 0.1}, {1, 1.5, kNaN, 0.4}};  // stopped after epoch 1, no validation set
    const std::vector<LossPoint> m = aggregateLoss({a, b});
    ASSERT_EQ(m.size(), 3u);
    EXPECT_DOUBLE_EQ(m[1].train, 1.0);
    EXPECT_DOUBLE_EQ(m[2].train, (0.25 + 1.5) / 2) << "b contributes its last value";
    EXPECT_DOUBLE_EQ(m[2].validation, 0.5) << "NaN validation losses are left out";
    EXPECT_DOUBLE_EQ(m[1].seconds, 0.4);
    EXPECT_TRUE(aggregateLoss({}).empty());
}

TEST(PlotAxes, LogAxisSpansWholeDecades) {
    const PlotAxis a = logAxis(0.003, 42.0, 0.f, 100.f);
    EXPECT_DOUBLE_EQ(a.lo, -3.0);
    EXPECT_DOUBLE_EQ(a.hi, 2.0);
    EXPECT_NEAR(a.toPixel(1.0), 60.f, 1e-4);
    const PlotAxis d = logAxis(0.0, -1.0, 0.f, 1.f);  // nothing positive: a usable default
    EXPECT_LT(d.lo, d.hi);
    EXPECT_EQ(tickLabel(1e-4), "1e-4");
    EXPECT_EQ(tickLabel(10.0), "10");
}

// Issue 30 item 7: zoom about the cursor, pan by dragging, double-click fits the data again.
TEST(PlotAxes, WheelZoomsAboutTheCursorDragPansAndDoubleClickFits) {
    PlotAxis x = linearAxis(0, 10, 0.f, 100.f), y = logAxis(1e-3, 1.0, 100.f, 0.f);
    PlotView v;
    zoomPanPlot(v, x, y, ImVec2(25, 50), 0.f, ImVec2(0, 0), false);
    EXPECT_TRUE(v.autoFit) << "no input: the axes follow the data";
    EXPECT_DOUBLE_EQ(x.lo, 0.0);
    zoomPanPlot(v, x, y, ImVec2(25, 50), 1.f, ImVec2(0, 0), false);
    EXPECT_FALSE(v.autoFit);
    // One notch shows 80 % of each span about the point under the cursor (x 2.5, y 10^-1.5).
    EXPECT_NEAR(x.lo, 0.5, 1e-12);
    EXPECT_NEAR(x.hi, 8.5, 1e-12);
    EXPECT_NEAR(x.toValue(25.f), 2.5, 1e-6);
    EXPECT_NEAR(std::log10(y.toValue(50.f)), -1.5, 1e-6);
    EXPECT_NEAR(y.hi - y.lo, 2.4, 1e-12);
    // The next frame's fitted axes are replaced by the view's ranges.
    PlotAxis x2 = linearAxis(0, 10, 0.f, 100.f), y2 = logAxis(1e-3, 1.0, 100.f, 0.f);
    zoomPanPlot(v, x2, y2, ImVec2(25, 50), 0.f, ImVec2(0, 0), false);
    EXPECT_DOUBLE_EQ(x2.lo, x.lo);
    EXPECT_DOUBLE_EQ(y2.hi, y.hi);
    // Dragging 10 pixels right moves the data with the mouse: 10 px of an 8-unit, 100-px axis.
    zoomPanPlot(v, x2, y2, ImVec2(35, 50), 0.f, ImVec2(10, 0), false);
    EXPECT_NEAR(x2.lo, 0.5 - 0.8, 1e-12);
    EXPECT_NEAR(x2.toValue(35.f), 2.5, 1e-6) << "the point dragged stays under the mouse";
    PlotAxis x3 = linearAxis(0, 10, 0.f, 100.f), y3 = logAxis(1e-3, 1.0, 100.f, 0.f);
    zoomPanPlot(v, x3, y3, ImVec2(35, 50), 0.f, ImVec2(0, 0), true);
    EXPECT_TRUE(v.autoFit);
    EXPECT_DOUBLE_EQ(x3.lo, 0.0);
    EXPECT_DOUBLE_EQ(y3.lo, -3.0);
}

// A click on a legend entry hides that curve (and its range), a second click shows it again; the
// wheel over the loss plot zooms it.
TEST_F(LearningPanelTest, LegendClicksHideCurvesAndTheWheelZoomsTheLossPlot) {
    WorkbenchState s;
    loadCornell(s);
    s.training.curves.push_back(decadeCurve());  // 1 ... 1e-3
    LossCurve high = decadeCurve();
    high.object = "ceiling";
    for (LossPoint& p : high.points) p.train *= 100.0;  // 100 ... 0.1
    s.training.curves.push_back(high);
    s.trainingView.showValidation = false;
    for (int i = 0; i < 2; ++i) frame([&] { drawTrainingPanel(trainingPanelView(s)); });
    TrainingView& v = s.trainingView;
    EXPECT_DOUBLE_EQ(v.yHi, 2.0);
    // Find the ceiling's entry by clicking down the legend column (its rows' place depends on the font).
    for (float y = v.plotMinY; y < v.plotMinY + 300.f && v.hidden.empty(); y += 3.f) {
        mouse(v.plotMaxX + 60.f, y, true);
        frame([&] { drawTrainingPanel(trainingPanelView(s)); });
        mouse(v.plotMaxX + 60.f, y, false);
        frame([&] { drawTrainingPanel(trainingPanelView(s)); });
    }
    ASSERT_EQ(v.hidden.size(), 1u) << "a legend entry hides its curve";
    frame([&] { drawTrainingPanel(trainingPanelView(s)); });
    // The hidden curve no longer sets the range: without the ceiling the top is 1, without the floor
    // the bottom is 0.1.
    if (v.hidden.front() == high.label()) EXPECT_DOUBLE_EQ(v.yHi, 0.0);
    else EXPECT_DOUBLE_EQ(v.yLo, -1.0);
    v.hidden.clear();
    frame([&] { drawTrainingPanel(trainingPanelView(s)); });
    EXPECT_DOUBLE_EQ(v.yHi, 2.0);

    const float cx = 0.5f * (v.plotMinX + v.plotMaxX), cy = 0.5f * (v.plotMinY + v.plotMaxY);
    mouse(cx, cy, false);
    frame([&] { drawTrainingPanel(trainingPanelView(s)); });
    mouse(cx, cy, false, 2.f);
    frame([&] { drawTrainingPanel(trainingPanelView(s)); });
    mouse(cx, cy, false, 0.f);
    frame([&] { drawTrainingPanel(trainingPanelView(s)); });
    EXPECT_FALSE(v.plot.autoFit);
    EXPECT_NEAR(v.yHi - v.yLo, 5.0 * 0.64, 1e-9) << "two notches: 64 % of the five decades";
}

TEST_F(LearningPanelTest, ObjectsTableSortsAndExports) {
    const std::vector<ObjectErrorRow> rows = {row(0, "left wall", 0.2, 500), row(1, "floor", 0.05, 900),
                                              row(2, "tall box", 0.4, 300)};
    auto ids = [](const std::vector<ObjectErrorRow>& r) {
        std::vector<int> out;
        for (const ObjectErrorRow& x : r) out.push_back(x.objectId);
        return out;
    };
    EXPECT_EQ(ids(sortedObjectRows(rows, ObjectColumn::Rmse, false)), (std::vector<int>{2, 0, 1}));
    EXPECT_EQ(ids(sortedObjectRows(rows, ObjectColumn::Pixels, true)), (std::vector<int>{2, 0, 1}));
    EXPECT_EQ(ids(sortedObjectRows(rows, ObjectColumn::Object, true)), (std::vector<int>{1, 0, 2}));
    EXPECT_EQ(ids(sortedObjectRows(rows, ObjectColumn::Samples, false)), (std::vector<int>{2, 1, 0}));

    const std::string csv = objectRowsCsv(sortedObjectRows(rows, ObjectColumn::Rmse, true), "global");
    EXPECT_EQ(csv.substr(0, csv.find('\n')),
              "term,object_id,object,rmse,relative_rmse,mae,max,pixels,samples,train_seconds,rmse_noise_floor,rmse_corrected,"
              "relative_rmse_noise_floor,relative_rmse_corrected,signed_relative_mean,relmse,relmse_noise_floor,"
              "relmse_corrected,smape,flip");
    EXPECT_NE(csv.find("\nglobal,1,\"floor\",0.05,0.1,"), std::string::npos) << csv;
    EXPECT_LT(csv.find("floor"), csv.find("tall box")) << "rows in the table's order";

    WorkbenchState s;
    loadCornell(s);
    s.evaluation.valid = true;
    s.evaluation.available[int(Term::Global)] = true;
    s.evaluation.rows[int(Term::Global)] = rows;
    for (int i = 0; i < 3; ++i) frame([&] { drawObjectsPanel(objectsPanelView(s)); });
    EXPECT_TRUE(s.requests.empty());

    // Clicking a row highlights its object, clicking it again clears the highlight. The rows' place
    // depends on the font; found by clicking upwards from inside the table (below its rows, clicks
    // hit nothing), so the first row found is the last one in the default (name) order: "tall box".
    auto clickAt = [&](float y) {
        mouse(60, y, true);
        frame([&] { drawObjectsPanel(objectsPanelView(s)); });
        mouse(60, y, false);
        frame([&] { drawObjectsPanel(objectsPanelView(s)); });
    };
    float rowY = -1;
    for (float y = 300; y > 0 && rowY < 0; y -= 2) {
        clickAt(y);
        if (s.view.selectedObject != -1) rowY = y;
    }
    ASSERT_GT(rowY, 0) << "no table row answered a click";
    EXPECT_EQ(s.view.selectedObject, 2) << "the last row in name order is the tall box";
    clickAt(rowY);
    EXPECT_EQ(s.view.selectedObject, -1) << "a second click clears the highlight";
    clickAt(rowY);
    EXPECT_EQ(s.view.selectedObject, 2);
    EXPECT_TRUE(s.requests.empty());

    // Not predicted: the panel says so instead of drawing a table, so the same click selects nothing.
    s.view.term = Term::Direct;
    s.view.selectedObject = -1;
    clickAt(rowY);
    EXPECT_EQ(s.view.selectedObject, -1) << "no table rows for a term the networks do not predict";
}

TEST_F(LearningPanelTest, CostPanelPlotsEvaluatedTrainingRuns) {
    std::vector<rrf::Run> runs(4);
    runs[0].kind = "render";
    runs[1].kind = "train";
    runs[1].name = "evaluated";
    runs[1].metrics.relativeRmse = 0.12;
    runs[1].metrics.evaluatedWidth = runs[1].metrics.evaluatedHeight = 256;
    runs[1].timings.train = 30.0;
    runs[1].timings.generate = 10.0;
    runs[2].kind = "train";  // never evaluated: no point
    runs[2].timings.train = 5.0;
    runs[3].kind = "train";  // evaluated against a reference of known noise, with its frame times
    runs[3].name = "with noise";
    runs[3].metrics.relativeRmse = 0.10;
    runs[3].metrics.relativeRmseCorrected = 0.08;
    runs[3].metrics.frameSeconds = 0.5;
    runs[3].metrics.glslFrameSeconds = 0.02;
    runs[3].metrics.evaluatedWidth = runs[3].metrics.evaluatedHeight = 128;
    runs[3].timings.train = 20.0;
    const CostSeries series = runsCostSeries(runs);
    ASSERT_EQ(series.points.size(), 2u);
    EXPECT_DOUBLE_EQ(series.points[0].seconds, 40.0) << "the cost of a run includes its data generation";
    EXPECT_DOUBLE_EQ(series.points[0].error, 0.12) << "raw where the reference's noise was unknown";
    EXPECT_FALSE(series.points[0].corrected);
    EXPECT_TRUE(std::isnan(series.points[0].glslFrameSeconds));
    // The sweeps' metric where it is known: the noise-corrected error, as the axis says.
    EXPECT_DOUBLE_EQ(series.points[1].error, 0.08);
    EXPECT_TRUE(series.points[1].corrected);
    EXPECT_DOUBLE_EQ(series.points[1].rawError, 0.10);
    EXPECT_DOUBLE_EQ(series.points[1].frameSeconds, 0.5);
    EXPECT_DOUBLE_EQ(series.points[1].glslFrameSeconds, 0.02);
    EXPECT_EQ(series.points[1].resolution, "128x128");
    EXPECT_EQ(series.resolution, "") << "runs measured at two sizes: the legend says the sizes differ";

    WorkbenchState s;
    loadCornell(s);
    s.project.runs = runs;
    s.costView.showRuns = true;
    CostSeries sweep{"sweep spp", {{0.1, 0.5, "1"}, {0.4, 0.25, "4"}, {1.6, 0.125, "16"}}};
    sweep.kind = CostKind::PathTracer;
    sweep.resolution = "64x64";
    s.cost.sweeps.push_back(sweep);
    for (int i = 0; i < 3; ++i) frame([&] { drawCostPanel(costPanelView(s)); });
    EXPECT_TRUE(s.requests.empty());
    // Every marker the plot drew is in the key, drawn as the key draws it.
    const std::string& drawn = s.costView.shapesDrawn;
    for (const char* m : {"oF", "dF", "sh", "th"}) EXPECT_NE(drawn.find(m), std::string::npos) << m << " in " << drawn;
    for (size_t i = 0; i + 1 < drawn.size(); i += 2)
        EXPECT_NE(s.costView.keyShapes.find(drawn.substr(i, 2)), std::string::npos)
            << "marker " << drawn.substr(i, 2) << " is drawn but not in the key " << s.costView.keyShapes;
}

TEST(LearningProjectIo, NetworkSettingsAndTrainingRunsSurviveSaveAndReopen) {
    const fs::path dir = fs::temp_directory_path() / ("rrf_gui_learning_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    fs::copy_file(RRF_SOURCE_DIR "/projects/cornell-box/project.json", dir / "project.json");
    fs::copy_file(RRF_SOURCE_DIR "/projects/cornell-box/scene.json", dir / "scene.json");
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, (dir / "project.json").string(), error)) << error;
    ASSERT_TRUE(addHiddenLayer(networkPanelView(s)));
    // Adam is the project default: switching away and back stores the trainer section.
    ASSERT_TRUE(setTrainerType(networkPanelView(s), TrainerType::LevenbergMarquardt));
    ASSERT_TRUE(setTrainerType(networkPanelView(s), TrainerType::Adam));
    NetworkSettings edited = s.project.networkOrDefault();
    TrainerConfig editedTrainer = s.project.trainerOrDefault();
    editedTrainer.adam.learningRate = 3e-3;
    editedTrainer.adam.loss = AdamLoss::RelativeL2;
    edited.options.targets = TargetMode::Joint;
    s.project.network = edited;
    s.project.trainer = editedTrainer;

    rrf::Run run;
    run.id = run.name = "train-1";
    run.kind = "train";
    run.curves = {decadeCurve()};
    run.loss = aggregateLoss(run.curves);
    run.settings.network = edited;
    run.settings.trainer = editedTrainer;
    run.metrics.relativeRmse = 0.2;
    run.artifacts = {"runs/train-1/models/models.json"};
    s.project.runs.push_back(run);
    ASSERT_TRUE(saveStateToProject(s, (dir / "project.json").string(), error)) << error;

    WorkbenchState t;
    ASSERT_TRUE(loadProjectIntoState(t, (dir / "project.json").string(), error)) << error;
    const NetworkSettings back = t.project.networkOrDefault();
    EXPECT_EQ(toJson(back), toJson(edited));
    EXPECT_EQ(toJson(t.project.trainerOrDefault()), toJson(editedTrainer));
    ASSERT_EQ(t.project.runs.size(), 1u);
    const rrf::Run& r = t.project.runs[0];
    ASSERT_EQ(r.curves.size(), 1u);
    EXPECT_EQ(r.curves[0].label(), "floor global");
    ASSERT_EQ(r.curves[0].points.size(), 4u);
    EXPECT_DOUBLE_EQ(r.curves[0].points[3].train, 1e-3);
    EXPECT_TRUE(std::isnan(r.curves[0].points[3].validation)) << "a missing validation loss stays missing";
    ASSERT_EQ(r.loss.size(), 4u);
    EXPECT_EQ(toJson(r), toJson(run));
    fs::remove_all(dir);
}

}  // namespace rrf::test::test_learning_panels
