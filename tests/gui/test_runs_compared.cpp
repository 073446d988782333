// Runs compared (issue 14 item 4): the runs table's row of a training run shows its trainer, hidden
// sizes, leaves, records, training time, held-out error with its noise floor and per-frame
// prediction time; two runs' per-object errors line up by object; and the Objects table says when
// it does not belong to the models shown.
#include <cmath>

#include <gtest/gtest.h>

#include "core/pipeline/run_recording.h"
#include "core/pipeline/run_summary.h"
#include "panels/panels.h"

namespace rrf::test::test_runs_compared {

using namespace rrf::panels;

namespace {
ObjectErrorRow row(int id, const std::string& name, double rel, double floor) {
    ObjectErrorRow r;
    r.objectId = id;
    r.name = name;
    r.stats.relativeRmse = rel;
    r.stats.relativeRmseNoiseFloor = floor;
    return r;
}
}  // namespace

TEST(RunsTable, ATrainRunRowCarriesItsSettingsCostsAndErrors) {
    rrf::Run run = beginRun({}, "train");
    TrainRecord r;
    r.network.options.hidden = {20, 10};
    r.trainer = TrainerConfig().withType("adam");
    r.modelsDir = "/p/runs/t/models";
    r.dataset = "/p/data/dataset.rrfd";
    r.networks = 7;
    r.leaves = 11;
    r.records = 4096;
    r.seconds = 12.5;
    setTrainRun(run, "/p", r);
    EvaluationRecord e;
    e.global.relativeRmse = 0.05;
    e.global.relativeRmseNoiseFloor = 0.01;
    e.global.relativeRmseCorrected = 0.049;
    e.referenceSpp = 256;
    e.lights = {Vec3(0.f)};
    e.width = 128;
    e.height = 96;
    std::vector<rrf::Run> runs = {run};
    ASSERT_EQ(recordEvaluation(runs, "/p", "/p/runs/t/models", e), 1);
    ASSERT_EQ(recordFrameSeconds(runs, "/p", "/p/runs/t/models", FramePath::Glsl, 0.004, 320, 240), 1);

    const RunSummary s = summarizeRun(runs[0]);
    EXPECT_EQ(s.trainer, "Adam");
    EXPECT_EQ(hiddenText(s.hidden), "20,10");
    ASSERT_TRUE(s.leaves && s.records && s.seconds && s.error && s.noiseFloor && s.frameSeconds);
    EXPECT_EQ(*s.leaves, 11);
    EXPECT_EQ(*s.records, 4096.0);
    EXPECT_EQ(*s.seconds, 12.5);
    EXPECT_EQ(*s.error, 0.05);
    EXPECT_EQ(*s.noiseFloor, 0.01);
    EXPECT_EQ(*s.frameSeconds, 0.004);
    EXPECT_TRUE(s.frameGlsl);
    EXPECT_EQ(s.frameWidth, 320) << "the frame's size is recorded beside its time";
    EXPECT_EQ(s.frameHeight, 240);
    EXPECT_EQ(s.evaluatedWidth, 128) << "and the size the error was measured at beside the error";
    EXPECT_EQ(s.evaluatedHeight, 96);
    EXPECT_EQ(s.status, "7 networks");
}

TEST(RunsTable, UnknownFiguresStayUnknownNotZero) {
    rrf::Run run = beginRun({}, "train");
    TrainRecord r;
    r.modelsDir = "/p/runs/t/models";
    r.dataset = "/p/d.rrfd";
    r.networks = 1;
    setTrainRun(run, "/p", r);
    EvaluationRecord e;  // a reference without its variance: the floor is NaN
    e.global.relativeRmse = 0.2;
    e.lights = {Vec3(0.f)};
    std::vector<rrf::Run> runs = {run};
    recordEvaluation(runs, "/p", "/p/runs/t/models", e);
    const RunSummary s = summarizeRun(runs[0]);
    EXPECT_FALSE(s.leaves.has_value());
    EXPECT_FALSE(s.records.has_value());
    EXPECT_FALSE(s.noiseFloor.has_value()) << "an unknown noise floor is not stored as a number";
    EXPECT_FALSE(s.frameSeconds.has_value());
    ASSERT_TRUE(s.error.has_value());
    EXPECT_EQ(*s.error, 0.2);
    EXPECT_EQ(hiddenText({}), "-");
}

TEST(RunsTable, TwoRunsPerObjectErrorsLineUpByObject) {
    EvaluationInfo a, b;
    a.valid = b.valid = true;
    a.rows[int(Term::Global)] = {row(0, "floor", 0.10, 0.01), row(2, "ball", 0.30, 0.02)};
    b.rows[int(Term::Global)] = {row(2, "ball", 0.20, 0.02), row(1, "wall", 0.05, 0.03)};
    const std::vector<PairedObjectRow> rows = pairedObjectRows(a, b, Term::Global);
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_EQ(rows[0].objectId, 0);
    EXPECT_EQ(rows[0].a, 0.10);
    EXPECT_TRUE(std::isnan(rows[0].b)) << "B has no row for the floor";
    EXPECT_EQ(rows[1].objectId, 1);
    EXPECT_TRUE(std::isnan(rows[1].a));
    EXPECT_EQ(rows[1].b, 0.05);
    EXPECT_EQ(rows[2].name, "ball");
    EXPECT_EQ(rows[2].a, 0.30);
    EXPECT_EQ(rows[2].b, 0.20);
    EXPECT_EQ(rows[2].noiseFloor, 0.02);
}

TEST(ObjectsTable, SaysWhenItJudgedOtherModelsThanTheOnesShown) {
    WorkbenchState s;
    EXPECT_EQ(objectsTableMismatch(objectsPanelView(s)), "") << "no evaluation: nothing to disown";
    s.evaluation.valid = true;
    s.evaluation.modelsDir = "/p/runs/train-1/models";
    s.training.modelsDir = "/p/runs/train-1/models/";
    EXPECT_EQ(objectsTableMismatch(objectsPanelView(s)), "");
    s.training.modelsDir = "/p/runs/train-2/models";
    const std::string m = objectsTableMismatch(objectsPanelView(s));
    EXPECT_NE(m.find("train-1"), std::string::npos) << m;
    EXPECT_NE(m.find("train-2"), std::string::npos) << m;
    s.training.modelsDir.clear();
    EXPECT_NE(objectsTableMismatch(objectsPanelView(s)).find("no models are loaded"), std::string::npos);
    s.view.compareSource = CompareSource::RunPair;
    EXPECT_NE(objectsTableMismatch(objectsPanelView(s)).find("two runs"), std::string::npos);
}

}  // namespace rrf::test::test_runs_compared
