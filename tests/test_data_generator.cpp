// Data generator tests on the bundled Cornell box with tiny grids: the same seed gives the same file
// bytes for any thread count, shards (API and CLI) merge into the bytes of the unsharded run, merge
// rejects missing, overlapping and foreign shards, records agree in expectation with rendered
// pixels, light positions stay in their region, inputs carry exactly the BRDF parameters the scene
// needs, and a cancelled run writes nothing.

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/wait.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include "core/project/project_file.h"
#include "core/data/dataset_header_json.h"
#include "core/scene/camera_rays.h"
#include "core/data/data_generator.h"
#include "core/data/dataset_file.h"
#include "core/project/project.h"
#include "core/render/renderer.h"
#include "scene_builders.h"
#include "tests/cli_runner.h"

namespace test_data_generator {

using namespace rrf;
using namespace rrf::test;
namespace fs = std::filesystem;

namespace {

const std::string kCornell = std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/project.json";

Project cornellBox() { return loadProjectOrScene(kCornell); }

/// A fresh empty directory per test, so parallel ctest runs never share files.
fs::path testDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const fs::path dir = fs::temp_directory_path() / ("rrf_datagen_" + std::string(info->name()) + "_" +
                                                      std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Byte comparison with memcmp (and a size check first, so a mismatch says which).
void expectSameBytes(const std::string& a, const std::string& b) {
    const std::string x = readBytes(a), y = readBytes(b);
    ASSERT_FALSE(x.empty()) << a;
    ASSERT_EQ(x.size(), y.size()) << a << " vs " << b;
    EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size()), 0) << a << " and " << b << " differ";
}

int tempFiles(const fs::path& dir) {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir)) n += e.path().extension() == ".tmp";
    return n;
}

/// The 4×4×4 grid of issue 3's shard test, kept tiny: 64 cells × 20 directions × 4 paths.
SamplingSettings tinySettings(uint64_t seed = 5) {
    SamplingSettings s;
    s.nx = s.ny = s.nz = 4;
    s.directions = 20;
    s.spp = 4;
    s.seed = seed;
    return s;
}

void generateTo(const Scene& scene, const SamplingSettings& s, const std::string& path, int shard = 0, int shards = 1) {
    const DataGenerator gen(scene, s);
    const GeneratedData d = gen.run(shard, shards);
    ASSERT_FALSE(d.cancelled);
    writeDataset(path, datasetHeader(d), d.sceneHash, d.perObject);
}

/// Runs a shell command, returns its exit status and captures stdout+stderr.
int runCommand(const std::string& command, std::string* output = nullptr) {
    std::FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return -1;
    std::string out;
    char buf[512];
    size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
    const int status = ::pclose(pipe);
    if (output) *output = out;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string cli() { return std::string("'") + RRF_CLI_PATH + "'"; }
std::string shellQuote(const std::string& s) { return "'" + s + "'"; }

/// Message of the std::runtime_error that `f` throws ("" and a test failure if none).
template <class F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    ADD_FAILURE() << "no error thrown";
    return "";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

/// Applies `check(objectIndex, record)` to every record of `d`.
template <class F>
void forEachRecord(const GeneratedData& d, int floatsPerRecord, F&& check) {
    for (size_t i = 0; i < d.perObject.size(); ++i)
        for (size_t k = 0; k + size_t(floatsPerRecord) <= d.perObject[i].size(); k += size_t(floatsPerRecord))
            check(i, &d.perObject[i][k]);
}

}  // namespace

TEST(DataGenerator, SameSeedGivesTheSameBytesForAnyThreadCount) {
    const fs::path dir = testDir();
    const Project project = cornellBox();
    const std::string one = (dir / "one.rrfd").string(), two = (dir / "two.rrfd").string();
    {
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        generateTo(project.scene, tinySettings(), one);
    }
    {
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        generateTo(project.scene, tinySettings(), two);
    }
    expectSameBytes(one, two);
    const Dataset d(one, true, project.scene.contentHash());
    EXPECT_GT(d.totalRecords(), 500u) << "most of 64 × 20 rays from inside the room hit something";
    // Another seed gives other data (the seed is really used).
    const std::string other = (dir / "other.rrfd").string();
    generateTo(project.scene, tinySettings(6), other);
    EXPECT_NE(readBytes(one), readBytes(other));
    fs::remove_all(dir);
}

