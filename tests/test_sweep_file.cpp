// Sweeps read back from their JSON files (core/pipeline/sweep_file.h): what a re-opened project's
// Cost panel shows is what the sweep measured, and a damaged file is refused naming the file and
// the member.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "core/pipeline/sweep.h"
#include "core/pipeline/sweep_file.h"
#include "core/util/error.h"
#include "core/util/json_reader.h"
#include "scene_builders.h"
#include "sweep_builders.h"
#include "test_dirs.h"

namespace test_sweep_file {

using namespace rrf;

namespace {
/// Equal, or both unknown (NaN).
void expectSameFigure(double a, double b, const std::string& what) {
    if (std::isnan(a) || std::isnan(b)) EXPECT_TRUE(std::isnan(a) && std::isnan(b)) << what << ": " << a << " vs " << b;
    else EXPECT_DOUBLE_EQ(a, b) << what;
}

void expectSameRow(const SweepRow& a, const SweepRow& b) {
    EXPECT_EQ(a.setting, b.setting);
    EXPECT_EQ(a.spp, b.spp);
    EXPECT_EQ(a.stageSeconds.size(), b.stageSeconds.size()) << a.setting;
    expectSameFigure(a.overall.relativeRmse, b.overall.relativeRmse, a.setting + " relative RMSE");
    expectSameFigure(a.overall.relativeRmseCorrected, b.overall.relativeRmseCorrected, a.setting + " corrected");
    expectSameFigure(a.overall.relativeRmseNoiseFloor, b.overall.relativeRmseNoiseFloor, a.setting + " floor");
    EXPECT_EQ(a.overall.pixels, b.overall.pixels);
    expectSameFigure(a.oneOffSeconds, b.oneOffSeconds, a.setting + " one-off");
    expectSameFigure(a.frameSeconds, b.frameSeconds, a.setting + " frame");
    expectSameFigure(a.glslFrameSeconds, b.glslFrameSeconds, a.setting + " GLSL frame");
    EXPECT_EQ(a.breakEven.known, b.breakEven.known);
    if (a.breakEven.known) {
        EXPECT_DOUBLE_EQ(a.breakEven.spp, b.breakEven.spp);
    }
    EXPECT_EQ(a.perObject.size(), b.perObject.size());
    EXPECT_EQ(a.extra, b.extra);
}

SweepResult tinySweep(const Scene& scene) { return runSweep(scene, test::tinyHiddenSweep({"3"})); }
}  // namespace

TEST(SweepFile, ReadsBackWhatTheSweepWrote) {
    const Scene scene = test::cornellLike(1.f, 16);
    SweepResult r = tinySweep(scene);
    ASSERT_EQ(r.rows.size(), 1u);
    r.rows[0].glslFrameSeconds = 0.004;  // as the workbench measures it after the sweep
    const std::filesystem::path dir = test::freshTestDir("rrf_sweep_file");
    const std::string path = (dir / "hidden-1.json").string();
    std::ofstream(path) << sweepJson(scene, r).dump(2);

    const SweepResult back = readSweepFile(path);
    EXPECT_EQ(back.what, "hidden");
    EXPECT_EQ(back.width, 8);
    EXPECT_EQ(back.height, 8);
    EXPECT_EQ(back.referenceSpp, r.referenceSpp);
    EXPECT_TRUE(back.lightPosition == r.lightPosition);
    expectSameFigure(back.relativeNoiseFloor, r.relativeNoiseFloor, "noise floor");
    ASSERT_EQ(back.rows.size(), r.rows.size());
    ASSERT_EQ(back.pathTracer.size(), r.pathTracer.size());
    for (size_t i = 0; i < r.rows.size(); ++i) expectSameRow(back.rows[i], r.rows[i]);
    for (size_t i = 0; i < r.pathTracer.size(); ++i) expectSameRow(back.pathTracer[i], r.pathTracer[i]);
    EXPECT_DOUBLE_EQ(back.rows[0].glslFrameSeconds, 0.004);
}

TEST(SweepFile, EveryFigureIsWrittenUnderItsKeyAndReadBackToTheSameBytes) {
    const Scene scene = test::cornellLike(1.f, 16);
    SweepResult r;
    r.what = "trainer";
    r.width = r.height = 8;
    r.extra.generateSeconds = 1.5;
    r.extra.loglogSlopeRmse = -0.5;
    r.extra.loglogSlopeRmseCorrected = std::nan("");
    r.extra.other = jsonText({{"future_result_figure", {1, 2}}});
    SweepRow model;
    model.setting = "lm";
    model.stageSeconds = {{"train", 2.0}};
    model.oneOffSeconds = 3.0;
    model.extra.parameters = 300;
    model.extra.modelBytes = 3840;
    model.extra.leaves = 5;
    model.extra.leafEpochs = 15;
    model.extra.pixelsWithoutNetwork = 63;
    model.extra.nonFinitePredictionValues = 0;
    model.extra.direct = SweepTermFigures{0.25, 0.125, std::nan("")};
    model.extra.records = 15;
    model.extra.meanRecordSpp = 1.0;
    model.extra.recordsAtSppCap = 0;
    model.extra.curve = std::vector<SweepCurvePoint>{{0, "global", 1, 0.5, 0.75, std::nan("")}};
    model.extra.other = jsonText({{"future_row_figure", "x"}, {"leaves_of_a_newer_kind", {{"n", 1}}}});
    r.rows.push_back(model);
    SweepRow series;
    series.setting = "1";
    series.spp = 1;
    series.extra.nonFiniteSamplesDropped = 2;
    r.pathTracer.push_back(series);

    const nlohmann::json j = sweepJson(scene, r);
    EXPECT_EQ(j["extra"].dump(),
              R"({"future_result_figure":[1,2],"generate_seconds":1.5,"loglog_slope_rmse":-0.5,"loglog_slope_rmse_corrected":null})");
    EXPECT_EQ(j["rows"][0]["extra"].dump(),
              R"({"curve":[{"epoch":1,"object":0,"seconds":0.5,"target":"global","train_loss":0.75,"validation_loss":null}],)"
              R"("direct_relative_rmse":0.25,"direct_relative_rmse_corrected":null,"direct_relative_rmse_noise_floor":0.125,)"
              R"("future_row_figure":"x","leaf_epochs":15,"leaves":5,"leaves_of_a_newer_kind":{"n":1},"mean_record_spp":1.0,)"
              R"("model_bytes":3840,"non_finite_prediction_values":0,"parameters":300,"pixels_without_network":63,)"
              R"("records":15,"records_at_spp_cap":0})");
    EXPECT_EQ(j["path_tracer"][0]["extra"].dump(), R"({"non_finite_samples_dropped":2})");

    const std::filesystem::path dir = test::freshTestDir("rrf_sweep_file");
    const std::string path = (dir / "trainer-1.json").string();
    std::ofstream(path) << j.dump(2);
    const SweepResult back = readSweepFile(path);
    EXPECT_EQ(back.rows[0].extra, r.rows[0].extra);
    EXPECT_EQ(back.pathTracer[0].extra, r.pathTracer[0].extra);
    EXPECT_EQ(sweepJson(scene, back).dump(2), j.dump(2)) << "a sweep file read back writes the same bytes";
}

TEST(SweepFile, DamagedFileNamesTheFileAndTheMember) {
    const Scene scene = test::cornellLike(1.f, 16);
    const SweepResult r = tinySweep(scene);
    nlohmann::json j = sweepJson(scene, r);
    j["rows"][0]["error"]["relative_rmse"] = "low";
    const std::filesystem::path dir = test::freshTestDir("rrf_sweep_file");
    const std::string path = (dir / "hidden-2.json").string();
    std::ofstream(path) << j.dump();
    try {
        readSweepFile(path);
        FAIL() << "a mistyped figure was read";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_TRUE(test::contains(what, path)) << what;
        EXPECT_TRUE(test::contains(what, "/rows/0/error/relative_rmse")) << what;
    }
}

TEST(SweepFile, FilesOfADirectoryComeInNameOrder) {
    const std::filesystem::path dir = test::freshTestDir("rrf_sweep_file");
    for (const char* name : {"spp-2.json", "hidden-2.json", "hidden-1.json", "hidden-1.csv"}) std::ofstream(dir / name) << "{}";
    const std::vector<std::string> files = sweepFilesIn(dir.string());
    ASSERT_EQ(files.size(), 3u) << "the CSV beside each JSON is not a sweep file";
    EXPECT_EQ(std::filesystem::path(files[0]).filename(), "hidden-1.json");
    EXPECT_EQ(std::filesystem::path(files[2]).filename(), "spp-2.json");
    EXPECT_TRUE(sweepFilesIn((dir / "none").string()).empty());
}

}  // namespace test_sweep_file
