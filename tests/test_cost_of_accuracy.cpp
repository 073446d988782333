// What accuracy costs (core/eval/break_even.h, core/pipeline/sweep.h): the break-even read off a path
// tracer series with a known closed form, the error a comparison uses, and the sweep's reports with
// the cost columns; a small real sweep measures every point over one footprint mask against one
// reference and renders the path tracer's series for a model sweep.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/eval/break_even.h"
#include "core/pipeline/sweep.h"
#include "core/pipeline/sweep_file.h"
#include "core/predict/footprint_mask.h"
#include "core/predict/gbuffer.h"
#include "core/scene/accel.h"
#include "scene_builders.h"
#include "sweep_builders.h"
#include "tests/training_builders.h"

namespace test_cost_of_accuracy {

using namespace rrf;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// error = c / sqrt(spp), render time 10 ms per spp, at spp = 1, 2, 4, …, 256.
std::vector<PathTracerPoint> monteCarloSeries(double c) {
    std::vector<PathTracerPoint> s;
    for (int spp = 1; spp <= 256; spp *= 2) s.push_back({double(spp), 0.01 * spp, c / std::sqrt(double(spp))});
    return s;
}

}  // namespace

TEST(BreakEven, RecoversTheSppOfTheMonteCarloLaw) {
    const double c = 0.8;
    // error = c/√N  ⇒  N = (c/e)², seconds = 0.01·N.
    for (double e : {0.4, 0.1, 0.07, 0.0523}) {
        const BreakEven b = breakEven(monteCarloSeries(c), e);
        const double n = (c / e) * (c / e);
        ASSERT_TRUE(b.known) << e;
        EXPECT_FALSE(b.extrapolated) << e;
        EXPECT_NEAR(b.spp, n, 1e-9 * n) << e;
        EXPECT_NEAR(b.seconds, 0.01 * n, 1e-9 * n) << e;
    }
    // Outside the measured range the fitted line (slope exactly -1/2 here) is extended, and said so.
    const BreakEven below = breakEven(monteCarloSeries(c), 0.02);
    ASSERT_TRUE(below.known);
    EXPECT_TRUE(below.extrapolated);
    EXPECT_NEAR(below.spp, 1600.0, 1e-6);
    EXPECT_NEAR(below.seconds, 16.0, 1e-8);
    const BreakEven above = breakEven(monteCarloSeries(c), 1.6);
    ASSERT_TRUE(above.known);
    EXPECT_TRUE(above.extrapolated);
    EXPECT_NEAR(above.spp, 0.25, 1e-12);
}

TEST(BreakEven, OrderOfTheSeriesDoesNotMatterAndBadPointsAreIgnored) {
    std::vector<PathTracerPoint> s = monteCarloSeries(0.8);
    std::reverse(s.begin(), s.end());
    s.push_back({32.0, 0.32, 0.0});  // a point at the noise floor has no place on a log axis
    const BreakEven b = breakEven(s, 0.1);
    ASSERT_TRUE(b.known);
    EXPECT_NEAR(b.spp, 64.0, 1e-9);
}

TEST(BreakEven, UnknownWithoutAUsableSeriesOrError) {
    EXPECT_FALSE(breakEven(monteCarloSeries(0.8), 0.0).known) << "at the noise floor: not measurable";
    EXPECT_FALSE(breakEven(monteCarloSeries(0.8), kNaN).known);
    EXPECT_FALSE(breakEven({{1, 0.01, 0.5}}, 0.1).known) << "one point gives no line";
    // A series that does not converge reaches no lower error.
    EXPECT_FALSE(breakEven({{1, 0.01, 0.5}, {4, 0.04, 0.5}}, 0.1).known);
}

TEST(BreakEven, ComparesTheCorrectedErrorWhenTheNoiseIsKnown) {
    ErrorStats s;
    s.relativeRmse = 0.2;
    EXPECT_DOUBLE_EQ(comparableError(s), 0.2) << "unknown noise: the raw figure";
    s.noiseKnown = true;
    s.relativeRmseNoiseFloor = 0.16;
    s.relativeRmseCorrected = 0.12;
    EXPECT_DOUBLE_EQ(comparableError(s), 0.12);
}

TEST(BreakEven, SentenceNamesSppSecondsAndFrameTimes) {
    const BreakEven b = breakEven(monteCarloSeries(0.8), 0.1);
    const std::string t = breakEvenText(b, 0.1, true, 2.5e-3, 4e-4);
    EXPECT_NE(t.find("the path tracer needs 64 spp / 0.64 s to reach this model's error (0.1, corrected)"), std::string::npos) << t;
    EXPECT_NE(t.find("the model needs 2.5 ms per frame (CPU), 0.4 ms (GLSL)"), std::string::npos) << t;
    EXPECT_NE(breakEvenText(b, 0.1, false, kNaN, kNaN).find("(0.1, raw)"), std::string::npos);
    EXPECT_EQ(breakEvenText(b, 0.1, true, kNaN, kNaN).find("per frame"), std::string::npos) << "unknown times are left out";
    EXPECT_NE(breakEvenText(BreakEven{}, 0.0, true, kNaN, kNaN).find("noise floor"), std::string::npos);
}