TEST(DataGenerator, ShardsMergeIntoTheBytesOfTheUnshardedRun) {
    const fs::path dir = testDir();
    const Project project = cornellBox();
    const std::string whole = (dir / "whole.rrfd").string();
    generateTo(project.scene, tinySettings(), whole);
    std::vector<std::string> shards;
    for (int k = 0; k < 3; ++k) {
        shards.push_back((dir / ("shard" + std::to_string(k) + ".rrfd")).string());
        generateTo(project.scene, tinySettings(), shards.back(), k, 3);
    }
    // Shards in shuffled order: merge sorts them by their cell range.
    const std::string merged = (dir / "merged.rrfd").string();
    mergeDatasets({shards[2], shards[0], shards[1]}, merged);
    expectSameBytes(whole, merged);
    // The shards really are disjoint parts: their record counts add up and none is empty.
    uint64_t sum = 0;
    for (const std::string& s : shards) {
        const Dataset d(s);
        EXPECT_GT(d.totalRecords(), 0u) << s;
        sum += d.totalRecords();
    }
    EXPECT_EQ(sum, Dataset(whole).totalRecords());
    EXPECT_EQ(tempFiles(dir), 0);
    fs::remove_all(dir);
}

TEST(DataGenerator, CliShardsMergeAndInspect) {
    const fs::path dir = testDir();
    const Project project = cornellBox();
    const std::string whole = (dir / "whole.rrfd").string();
    generateTo(project.scene, tinySettings(), whole);
    std::vector<std::string> shards;
    std::string out;
    for (int k = 0; k < 3; ++k) {
        shards.push_back((dir / ("cli" + std::to_string(k) + ".rrfd")).string());
        const std::string cmd = cli() + " generate " + shellQuote(kCornell) + " --grid 4,4,4 --dirs 20 --spp 4 --seed 5 --threads 2" +
                                " --shard " + std::to_string(k) + "/3 --out " + shellQuote(shards.back());
        ASSERT_EQ(runCommand(cmd, &out), 0) << cmd << "\n" << out;
    }
    EXPECT_TRUE(contains(out, "inputs (15)")) << out;
    const std::string merged = (dir / "cli-merged.rrfd").string();
    ASSERT_EQ(runCommand(cli() + " merge " + shellQuote(shards[1]) + " " + shellQuote(shards[2]) + " " + shellQuote(shards[0]) +
                             " --out " + shellQuote(merged),
                         &out),
              0)
        << out;
    // The CLI's shards, merged by the CLI, are the bytes of the library's unsharded run.
    expectSameBytes(whole, merged);

    ASSERT_EQ(runCommand(cli() + " inspect " + shellQuote(merged), &out), 0) << out;
    const Dataset d(merged);
    for (const std::string& part : {std::string("records: ") + std::to_string(d.totalRecords()), std::string("short-box"),
                                    std::string("light_x"), std::string("indirect_b")})
        EXPECT_TRUE(contains(out, part)) << "inspect output lacks '" << part << "':\n" << out;
    fs::remove_all(dir);
}

TEST(DataGenerator, CliRejectsBadInputWithAClearMessage) {
    const fs::path dir = testDir();
    const std::string out = (dir / "x.rrfd").string();
    std::string msg;
    EXPECT_EQ(runCommand(cli() + " generate " + shellQuote(kCornell) + " --shard 3/3 --out " + shellQuote(out), &msg), 1) << msg;
    EXPECT_TRUE(contains(msg, "--shard")) << msg;
    EXPECT_EQ(runCommand(cli() + " generate " + shellQuote(kCornell) + " --grid 4,0,4 --out " + shellQuote(out), &msg), 1) << msg;
    EXPECT_TRUE(contains(msg, "--grid")) << msg;
    const std::string noProject = (dir / "no-such-project.json").string();
    EXPECT_EQ(runCommand(cli() + " generate " + shellQuote(noProject) + " --out " + shellQuote(out), &msg), 1) << msg;
    EXPECT_TRUE(contains(msg, noProject)) << msg;
    const std::string noData = (dir / "no-such-data.rrfd").string();
    EXPECT_EQ(runCommand(cli() + " inspect " + shellQuote(noData), &msg), 1) << msg;
    EXPECT_TRUE(contains(msg, noData)) << msg;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_EQ(tempFiles(dir), 0);
    fs::remove_all(dir);
}

