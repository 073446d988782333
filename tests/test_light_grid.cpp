// Error across the light region (core/eval/light_grid.h, `rrf evaluate --light-grid`): the grid's
// syntax and bounds, positions spanning the region with its edges, the figure each point shows
// (noise-corrected where known, raw otherwise, none where an object is out of view), slice images
// whose cells carry exactly their point's colour and whose marks fall in the right cell and height
// band, and the command end to end on a trained Cornell box with the training records' lights marked.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include <gtest/gtest.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include "core/eval/light_grid.h"
#include "core/util/error.h"
#include "core/util/image_io.h"
#include "tests/cli_runner.h"

namespace test_light_grid {

using namespace rrf;
namespace fs = std::filesystem;

namespace {
const double kNaN = std::numeric_limits<double>::quiet_NaN();

Bounds3 box(Vec3 lo, Vec3 hi) {
    Bounds3 b;
    b.lo = lo;
    b.hi = hi;
    return b;
}

/// An evaluation whose global term has the given overall and per-object figures.
Evaluation evaluationWith(Vec3 light, double raw, double corrected, std::vector<std::pair<double, uint64_t>> objects) {
    Evaluation e;
    e.lightPosition = light;
    TermErrors& g = e.terms[int(Term::Global)];
    g.overall.pixels = 100;
    g.overall.relativeRmse = raw;
    g.overall.relativeRmseCorrected = corrected;
    g.overall.relativeRmseNoiseFloor = std::isfinite(corrected) ? 0.01 : kNaN;
    for (const auto& [v, pixels] : objects) {
        ErrorStats s;
        s.pixels = pixels;
        s.relativeRmse = v;
        g.perObject.push_back(s);
    }
    return e;
}

std::string refusal(const std::string& text) {
    try {
        LightGridSpec::parse(text, "command line", "--light-grid");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST(LightGrid, ParsesNxMxKAndRefusesEveryOtherForm) {
    const LightGridSpec g = LightGridSpec::parse("4x2X3", "command line", "--light-grid");
    EXPECT_EQ(g.counts[0], 4);
    EXPECT_EQ(g.counts[1], 2);
    EXPECT_EQ(g.counts[2], 3);
    EXPECT_EQ(g.size(), 24u);
    EXPECT_EQ(g.text(), "4x2x3");
    for (const char* bad : {"", "4x2", "4x2x", "4x2x3x1", "0x1x1", "65x1x1", "a", "4,2,3", "-1x2x2", "4x2x3 ", "00001x1x1"}) {
        const std::string why = refusal(bad);
        EXPECT_NE(why.find("--light-grid"), std::string::npos) << "'" << bad << "': " << why;
        EXPECT_NE(why.find("NxMxK"), std::string::npos) << "'" << bad << "': " << why;
    }
    // Every count within bounds, but more points than references anyone should render at once.
    const std::string tooMany = refusal("16x16x17");
    EXPECT_NE(tooMany.find("at most 4096"), std::string::npos) << tooMany;
    EXPECT_NE(tooMany.find("4352"), std::string::npos) << tooMany;
}

TEST(LightGrid, RefusesAFixedLightAndSeveralPointsAlongAFlatAxis) {
    Scene scene;
    auto why = [&](const char* text) {
        try {
            checkLightGrid(LightGridSpec::parse(text, "t", "f"), scene, "command line", "--light-grid");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(why("2x2x2").find("does not move"), std::string::npos) << why("2x2x2");
    scene.lightRegion = box(Vec3(-1.f, 0.5f, -1.f), Vec3(1.f, 0.5f, 1.f));  // flat in y
    EXPECT_EQ(why("3x1x3"), "");
    const std::string flat = why("3x2x3");
    EXPECT_NE(flat.find("flat along y"), std::string::npos) << flat;
    EXPECT_NE(flat.find("--light-grid"), std::string::npos) << flat;
}

TEST(LightGrid, PositionsSpanTheRegionWithItsEdgesAndTheCentreOfASingleton) {
    const LightGridSpec g = LightGridSpec::parse("3x1x2", "t", "f");
    const std::vector<Vec3> p = g.positions(box(Vec3(-1.f, 0.f, 3.f), Vec3(1.f, 2.f, 4.f)));
    ASSERT_EQ(p.size(), 6u);
    const float xs[3] = {-1.f, 0.f, 1.f}, zs[2] = {3.f, 4.f};
    for (int k = 0; k < 2; ++k)
        for (int i = 0; i < 3; ++i) {
            const Vec3& v = p[g.index(i, 0, k)];
            EXPECT_FLOAT_EQ(v.x, xs[i]);
            EXPECT_FLOAT_EQ(v.y, 1.f);  // one point along y: the region's middle
            EXPECT_FLOAT_EQ(v.z, zs[k]);
        }
    // x runs fastest, then z, then y: a slice of constant y is one block.
    EXPECT_EQ(g.index(1, 0, 0), 1u);
    EXPECT_EQ(g.index(0, 0, 1), 3u);
    const LightGridSpec tall = LightGridSpec::parse("2x3x2", "t", "f");
    EXPECT_EQ(tall.index(0, 1, 0), 4u);
}

TEST(LightGrid, EachPointShowsTheCorrectedFigureWhereTheNoiseIsKnownAndTheRawOneElse) {
    const LightGridSpec g = LightGridSpec::parse("2x1x1", "t", "f");
    std::vector<Evaluation> evals;
    evals.push_back(evaluationWith(Vec3(0.f), 0.30, 0.20, {{0.5, 10}, {0.7, 0}}));
    evals.push_back(evaluationWith(Vec3(1.f), 0.40, kNaN, {{0.6, 10}, {0.9, 5}}));
    const LightGridMap m = lightGridMap(g, box(Vec3(0.f), Vec3(1.f)), evals, 2);
    EXPECT_DOUBLE_EQ(m.global[0], 0.20);
    EXPECT_DOUBLE_EQ(m.globalRaw[0], 0.30);
    EXPECT_DOUBLE_EQ(m.global[1], 0.40);
    EXPECT_TRUE(std::isnan(m.globalNoiseFloor[1]));
    EXPECT_DOUBLE_EQ(m.objects[0][0], 0.5);
    EXPECT_TRUE(std::isnan(m.objects[1][0]));  // out of view at the first light
    EXPECT_DOUBLE_EQ(m.objects[1][1], 0.9);
    EXPECT_DOUBLE_EQ(LightGridMap::scaleOf(m.global), 0.40);
    EXPECT_DOUBLE_EQ(LightGridMap::scaleOf({kNaN, kNaN}), 0.0);
    EXPECT_THROW(lightGridMap(LightGridSpec::parse("3x1x1", "t", "f"), m.region, evals, 2), std::invalid_argument);
}

TEST(LightGrid, SliceCellsCarryTheirPointsColourAndMarksFallInTheirCellAndHeightBand) {
    const LightGridSpec g = LightGridSpec::parse("2x2x2", "t", "f");
    const Bounds3 region = box(Vec3(0.f, 0.f, 0.f), Vec3(1.f, 1.f, 1.f));
    LightGridMap m;
    m.grid = g;
    m.region = region;
    m.lights = g.positions(region);
    std::vector<double> values(8);
    for (size_t n = 0; n < 8; ++n) values[n] = 0.1 * double(n + 1);
    values[g.index(1, 1, 1)] = kNaN;
    // One mark at the grid point (1, ·, 0) of the upper slice, one just inside the lower slice's band.
    m.marks = {Vec3(1.f, 0.9f, 0.f), Vec3(0.f, 0.4f, 1.f)};
    const int cell = 10;
    const double scale = 0.8;
    for (int j = 0; j < 2; ++j) {
        const Image s = lightGridSlice(m, values, j, cell, scale);
        ASSERT_EQ(s.width, 20);
        ASSERT_EQ(s.height, 20);
        for (int k = 0; k < 2; ++k)
            for (int i = 0; i < 2; ++i) {
                const double v = values[g.index(i, j, k)];
                const Vec3 want = std::isfinite(v) ? viridis(float(v / scale)) : Vec3(1.f, 0.f, 1.f);
                const Vec3 got = s.at(i * cell + 2, k * cell + 2);  // a corner pixel: never a mark
                EXPECT_NEAR(got.x, want.x, 1e-6) << i << "," << j << "," << k;
                EXPECT_NEAR(got.y, want.y, 1e-6);
                EXPECT_NEAR(got.z, want.z, 1e-6);
            }
        int white = 0;
        for (int y = 0; y < s.height; ++y)
            for (int x = 0; x < s.width; ++x) white += s.at(x, y) == Vec3(1.f);
        EXPECT_EQ(white, 1) << "slice " << j;
        // The upper slice's mark sits at the centre of cell (1, 0); the lower's at the centre of (0, 1).
        if (j == 1) {
            EXPECT_EQ(s.at(cell + cell / 2, cell / 2), Vec3(1.f));
        } else {
            EXPECT_EQ(s.at(cell / 2, cell + cell / 2), Vec3(1.f));
        }
    }
    EXPECT_THROW(lightGridSlice(m, values, 2, cell, scale), std::invalid_argument);
}

TEST(LightGrid, EvaluateWritesTheMapOfATrainedBoxWithItsTrainingLightsMarked) {
    const fs::path dir = fs::temp_directory_path() / ("rrf_light_grid_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path cornell = fs::path(RRF_SOURCE_DIR) / "projects" / "cornell-box";
    for (const char* f : {"project.json", "scene.json"}) fs::copy_file(cornell / f, dir / f);
    const std::string project = (dir / "project.json").string(), data = (dir / "data.rrfd").string();
    const auto g = rrf::test::runCli("generate " + project + " --grid 2,2,2 --dirs 4 --spp 2 --threads 2 --out " + data);
    ASSERT_EQ(g.code, 0) << g.output;
    const auto t = rrf::test::runCli("train " + project + " --data " + data +
                                     " --hidden 4 --epochs 2 --threads 2 --log-every 0 --record");
    ASSERT_EQ(t.code, 0) << t.output;
    const fs::path runs = dir / "runs";
    fs::path models;
    for (const auto& e : fs::directory_iterator(runs))
        if (fs::exists(e.path() / "models" / "models.json")) models = e.path() / "models";
    ASSERT_FALSE(models.empty());

    // A malformed grid is refused before any work, naming the flag.
    const auto bad = rrf::test::runCli("evaluate " + project + " --models " + models.string() + " --light-grid 2x2 --out " +
                                       (dir / "bad").string());
    EXPECT_NE(bad.code, 0);
    EXPECT_NE(bad.output.find("--light-grid"), std::string::npos) << bad.output;
    EXPECT_FALSE(fs::exists(dir / "bad"));

    const fs::path out = dir / "grid";
    const auto e = rrf::test::runCli("evaluate " + project + " --models " + models.string() +
                                     " --light-grid 2x2x2 --spp 1 --width 16 --height 16 --threads 2 --out " + out.string());
    ASSERT_EQ(e.code, 0) << e.output;
    EXPECT_NE(e.output.find("error across the light region (2x2x2"), std::string::npos) << e.output;
    nlohmann::json j;
    std::ifstream(out / "light_grid.json") >> j;
    ASSERT_EQ(j.at("lights").size(), 8u);
    EXPECT_EQ(j.at("grid"), nlohmann::json::array({2, 2, 2}));
    // The Cornell box's light region, corners included.
    const nlohmann::json& first = j.at("lights")[0];
    EXPECT_EQ(first.at("index"), nlohmann::json::array({0, 0, 0}));
    EXPECT_NEAR(first.at("position")[0].get<double>(), -0.5, 1e-6);
    EXPECT_NEAR(first.at("position")[1].get<double>(), 0.6, 1e-6);
    EXPECT_NEAR(first.at("position")[2].get<double>(), -0.5, 1e-6);
    EXPECT_NEAR(j.at("lights")[7].at("position")[1].get<double>(), 0.99, 1e-6);
    for (const auto& l : j.at("lights")) {
        EXPECT_TRUE(l.at("global").at("relative_rmse").is_number()) << l.dump();
        EXPECT_TRUE(l.at("objects").contains("floor")) << l.dump();
    }
    // The training run's dataset gave the marks (2x2x2 cells x 4 directions: a few dozen records).
    EXPECT_GT(j.at("marks").at("count").get<int>(), 0) << j.at("marks").dump();
    EXPECT_EQ(fs::path(j.at("marks").at("source").get<std::string>()), fs::path(data));
    for (int s = 0; s < 2; ++s) {
        const Image slice = readImage((out / ("light_grid_y" + std::to_string(s) + ".png")).string());
        EXPECT_EQ(slice.width, slice.height);
        EXPECT_GE(slice.width, 256);
    }
    EXPECT_FALSE(fs::exists(out / "light_grid_y2.png"));
    EXPECT_TRUE(fs::exists(out / "light_grid.txt"));
    EXPECT_TRUE(fs::exists(out / "light_7" / "evaluation.json"));
    EXPECT_TRUE(fs::exists(out / "held_out.json"));

    // A flatter grid into the same directory replaces the set of slices whole.
    const auto flat = rrf::test::runCli("evaluate " + project + " --models " + models.string() +
                                        " --light-grid 2x1x2 --spp 1 --width 16 --height 16 --threads 2 --out " + out.string());
    ASSERT_EQ(flat.code, 0) << flat.output;
    EXPECT_TRUE(fs::exists(out / "light_grid_y0.png"));
    EXPECT_FALSE(fs::exists(out / "light_grid_y1.png"));
    fs::remove_all(dir);
}

}  // namespace test_light_grid