TEST(SweepReports, CarryCostColumnsAndThePathTracerSeries) {
    const Scene scene = test::cornellLike();
    SweepResult r;
    r.what = "hidden";
    r.width = r.height = 16;
    r.relativeNoiseFloor = 0.03;
    for (const PathTracerPoint& p : monteCarloSeries(0.8)) {
        SweepRow row;
        row.setting = std::to_string(int(p.spp));
        row.spp = int(p.spp);
        row.stageSeconds = {{"render", p.seconds}};
        row.overall.relativeRmse = p.error;
        r.pathTracer.push_back(row);
    }
    SweepRow model;
    model.setting = "20,10";
    model.stageSeconds = {{"train", 3.0}};
    model.overall.relativeRmse = 0.1;
    model.oneOffSeconds = 5.0;
    model.frameSeconds = 2.5e-3;
    model.breakEven = breakEven(pathTracerPoints(r), comparableError(model.overall));
    r.rows.push_back(model);

    const std::string csv = sweepCsv(scene, r);
    const std::string header = csv.substr(0, csv.find('\n'));
    EXPECT_NE(header.find(",spp,one_off_seconds,frame_seconds,glsl_frame_seconds,breakeven_spp,breakeven_seconds,breakeven_extrapolated"),
              std::string::npos)
        << header;
    const size_t modelLine = csv.find("\nhidden,\"20,10\",");
    ASSERT_NE(modelLine, std::string::npos) << csv;
    const std::string line = csv.substr(modelLine + 1, csv.find('\n', modelLine + 1) - modelLine - 1);
    EXPECT_NE(line.find(",,5,0.0025,,64,0.64,0"), std::string::npos) << "no spp, unknown GLSL time left empty: " << line;
    EXPECT_NE(csv.find("\npath_tracer,16,"), std::string::npos) << "the series follows as path_tracer rows";

    const nlohmann::json j = sweepJson(scene, r);
    ASSERT_EQ(j["path_tracer"].size(), 9u);
    EXPECT_EQ(j["path_tracer"][4]["spp"], 16);
    EXPECT_DOUBLE_EQ(j["rows"][0]["break_even"]["spp"].get<double>(), 64.0);
    EXPECT_TRUE(j["rows"][0]["glsl_frame_seconds"].is_null()) << "unknown, not 0";
    EXPECT_DOUBLE_EQ(j["reference"]["relative_rmse_noise_floor"].get<double>(), 0.03);

    const std::string table = sweepTable(r);
    EXPECT_NE(table.find("the path tracer needs 64 spp / 0.64 s"), std::string::npos) << table;
}

TEST(SweepRun, ProgressMovesWithTheWorkAndNeverGoesBack) {
    const Scene scene = test::cornellLike(1.f, 16);
    SweepOptions o = test::tinyHiddenSweep({"3", "4"});
    std::vector<double> seen;
    o.progress = [&](double f) { seen.push_back(f); };
    runSweep(scene, o);
    // Start, the reference, the shared dataset, then the path tracer's series and two points: three
    // equal shares of what is left.
    const double r = kSweepReferenceShare, d = r + kSweepDataShare;
    const std::vector<double> expected = {0, r, d, d + (1 - d) / 3, d + 2 * (1 - d) / 3, 1};
    ASSERT_EQ(seen.size(), expected.size());
    for (size_t i = 0; i < seen.size(); ++i) EXPECT_NEAR(seen[i], expected[i], 1e-12) << i;
    for (size_t i = 1; i < seen.size(); ++i) EXPECT_GE(seen[i], seen[i - 1]);
}

TEST(SweepRun, EveryPointUsesOneFootprintMaskAndModelSweepsRenderThePathTracer) {
    const Scene scene = test::cornellLike(1.f, 16);
    SweepOptions o;
    o.training = test::plainTraining();
    o.what = "hidden";
    o.values = {"3"};
    o.width = o.height = 16;
    o.referenceSpp = 16;
    o.pathTracerSpp = {4, 1, 2, 2};  // unordered, repeated: rendered once each, in spp order
    o.sampling.nx = o.sampling.ny = o.sampling.nz = 1;
    o.sampling.directions = 20;
    o.sampling.spp = 2;
    o.training.trainer.lm.maxEpochs = 2;
    const SweepResult r = runSweep(scene, o);
    ASSERT_EQ(r.pathTracer.size(), 3u);
    EXPECT_EQ(r.pathTracer[0].spp, 1);
    EXPECT_EQ(r.pathTracer[2].spp, 4);
    ASSERT_EQ(r.rows.size(), 1u);

    // The mask, built independently from the G-buffer at the sweep's light position.
    const Accel accel(scene);
    const PathTracer tracer(scene, accel, Estimator::NEE, 1);
    const FootprintMask mask =
        footprintMask(buildGBuffer(tracer, RecordLayout::forScene(scene), r.lightPosition, o.width, o.height));
    ASSERT_GT(mask.counts.total(), 0u) << "the scene has edges to leave out";
    for (const SweepRow& row : r.pathTracer) EXPECT_EQ(row.overall.pixels, mask.kept.size()) << row.setting;
    EXPECT_EQ(r.rows[0].overall.pixels, mask.kept.size());
    EXPECT_GT(r.rows[0].oneOffSeconds, 0.0);
    EXPECT_GT(r.rows[0].frameSeconds, 0.0);
    EXPECT_TRUE(std::isnan(r.rows[0].glslFrameSeconds)) << "core has no GL";
    EXPECT_EQ(r.rows[0].models, nullptr) << "networks are kept only on request";
    EXPECT_DOUBLE_EQ(r.relativeNoiseFloor, r.rows[0].overall.relativeRmseNoiseFloor) << "one reference, one mask";
}

}  // namespace test_cost_of_accuracy