TEST(DataGenerator, MergeRejectsMissingOverlappingAndForeignShards) {
    const fs::path dir = testDir();
    const Project project = cornellBox();
    auto path = [&](const std::string& name) { return (dir / name).string(); };
    for (int k = 0; k < 3; ++k) generateTo(project.scene, tinySettings(), path("shard" + std::to_string(k) + ".rrfd"), k, 3);
    const std::string s0 = path("shard0.rrfd"), s1 = path("shard1.rrfd"), s2 = path("shard2.rrfd");
    const std::string out = path("merged.rrfd");

    // Missing middle shard: the next shard does not start where the previous one ended.
    std::string msg = errorOf([&] { mergeDatasets({s0, s2}, out); });
    EXPECT_TRUE(contains(msg, s2) && contains(msg, "tile")) << msg;
    // Missing last shard: the grid is not covered.
    msg = errorOf([&] { mergeDatasets({s1, s0}, out); });
    EXPECT_TRUE(contains(msg, s1) && contains(msg, "missing")) << msg;
    // Overlap: shard 0 of 2 covers cells [0, 32), shard 1 of 3 starts at 21.
    const std::string half = path("half0.rrfd");
    generateTo(project.scene, tinySettings(), half, 0, 2);
    msg = errorOf([&] { mergeDatasets({half, s1, s2}, out); });
    EXPECT_TRUE(contains(msg, s1)) << msg;
    // The same shard twice.
    msg = errorOf([&] { mergeDatasets({s0, s1, s1, s2}, out); });
    EXPECT_TRUE(contains(msg, s1)) << msg;
    // Other settings (another spp) for one shard.
    SamplingSettings otherSpp = tinySettings();
    otherSpp.spp = 2;
    const std::string foreignSettings = path("other-settings1.rrfd");
    generateTo(project.scene, otherSpp, foreignSettings, 1, 3);
    msg = errorOf([&] { mergeDatasets({s0, foreignSettings, s2}, out); });
    EXPECT_TRUE(contains(msg, foreignSettings) && contains(msg, "different")) << msg;
    // Another scene (one albedo changed) for one shard.
    Project changed = cornellBox();
    changed.scene.materials[0].kd = changed.scene.materials[0].kd * 0.5f;
    const std::string foreignScene = path("other-scene2.rrfd");
    generateTo(changed.scene, tinySettings(), foreignScene, 2, 3);
    msg = errorOf([&] { mergeDatasets({s0, s1, foreignScene}, out); });
    EXPECT_TRUE(contains(msg, foreignScene) && contains(msg, "different")) << msg;
    // A missing input file.
    msg = errorOf([&] { mergeDatasets({s0, s1, path("nowhere.rrfd")}, out); });
    EXPECT_TRUE(contains(msg, "nowhere.rrfd")) << msg;

    EXPECT_FALSE(fs::exists(out)) << "a failed merge must not write its output";
    EXPECT_EQ(tempFiles(dir), 0);
    // The CLI reports the same error and exit code 1.
    std::string cliOut;
    EXPECT_EQ(runCommand(cli() + " merge " + shellQuote(s0) + " " + shellQuote(s2) + " --out " + shellQuote(out), &cliOut), 1);
    EXPECT_TRUE(contains(cliOut, s2)) << cliOut;
    fs::remove_all(dir);
}

