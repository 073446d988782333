// Hostile input (issue 12): coordinates beyond the range where rays stay valid, numbers beyond
// double, malformed dataset headers, memory requests beyond what the machine has, an object without
// records, a cancel in the middle of one huge cell, scenes whose every sample is non-finite and
// damaged scene overrides. Each must end in an InputError that names the file (or setting), the
// field and what is accepted — never an abort, raw library text, undefined behaviour or a hang.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "core/data/data_generator.h"
#include "core/data/dataset_file.h"
#include "core/data/dataset_header_json.h"
#include "core/project/scene_overrides.h"
#include "core/project/scene_overrides_json.h"
#include "core/render/render_settings.h"
#include "core/render/renderer.h"
#include "core/scene/accel.h"
#include "core/scene/coordinate_range.h"
#include "core/scene/scene_json.h"
#include "core/util/error.h"
#include "core/util/json_reader.h"
#include "core/util/memory_budget.h"

namespace test_hostile_input {

using namespace rrf;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

/// A fresh empty directory per test.
fs::path testDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const fs::path dir = fs::temp_directory_path() / ("rrf_hostile_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

/// An open room (floor, ceiling, three walls; the +z side open) of half-size `h` with a point light
/// of `intensity` at its centre: viewpoints inside it see the walls, so the generator keeps them.
json openRoom(double h, double intensity) {
    auto quad = [](const std::string& name, std::vector<double> c, std::vector<double> e1, std::vector<double> e2) {
        return json{{"type", "quad"}, {"name", name}, {"material", "white"}, {"corner", c}, {"edge1", e1}, {"edge2", e2}};
    };
    const double d = 2 * h;
    return json{{"camera", {{"eye", {0, 0, 3 * h}}, {"target", {0, 0, 0}}, {"fov_y", 60}, {"width", 8}, {"height", 8}}},
                {"materials", {{"white", {{"type", "lambert"}, {"albedo", {0.8, 0.8, 0.8}}}}}},
                {"shapes",
                 {quad("floor", {-h, -h, -h}, {0, 0, d}, {d, 0, 0}), quad("ceiling", {-h, h, -h}, {d, 0, 0}, {0, 0, d}),
                  quad("back", {-h, -h, -h}, {d, 0, 0}, {0, d, 0}), quad("left", {-h, -h, -h}, {0, d, 0}, {0, 0, d}),
                  quad("right", {h, -h, -h}, {0, 0, d}, {0, d, 0})}},
                {"lights", {{{"type", "point"}, {"name", "bulb"}, {"position", {0, 0, 0}}, {"intensity", {intensity, intensity, intensity}}}}}};
}

/// The InputError message of parsing `scene` as "scene.json" ("" if it parsed).
std::string sceneError(const json& scene) {
    try {
        parseScene(scene, "scene.json", "");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

/// Writes a dataset file by hand (fixed header, JSON header, padding, payload) so that headers the
/// writer would never produce can be tested; the checksums are right, so only the header is wrong.
void writeRawDataset(const std::string& path, const std::string& header, const std::string& payload = "") {
    const uint64_t payloadOffset = (64 + header.size() + 63) / 64 * 64;
    std::string bytes(64, '\0');
    const unsigned char magic[8] = {'R', 'R', 'F', 'D', '\r', '\n', 0x1a, '\n'};
    std::memcpy(&bytes[0], magic, 8);
    const uint32_t version = kDatasetVersion, zero = 0;
    const uint64_t fields[6] = {header.size(), payloadOffset, payload.size(), checksum64(payload.data(), payload.size()),
                                0x1234, checksum64(header.data(), header.size())};
    std::memcpy(&bytes[8], &version, 4);
    std::memcpy(&bytes[12], &zero, 4);
    std::memcpy(&bytes[16], fields, sizeof fields);
    bytes += header;
    bytes.resize(payloadOffset, '\0');
    bytes += payload;
    std::ofstream(path, std::ios::binary) << bytes;
}

/// A valid header of an empty dataset (no objects) for scene hash 0x1234; tests break one field.
json emptyDatasetHeader() {
    return {{"format", "rrf-dataset"},
            {"scene_hash", "1234"},
            {"settings", {{"spp", 1}}},
            {"shard", {{"index", 0}, {"count", 1}, {"cell_begin", 0}, {"cell_end", 1}, {"cells_total", 1}}},
            {"stats", {{"records", 0}, {"records_per_cell", {0}}}},
            {"input_layout", {"in0"}},
            {"target_layout", {"t0"}},
            {"noise_layout", json::array()},
            {"floats_per_record", 2},
            {"objects", json::array()}};
}

/// The message of opening a dataset whose JSON header is `header` ("" if it opened).
std::string datasetError(const fs::path& dir, const std::string& header) {
    const std::string path = (dir / "d.rrfd").string();
    writeRawDataset(path, header);
    try {
        Dataset d(path);
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(HostileInput, CoordinatesBeyondTheRayRangeAreRefusedNamingTheField) {
    struct Case {
        std::string name, pointer;
        std::function<void(json&)> edit;
    };
    const std::vector<Case> cases = {
        {"camera eye 1e19", "/camera/eye", [](json& s) { s["camera"]["eye"] = {0, 0, 1e19}; }},
        {"sphere radius 3e38", "/shapes/5",
         [](json& s) {
             s["shapes"].push_back({{"type", "sphere"}, {"material", "white"}, {"center", {0, 0, 0}}, {"radius", 3e38}});
         }},
        {"box scale 1e30", "/shapes/5",
         [](json& s) { s["shapes"].push_back({{"type", "box"}, {"material", "white"}, {"transform", {{"scale", 1e30}}}}); }},
        {"floor 2e19 wide", "/shapes/0", [](json& s) {
             s["shapes"][0]["edge1"] = {0, 0, 2e19};
             s["shapes"][0]["edge2"] = {2e19, 0, 0};
         }},
        {"point light at 1e30", "/lights/0", [](json& s) { s["lights"][0]["position"] = {1e30, 0, 0}; }},
        {"light region up to 1e10", "/light_region",
         [](json& s) { s["light_region"] = {{"min", {0, 0, 0}}, {"max", {0, 1e10, 0}}}; }},
    };
    for (const Case& c : cases) {
        json scene = openRoom(1, 1);
        c.edit(scene);
        const std::string msg = sceneError(scene);
        EXPECT_TRUE(contains(msg, "scene.json: " + c.pointer)) << c.name << ": " << msg;
        // The accepted range, from the one definition.
        EXPECT_TRUE(contains(msg, "[-1e+09, 1e+09]")) << c.name << ": " << msg;
    }
    // The largest coordinate itself is accepted.
    json edge = openRoom(1, 1);
    edge["camera"]["eye"] = {0, 0, kMaxCoordinate};
    EXPECT_EQ(sceneError(edge), "");
}

TEST(HostileInput, RoomScaledToTheCoordinateBoundRendersAsAtScaleOne) {
    // Radiance does not depend on the scale of a scene lit by an area light, so the open room with a
    // ceiling panel, scaled up until the camera's eye sits on the coordinate bound, must render the
    // image of the room at scale 1 (the same random numbers drive both): no abort inside Embree, no
    // normals or light areas lost to float overflow.
    auto render = [](double h) {
        json j = openRoom(h, 1);
        j["camera"]["eye"] = {0, 0, 2 * h};
        j["lights"] = {{{"type", "rect"}, {"name", "panel"}, {"corner", {-h / 2, 0.99 * h, -h / 2}}, {"edge1", {h, 0, 0}},
                        {"edge2", {0, 0, h}}, {"radiance", {1, 1, 1}}}};
        const Scene scene = parseScene(j, "scene.json", "");
        const Accel accel(scene);
        RenderOptions o;
        o.width = o.height = 8;
        o.spp = o.samplesPerPass = 8;
        Renderer r(scene, accel, o);
        r.run();
        return r.snapshot();
    };
    const RenderSnapshot unit = render(1), edge = render(double(kMaxCoordinate) / 2);
    EXPECT_EQ(edge.nonFinite, 0u);
    double sumUnit = 0, sumEdge = 0;
    for (size_t i = 0; i < unit.global.data.size(); ++i) {
        ASSERT_TRUE(std::isfinite(edge.global.data[i]));
        sumUnit += unit.global.data[i];
        sumEdge += edge.global.data[i];
    }
    EXPECT_GT(sumUnit, 0.0);
    EXPECT_NEAR(sumEdge / sumUnit, 1.0, 1e-2);
}

TEST(HostileInput, LightPositionsOutsideTheRangeNeverReachTheScene) {
    Scene scene = parseScene(openRoom(1, 1), "scene.json", "");  // a fixed light: no light region
    const Vec3 before = scene.lightPosition();
    EXPECT_FALSE(lightPlacementProblem(scene.lights[0], Vec3(1e30f, 0, 0)).empty());
    EXPECT_TRUE(lightPlacementProblem(scene.lights[0], Vec3(1e8f, 0, 0)).empty());
    // The workbench and scripts move lights through clampToLightRegion.
    const Vec3 kept = clampToLightRegion(scene, Vec3(1e30f, 0, 0));
    EXPECT_EQ(kept.x, before.x);
    // A project's override is ignored with a warning naming the entry and the range.
    SceneOverrides o;
    o.lightPosition = Vec3(1e30f, 0, 0);
    std::vector<std::string> problems;
    applySceneOverrides(o, scene, problems);
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_TRUE(contains(problems[0], "/scene_overrides/light_position")) << problems[0];
    EXPECT_TRUE(contains(problems[0], "[-1e+09, 1e+09]")) << problems[0];
    EXPECT_EQ(scene.lightPosition().x, before.x);
}

TEST(HostileInput, NumberBeyondDoubleNamesTheFileAndLine) {
    try {
        parseJsonText("{\n  \"camera\": {\n    \"fov_y\": 1e400\n  }\n}", "scene.json");
        FAIL() << "1e400 parsed";
    } catch (const InputError& e) {
        const std::string msg = e.what();
        EXPECT_TRUE(contains(msg, "scene.json")) << msg;
        EXPECT_TRUE(contains(msg, "1e400 at line 3, column 14")) << msg;
        EXPECT_TRUE(contains(msg, "1.8e308")) << msg;
        EXPECT_FALSE(contains(msg, "json.exception")) << msg;
    }
}

TEST(HostileInput, IntegersBeyondInt64AreRefusedNotCast) {
    const json doc = json::parse(R"({"a": 1e300, "b": 9223372036854775808.0, "c": -1e300})");
    const JsonReader r(doc, "f.json");
    for (const char* key : {"a", "b", "c"}) {
        try {
            r.at(key).integer(std::numeric_limits<int64_t>::min(), std::numeric_limits<int64_t>::max());
            FAIL() << key << " was accepted";
        } catch (const InputError& e) {
            EXPECT_TRUE(contains(e.what(), "f.json: /" + std::string(key) + ": integer")) << e.what();
            EXPECT_TRUE(contains(e.what(), "out of range")) << e.what();
        }
    }
}

// 2^63 and beyond, written as integers: nlohmann keeps 2^63..2^64-1 as unsigned and turns 2^64 and
// integers below -2^63 into doubles; none fits int64, and none may reach a float→int cast (UBSan's
// job checks). -2^63-1 itself would round to the double -2^63, a valid int64; -(2^63 + 2^11) is the
// next double below it.
TEST(HostileInput, IntegersFrom2To63OnNameFileFieldAndRange) {
    const json doc = json::parse(R"({"two63": 9223372036854775808, "max64": 18446744073709551615,
                                     "two64": 18446744073709551616, "below": -9223372036854777856,
                                     "e19": 1e19, "fits": 9223372036854775807, "least": -9223372036854775808})");
    const JsonReader r(doc, "f.json");
    const int64_t lo = std::numeric_limits<int64_t>::min(), hi = std::numeric_limits<int64_t>::max();
    const std::string range = " out of range [-9223372036854775808, 9223372036854775807]";
    const std::pair<const char*, const char*> refused[] = {{"two63", "9223372036854775808"},
                                                           {"max64", "18446744073709551615"},
                                                           {"two64", "1.8446744073709552e+19"},
                                                           {"below", "-9.223372036854778e+18"},
                                                           {"e19", "1e+19"}};
    for (const auto& [key, shown] : refused) {
        try {
            r.at(key).integer(lo, hi);
            FAIL() << key << " was accepted";
        } catch (const InputError& e) {
            EXPECT_TRUE(contains(e.what(), "f.json: /" + std::string(key) + ": integer " + shown + range)) << e.what();
        }
    }
    try {
        r.at("two63").integer(0, 100);
        FAIL() << "2^63 accepted in [0, 100]";
    } catch (const InputError& e) {
        EXPECT_TRUE(contains(e.what(), "f.json: /two63: integer 9223372036854775808 out of range [0, 100]")) << e.what();
    }
    EXPECT_EQ(r.at("fits").integer(lo, hi), hi);
    EXPECT_EQ(r.at("least").integer(lo, hi), lo);
}

TEST(HostileInput, MalformedDatasetHeadersNameTheFileAndField) {
    const fs::path dir = testDir();
    struct Case {
        std::string name, expect;
        std::function<void(json&)> edit;
    };
    const std::vector<Case> cases = {
        {"17-digit scene hash", ": /scene_hash: malformed dataset header: expected a hexadecimal number of 1 to 16 digits",
         [](json& h) { h["scene_hash"] = "12345678901234567"; }},
        {"no settings", ": malformed dataset header: missing required field 'settings'", [](json& h) { h.erase("settings"); }},
        {"string in records_per_cell", ": /stats/records_per_cell/0: malformed dataset header: expected non-negative integer",
         [](json& h) { h["stats"]["records_per_cell"] = {"many"}; }},
        {"floats_per_record 2e9", ": /floats_per_record: inconsistent record layout in header: floats_per_record is 2000000000",
         [](json& h) { h["floats_per_record"] = 2000000000; }},
        {"floats_per_record 1e300", ": /floats_per_record: malformed dataset header: integer 1e+300 out of range",
         [](json& h) { h["floats_per_record"] = 1e300; }},
        {"shard cell 1e300", ": /shard/cell_end: malformed dataset header: integer 1e+300 out of range",
         [](json& h) { h["shard"]["cell_end"] = 1e300; }},
    };
    for (const Case& c : cases) {
        json h = emptyDatasetHeader();
        c.edit(h);
        const std::string msg = datasetError(dir, h.dump());
        EXPECT_TRUE(contains(msg, (dir / "d.rrfd").string() + c.expect)) << c.name << ": " << msg;
        EXPECT_FALSE(contains(msg, "json.exception")) << c.name << ": " << msg;
    }
    // A number beyond double in the header.
    std::string text = emptyDatasetHeader().dump();
    text.replace(text.find("\"floats_per_record\":2"), 21, "\"floats_per_record\":1e400");
    const std::string msg = datasetError(dir, text);
    EXPECT_TRUE(contains(msg, "number 1e400 at line 1")) << msg;
    // The unchanged header opens: the cases above fail for their one field.
    EXPECT_EQ(datasetError(dir, emptyDatasetHeader().dump()), "");
    fs::remove_all(dir);
}

TEST(HostileInput, MemoryEstimatesRefuseWithTheEstimateInTheMessage) {
    EXPECT_EQ(formatBytes(100), "100 bytes");
    EXPECT_EQ(formatBytes(1536), "1.5 KiB");
    EXPECT_EQ(formatBytes(uint64_t(3) << 30), "3.0 GiB");
    EXPECT_EQ(memoryShortfall(1000, 1000, "x"), "");
    EXPECT_EQ(memoryShortfall(uint64_t(3) << 30, uint64_t(1) << 30, "3 records"),
              "needs about 3.0 GiB of memory (3 records), but only 1.0 GiB is available");
    // Products of absurd sizes saturate instead of wrapping to something small.
    EXPECT_EQ(saturatingProduct(uint64_t(1) << 40, uint64_t(1) << 40), std::numeric_limits<uint64_t>::max());
    EXPECT_EQ(saturatingProduct(3, 5, 7), 105u);
    // A render holds at least its two copies of the per-pixel sums.
    EXPECT_GE(renderMemoryBytes(16384, 16384), uint64_t(16384) * 16384 * 2 * sizeof(PixelSums));
    EXPECT_GT(availableMemoryBytes(), 0u);
}

TEST(HostileInput, ObjectsWithoutRecordsWriteAndReadBack) {
    // One viewpoint, three directions: most objects of the room get no record (an empty vector,
    // whose data() may be null, goes through the checksum and the writer).
    const fs::path dir = testDir();
    const Scene scene = parseScene(openRoom(1, 1), "scene.json", "");
    SamplingSettings s;
    s.nx = s.ny = s.nz = 1;
    s.directions = 3;
    s.spp = s.maxSpp = 1;
    const DataGenerator gen(scene, s);
    const GeneratedData d = gen.run();
    size_t empty = 0;
    for (const auto& v : d.perObject) empty += v.empty();
    ASSERT_GE(empty, 2u);
    const std::string path = (dir / "few.rrfd").string();
    writeDataset(path, datasetHeader(d), d.sceneHash, d.perObject);
    const Dataset back(path);
    uint64_t total = 0;
    for (const auto& v : d.perObject) total += v.size() / size_t(gen.layout().floatsPerRecord());
    EXPECT_EQ(back.totalRecords(), total);
    fs::remove_all(dir);
}

TEST(HostileInput, CancelStopsWithinOneCellOfMillionsOfDirections) {
    // One cell with 2 million directions: a cancel checked per cell would wait for all of them.
    const Scene scene = parseScene(openRoom(1, 1), "scene.json", "");
    SamplingSettings s;
    s.nx = s.ny = s.nz = 1;
    s.directions = 2000000;
    s.spp = s.maxSpp = 4;
    const DataGenerator gen(scene, s);
    std::atomic<bool> cancel{false};
    GeneratorProgress progress;
    std::chrono::steady_clock::time_point cancelledAt;
    // 8 million paths: seconds even on a fast machine, so the cancel at 200 ms finds the cell running
    // (progress counts records only per finished cell, so it cannot trigger the cancel).
    std::thread stopper([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
        cancelledAt = std::chrono::steady_clock::now();
        cancel = true;
    });
    const GeneratedData d = gen.run(0, 1, &cancel, &progress);
    const auto returned = std::chrono::steady_clock::now();
    stopper.join();
    EXPECT_TRUE(d.cancelled);
    EXPECT_EQ(progress.cellsDone.load(), 1u);
    EXPECT_LT(std::chrono::duration<double>(returned - cancelledAt).count(), 1.0);
    for (const auto& v : d.perObject) EXPECT_TRUE(v.empty());
}

TEST(HostileInput, EveryRecordNonFiniteIsRefusedNamingTheScene) {
    // A bulb of intensity 3e38 in a room of half-size 0.1: every wall point receives
    // I cos θ / d² > 3e38 / 0.03 · 0.58, beyond float, so every sample is infinite. The scene
    // reader refuses such a bulb (RadiometricRange tests); set behind its back, it checks the
    // generator's own guard against scenes built in code.
    Scene scene = parseScene(openRoom(0.1, 1), "scene.json", "");
    scene.lights[0].intensity = Vec3(3e38f);
    SamplingSettings s;
    s.nx = s.ny = s.nz = 2;
    s.directions = 8;
    s.spp = s.maxSpp = 2;
    const DataGenerator gen(scene, s);
    try {
        gen.run();
        FAIL() << "a dataset without a finite sample was produced";
    } catch (const InputError& e) {
        EXPECT_TRUE(contains(e.what(), "scene.json: every sample of every record was NaN or infinite")) << e.what();
    }
}

TEST(HostileInput, UnknownKeysInMaterialOverridesWarnAndKeepTheRest) {
    const json doc = json::parse(R"({"materials": {"white": {"kd": [0.5, 0.4, 0.3], "albedo": [1, 1, 1]}}})");
    std::vector<std::string> warnings;
    const SceneOverrides o = sceneOverridesFromJson(JsonReader(doc, "project.json", "/scene_overrides"), warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_TRUE(contains(warnings[0], "project.json: /scene_overrides/materials/white/albedo: unknown key 'albedo'"))
        << warnings[0];
    ASSERT_EQ(o.materials.count("white"), 1u);
    EXPECT_FLOAT_EQ(o.materials.at("white").kd->y, 0.4f);
}

TEST(HostileInput, ObjFileThatIsNotARegularFileIsRefused) {
    json scene = openRoom(1, 1);
    scene["shapes"].push_back({{"type", "obj"}, {"name", "zeros"}, {"material", "white"}, {"file", "/dev/zero"}});
    const std::string msg = sceneError(scene);
    EXPECT_TRUE(contains(msg, "scene.json: /shapes/5/file: OBJ file '/dev/zero' is not a regular file")) << msg;
}

}  // namespace test_hostile_input