namespace {

/// Compares records with a rendered pixel, the light centre at `lightPos` in both: the render moves
/// the scene's light there (Scene::setLightPosition, a static light in the BVH), the generator is
/// built on the unmoved scene and gets `lightPos` per record (its analytic movable light).
///
/// A 1×1-pixel camera with a 0.1° field of view at the scene camera's eye, aimed at a point of the
/// back wall: the pixel's footprint is ~0.009 units wide, so its mean equals the radiance of the
/// ray through the pixel centre up to a second-order term far below the noise. A record with
/// viewpoint = eye and direction = that ray estimates the same direct and indirect radiance:
/// records with different recordIndex are independent, so their mean has standard error σ_rec/√N;
/// the render's error comes from 16 independent renders (seeds 1…16). Agreement within 5 combined
/// standard errors, per channel.
void compareRecordsWithPixel(const Vec3& lightPos) {
    Project project = cornellBox();
    Scene& scene = project.scene;
    scene.camera.target = Vec3(0.6f, 0.5f, -1.f);
    scene.camera.fovYDegrees = 0.1f;
    scene.camera.width = scene.camera.height = 1;
    const Scene original = scene;
    scene.setLightPosition(lightPos);
    const Accel accel(scene);

    RunningStat pixel[2][3];
    for (int r = 0; r < 16; ++r) {
        RenderOptions o;
        o.width = o.height = 1;
        o.spp = 2000;
        o.samplesPerPass = 2000;
        o.seed = uint64_t(r + 1);
        Renderer renderer(scene, accel, o);
        renderer.run();
        const RenderSnapshot snap = renderer.snapshot();
        for (int c = 0; c < 3; ++c) {
            pixel[0][c].add(snap.direct.at(0, 0)[c]);
            pixel[1][c].add(snap.indirect.at(0, 0)[c]);
        }
    }

    SamplingSettings s;
    s.spp = 4;
    s.maxSpp = 4;  // fixed 4-path records: the bounds below are derived for them
    s.seed = 3;
    const DataGenerator gen(original, s);
    const Ray centre = CameraRays(scene.camera, 1, 1).generate(0, 0, 0.5f, 0.5f);
    const int fpr = gen.layout().floatsPerRecord(), nin = gen.layout().inputCount();
    std::vector<float> rec(size_t(fpr), 0.f);
    RunningStat record[2][3];
    TraceCounters counters;
    uint64_t nonFinite = 0;
    for (uint64_t i = 0; i < 8000; ++i) {
        int object = -1;
        ASSERT_TRUE(gen.estimateRecord(centre.origin, centre.dir, lightPos, i, rec.data(), object, counters, nonFinite));
        ASSERT_EQ(original.objects[size_t(object)].name, "back-wall");
        for (int c = 0; c < 3; ++c) {
            record[0][c].add(rec[size_t(nin + c)]);
            record[1][c].add(rec[size_t(nin + 3 + c)]);
        }
    }
    EXPECT_EQ(nonFinite, 0u);
    // The record's inputs describe that ray: hit on the wall z = −1, normal +z towards the eye.
    EXPECT_NEAR(rec[2], -1.f, 1e-4f);
    EXPECT_NEAR(rec[0], 0.6f, 1e-3f);
    EXPECT_NEAR(rec[1], 0.5f, 1e-3f);
    for (int c = 0; c < 3; ++c) {
        EXPECT_FLOAT_EQ(rec[size_t(3 + c)], -centre.dir[c]) << "view direction points back to the eye";
        EXPECT_EQ(rec[size_t(6 + c)], lightPos[c]);
    }
    EXPECT_EQ(rec[9], 0.f);
    EXPECT_EQ(rec[11], 1.f);

    const char* part[2] = {"direct", "indirect"};
    for (int k = 0; k < 2; ++k)
        for (int c = 0; c < 3; ++c) {
            const double sigma = std::sqrt(record[k][c].sigma() * record[k][c].sigma() + pixel[k][c].sigma() * pixel[k][c].sigma());
            EXPECT_GT(pixel[k][c].mean, 0.0) << part[k] << " channel " << c << " is lit";
            EXPECT_NEAR(record[k][c].mean, pixel[k][c].mean, 5 * sigma)
                << part[k] << " channel " << c << ": record " << record[k][c].mean << " ± " << record[k][c].sigma()
                << ", pixel " << pixel[k][c].mean << " ± " << pixel[k][c].sigma();
        }
}

}  // namespace

TEST(DataGenerator, RecordMatchesTheRenderedPixelInExpectation) {
    compareRecordsWithPixel(cornellBox().scene.lightPosition());
}

TEST(DataGenerator, RecordWithAMovedLightMatchesAPixelRenderedWithTheLightMoved) {
    // A light position from the light region, off centre and lower than the ceiling: the
    // generator's per-record light must shade exactly like the scene's light moved there.
    const Bounds3 region = cornellBox().scene.lightRegion;
    compareRecordsWithPixel(region.lo + region.extent() * Vec3(0.8f, 0.25f, 0.3f));
}

TEST(DataGenerator, LightPositionsStayInsideTheRegion) {
    const Project project = cornellBox();
    const Scene& scene = project.scene;
    ASSERT_FALSE(scene.lightRegion.empty());
    SamplingSettings s = tinySettings();
    s.nx = s.ny = s.nz = 3;
    s.spp = 1;
    const DataGenerator gen(scene, s);
    const GeneratedData d = gen.run();
    const int fpr = gen.layout().floatsPerRecord();
    const Bounds3& region = scene.lightRegion;
    const Vec3 e = region.extent();
    // lo + extent·u with u < 1 is ≤ hi up to one rounding of the sum: 1e-6 of the coordinates.
    const float tol = 1e-6f * (vabs(region.lo).maxComponent() + vabs(region.hi).maxComponent());
    Vec3 lo(INFINITY), hi(-INFINITY);
    uint64_t n = 0;
    forEachRecord(d, fpr, [&](size_t, const float* r) {
        const Vec3 l(r[6], r[7], r[8]);
        for (int c = 0; c < 3; ++c) {
            EXPECT_GE(l[c], region.lo[c] - tol);
            EXPECT_LE(l[c], region.hi[c] + tol);
        }
        lo = vmin(lo, l);
        hi = vmax(hi, l);
        ++n;
    });
    ASSERT_GT(n, 200u);
    // The positions cover the region: with n ≥ 200 uniform draws, the chance that none falls in the
    // outer 10% of an axis on one side is 0.9^200 ≈ 7e-10.
    for (int c = 0; c < 3; ++c) {
        EXPECT_LT(lo[c], region.lo[c] + 0.1f * e[c]) << "axis " << c;
        EXPECT_GT(hi[c], region.hi[c] - 0.1f * e[c]) << "axis " << c;
    }
    EXPECT_EQ(gen.lightRegion().lo.x, region.lo.x);

    // A fixed light: every record carries the scene's light position exactly.
    s.fixedLight = true;
    const DataGenerator fixed(scene, s);
    const GeneratedData f = fixed.run();
    const Vec3 p = scene.lightPosition();
    uint64_t m = 0;
    forEachRecord(f, fpr, [&](size_t, const float* r) {
        EXPECT_TRUE(r[6] == p.x && r[7] == p.y && r[8] == p.z) << Vec3(r[6], r[7], r[8]) << " vs " << p;
        ++m;
    });
    EXPECT_GT(m, 200u);
}

TEST(DataGenerator, LambertSceneRecordsCarryAlbedoOnly) {
    const Project project = cornellBox();
    const Scene& scene = project.scene;
    SamplingSettings s = tinySettings();
    s.nx = s.ny = s.nz = 3;
    s.spp = 2;
    const DataGenerator gen(scene, s);
    ASSERT_EQ(gen.layout().inputCount(), 15);
    ASSERT_EQ(gen.layout().floatsPerRecord(), 27) << "15 inputs, 6 targets, 6 target variances";
    const GeneratedData d = gen.run();
    EXPECT_EQ(datasetHeader(d).at("input_layout").size(), 15u);
    EXPECT_EQ(datasetHeader(d).at("input_layout")[12], "kd_r");
    EXPECT_EQ(datasetHeader(d).at("floats_per_record"), 27);
    uint64_t n = 0;
    forEachRecord(d, 27, [&](size_t obj, const float* r) {
        const Vec3 kd = scene.materials[size_t(scene.objects[obj].material)].kd;
        EXPECT_TRUE(r[12] == kd.x && r[13] == kd.y && r[14] == kd.z) << scene.objects[obj].name;
        ++n;
    });
    EXPECT_EQ(n, datasetHeader(d).at("stats").at("records").get<uint64_t>());
    // Every object of the room gets records from a 3×3×3 grid.
    for (size_t i = 0; i < d.perObject.size(); ++i) EXPECT_GT(d.perObject[i].size(), 0u) << scene.objects[i].name;
}

TEST(DataGenerator, PhongMaterialAddsSpecularParameters) {
    Project project = cornellBox();
    Scene& scene = project.scene;
    // A Phong material with ks = 0 is a Lambert material: no extra inputs.
    const int floorMaterial = scene.objects[0].material;
    scene.objects[0].material = addPhong(scene, Vec3(0.4f), Vec3(0.f), 20.f, "dull");
    EXPECT_EQ(DataGenerator(scene, tinySettings()).layout().inputCount(), 15);
    scene.objects[0].material = floorMaterial;
    // A glossy one on the tall box: kd, ks and log10(1 + n) for every record (zeros for Lambert).
    const int glossy = addPhong(scene, Vec3(0.3f, 0.2f, 0.1f), Vec3(0.4f, 0.5f, 0.6f), 99.f, "glossy");
    int tall = -1;
    for (const Object& o : scene.objects)
        if (o.name == "tall-box") tall = o.id;
    ASSERT_GE(tall, 0);
    scene.objects[size_t(tall)].material = glossy;
    SamplingSettings s = tinySettings();
    s.nx = s.ny = s.nz = 3;
    s.spp = 1;
    const DataGenerator gen(scene, s);
    ASSERT_EQ(gen.layout().inputCount(), 19);
    const GeneratedData d = gen.run();
    const std::vector<std::string> names = datasetHeader(d).at("input_layout").get<std::vector<std::string>>();
    ASSERT_EQ(names.size(), 19u);
    EXPECT_EQ(names[15], "ks_r");
    EXPECT_EQ(names[18], "log10_exponent_plus_1");
    ASSERT_GT(d.perObject[size_t(tall)].size(), 0u);
    forEachRecord(d, 31, [&](size_t obj, const float* r) {  // 19 inputs, 6 targets, 6 variances
        const Material& m = scene.materials[size_t(scene.objects[obj].material)];
        EXPECT_TRUE(r[12] == m.kd.x && r[13] == m.kd.y && r[14] == m.kd.z) << scene.objects[obj].name;
        if (int(obj) == tall) {
            EXPECT_TRUE(r[15] == 0.4f && r[16] == 0.5f && r[17] == 0.6f);
            EXPECT_FLOAT_EQ(r[18], 2.f) << "log10(1 + 99)";
        } else {
            EXPECT_TRUE(r[15] == 0.f && r[16] == 0.f && r[17] == 0.f && r[18] == 0.f) << scene.objects[obj].name;
        }
    });
}

TEST(DataGenerator, UnusedPhongMaterialAddsNoInputs) {
    // "n comes from the materials present": records are only made on objects, so a glossy material
    // that no object uses (a library entry of the scene file, which the loader keeps) must not add
    // ks and exponent columns that are zero in every record.
    Project project = cornellBox();
    Scene& scene = project.scene;
    addPhong(scene, Vec3(0.3f), Vec3(0.5f), 50.f, "unused glossy");
    EXPECT_EQ(DataGenerator(scene, tinySettings()).layout().inputCount(), 15);
}

TEST(DataGenerator, RecordsAreFiniteWithUnitNormalsFacingTheViewer) {
    const Project project = cornellBox();
    const Scene& scene = project.scene;
    SamplingSettings s = tinySettings();
    s.spp = 2;
    const DataGenerator gen(scene, s);
    const GeneratedData d = gen.run();
    const int fpr = gen.layout().floatsPerRecord(), nin = gen.layout().inputCount();
    // Unit vectors are normalised in float: |len − 1| ≤ a few ulps; 1e-5 leaves room.
    const float unitTol = 1e-5f, posTol = 1e-4f * scene.scale();
    uint64_t n = 0;
    forEachRecord(d, fpr, [&](size_t obj, const float* r) {
        for (int c = 0; c < fpr; ++c) ASSERT_TRUE(std::isfinite(r[c])) << "column " << c;
        const Vec3 p(r[0], r[1], r[2]), view(r[3], r[4], r[5]), normal(r[9], r[10], r[11]);
        EXPECT_NEAR(length(view), 1.f, unitTol);
        EXPECT_NEAR(length(normal), 1.f, unitTol);
        EXPECT_GT(dot(view, normal), 0.f) << "normal faces the viewer";
        // The hit point lies on the object the record is filed under.
        const Bounds3 b = scene.objects[obj].bounds();
        for (int c = 0; c < 3; ++c) {
            EXPECT_GE(p[c], b.lo[c] - posTol);
            EXPECT_LE(p[c], b.hi[c] + posTol);
        }
        for (int c = 0; c < 6; ++c) EXPECT_GE(r[nin + c], 0.f) << "radiance is non-negative";
        ++n;
    });
    EXPECT_GT(n, 500u);
    const nlohmann::json st = datasetHeader(d).at("stats");
    EXPECT_EQ(st.at("non_finite_samples_dropped").get<uint64_t>(), 0u);
    // Every ray of every kept cell is accounted for: a record, an escape, an emitter hit, or a hit
    // without a finite sample.
    const uint64_t kept = uint64_t(s.cellCount()) - st.at("cells_dropped_inside_object").get<uint64_t>() -
                          st.at("cells_dropped_outside_scene").get<uint64_t>();
    EXPECT_EQ(st.at("records").get<uint64_t>() + st.at("rays_escaped").get<uint64_t>() +
                  st.at("rays_hit_emitter").get<uint64_t>() + st.at("records_without_finite_sample").get<uint64_t>(),
              kept * uint64_t(s.directions));
    EXPECT_EQ(st.at("records").get<uint64_t>(), n);
    uint64_t perCell = 0;
    for (const auto& v : st.at("records_per_cell")) perCell += v.get<uint64_t>();
    EXPECT_EQ(perCell, n);
    EXPECT_GT(st.at("rays_hit_emitter").get<uint64_t>() + st.at("rays_escaped").get<uint64_t>(), 0u)
        << "the open front and the light are seen from some viewpoints";
}

TEST(DataGenerator, CancelledRunProducesNoData) {
    const Project project = cornellBox();
    const DataGenerator gen(project.scene, tinySettings());
    std::atomic<bool> cancel{true};
    GeneratorProgress progress;
    const GeneratedData d = gen.run(0, 1, &cancel, &progress);
    EXPECT_TRUE(d.cancelled);
    EXPECT_EQ(progress.cellsDone.load(), 0u);
    for (const auto& v : d.perObject) EXPECT_TRUE(v.empty());
    EXPECT_THROW(gen.run(3, 3), std::runtime_error) << "shard index out of range";
}

TEST(DataGenerator, InterruptedCliWritesNothing) {
    // SIGINT (Ctrl-C) during `rrf generate`: exit code 130, no dataset and no temporary file.
    // The job cannot finish before the signal (one cell × 200 000 directions × 4096 paths: minutes on
    // 2 cores, and only ~22 MB against the memory bound rrf generate checks up front), so the signal always
    // finds it running, however loaded the machine; it comes once
    // the progress line shows that the interrupt handler is installed. A run that ignored the
    // signal would be killed after a minute and fail the test instead of hanging it.
    const fs::path dir = testDir();
    const std::string out = (dir / "interrupted.rrfd").string();
    const InterruptedRun run = interruptCli(
        {"generate", kCornell, "--grid", "1,1,1", "--dirs", "200000", "--spp", "4096", "--out", out}, "generate:");
    ASSERT_TRUE(run.started);
    if (!run.exited) FAIL() << "rrf generate still running a minute after SIGINT: " << run.err;
    const int status = run.status;
    const std::string& err = run.err;
    ASSERT_TRUE(WIFEXITED(status)) << err;
    EXPECT_EQ(WEXITSTATUS(status), 130) << err;
    EXPECT_TRUE(contains(err, "no dataset written")) << err;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_EQ(tempFiles(dir), 0);
    fs::remove_all(dir);
}

}  // namespace test_data_generator
