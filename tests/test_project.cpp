#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/project/project.h"

using namespace rrf;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const std::string kCornellDir = std::string(RRF_SOURCE_DIR) + "/projects/cornell-box";

/// A fresh directory per test so saved files never leak between tests.
std::string freshDir(const std::string& name) {
    const fs::path dir = fs::path(::testing::TempDir()) / "rrf_project_tests" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir.string();
}

std::string writeText(const std::string& path, const std::string& text) {
    std::ofstream(path) << text;
    return path;
}

std::string loadError(const std::string& path) {
    try {
        loadProjectOrScene(path);
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << path << " loaded although it is invalid";
    return "";
}

/// A small embedded scene that loads an OBJ file by relative path.
json embeddedScene() {
    return json::parse(R"({
      "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "fov_y": 45},
      "materials": {"grey": {"type": "lambert", "albedo": [0.5, 0.5, 0.5]}},
      "shapes": [{"type": "obj", "name": "pyramid", "material": "grey", "file": "mesh/pyramid.obj"}],
      "lights": [{"type": "point", "position": [0, 3, 0], "intensity": [1, 1, 1]}]
    })");
}

}  // namespace

TEST(Project, LoadsCornellProject) {
    const Project p = loadProjectOrScene(kCornellDir + "/project.json");
    EXPECT_EQ(p.sceneRef, "scene.json");
    EXPECT_EQ(p.render.spp, 64);
    EXPECT_EQ(p.render.estimator, Estimator::NEE);
    EXPECT_EQ(p.render.width, 0);
    EXPECT_EQ(p.scene.objects.size(), 7u);
    EXPECT_EQ(p.scene.sourcePath, kCornellDir + "/scene.json");
    EXPECT_EQ(p.doc["name"], "Cornell box");
}

TEST(Project, RoundTripKeepsUnknownSectionsAndRebasesSceneRef) {
    Project p = loadProjectOrScene(kCornellDir + "/project.json");
    p.doc["network"] = {{"hidden", {20, 10}}, {"activation", "tanh"}};
    p.doc["runs"] = json::array({{{"id", 3}, {"rmse", 0.125}}});
    p.doc["layout"] = {{"left", 0.25}};
    p.render.spp = 256;
    p.render.estimator = Estimator::Naive;
    p.render.seed = 18446744073709551615ULL;
    p.render.exposure = -1.5f;
    p.render.width = 128;

    const std::string dir = freshDir("roundtrip");
    const std::string out = dir + "/sub/copy.json";
    fs::create_directories(dir + "/sub");
    saveProject(p, out);
    EXPECT_EQ(p.path, out);

    const std::string text = readFile(out);
    EXPECT_NE(text.find("\n  \"network\": {\n    \""), std::string::npos) << "expected 2-space indentation:\n" << text;
    for (const auto& entry : fs::directory_iterator(dir + "/sub"))
        EXPECT_EQ(entry.path().extension(), ".json") << "left behind: " << entry.path();

    const Project q = loadProjectOrScene(out);
    EXPECT_FALSE(fs::path(q.sceneRef).is_absolute()) << q.sceneRef;
    EXPECT_TRUE(fs::equivalent(fs::path(out).parent_path() / q.sceneRef, kCornellDir + "/scene.json")) << q.sceneRef;
    EXPECT_EQ(q.scene.objects.size(), 7u);
    EXPECT_EQ(q.render.spp, 256);
    EXPECT_EQ(q.render.estimator, Estimator::Naive);
    EXPECT_EQ(q.render.seed, 18446744073709551615ULL);
    EXPECT_FLOAT_EQ(q.render.exposure, -1.5f);
    EXPECT_EQ(q.render.width, 128);
    EXPECT_EQ(q.render.maxDepth, 64);
    EXPECT_EQ(q.doc["network"], p.doc["network"]);
    EXPECT_EQ(q.doc["runs"], p.doc["runs"]);
    EXPECT_EQ(q.doc["layout"], p.doc["layout"]);
    EXPECT_EQ(q.doc["name"], "Cornell box");
}

TEST(Project, BareSceneGetsDefaultSettings) {
    Project p = loadProjectOrScene(kCornellDir + "/scene.json");
    EXPECT_EQ(p.scene.objects.size(), 7u);
    EXPECT_EQ(p.sceneRef, "scene.json");
    EXPECT_EQ(p.render.spp, RenderSettings().spp);
    EXPECT_EQ(p.doc["rrf_project"], 1);
    // Saving over the scene file itself would destroy it.
    EXPECT_THROW(saveProject(p, kCornellDir + "/scene.json"), std::runtime_error);

    const std::string dir = freshDir("bare");
    saveProject(p, dir + "/project.json");
    const Project q = loadProjectOrScene(dir + "/project.json");
    EXPECT_EQ(q.scene.contentHash(), p.scene.contentHash());
}

TEST(Project, EmbeddedSceneRebasesObjPathsOnSave) {
    const std::string dir = freshDir("embedded");
    fs::create_directories(dir + "/a/mesh");
    fs::create_directories(dir + "/b");
    fs::copy_file(std::string(RRF_SOURCE_DIR) + "/tests/data/pyramid.obj", dir + "/a/mesh/pyramid.obj");
    const json doc = {{"rrf_project", 1}, {"scene", embeddedScene()}, {"trainer", {{"type", "lm"}}}};
    const std::string first = writeText(dir + "/a/project.json", doc.dump(2));

    Project p = loadProjectOrScene(first);
    EXPECT_TRUE(p.sceneRef.empty());
    EXPECT_EQ(p.scene.objects[0].primitiveCount(), 6u);
    saveProject(p, dir + "/b/moved.json");
    EXPECT_EQ(p.sceneJson["shapes"][0]["file"], "../a/mesh/pyramid.obj");

    const Project q = loadProjectOrScene(dir + "/b/moved.json");
    EXPECT_EQ(q.scene.contentHash(), p.scene.contentHash());
    EXPECT_EQ(q.doc["trainer"]["type"], "lm");
}

TEST(Project, EmbeddedSceneErrorsPointIntoProject) {
    const std::string dir = freshDir("embedded_error");
    json scene = embeddedScene();
    scene["materials"]["grey"]["albedo"] = "grey";
    const std::string path = writeText(dir + "/broken.json", json{{"rrf_project", 1}, {"scene", scene}}.dump());
    const std::string msg = loadError(path);
    EXPECT_NE(msg.find("broken.json: /scene/materials/grey/albedo: expected array of 3 numbers, got string"),
              std::string::npos)
        << msg;
}

TEST(Project, MissingSceneFile) {
    const std::string dir = freshDir("missing_scene");
    const std::string path = writeText(dir + "/p.json", R"({"rrf_project": 1, "scene": "nowhere.json"})");
    const std::string msg = loadError(path);
    EXPECT_NE(msg.find("p.json: /scene: cannot open scene file"), std::string::npos) << msg;
    EXPECT_NE(msg.find("nowhere.json"), std::string::npos) << msg;
}

TEST(Project, RenderSectionIsValidated) {
    const std::string dir = freshDir("render");
    const std::string scene = kCornellDir + "/scene.json";
    auto project = [&](const json& render) {
        return writeText(dir + "/r.json", json{{"rrf_project", 1}, {"scene", scene}, {"render", render}}.dump());
    };
    std::string msg = loadError(project({{"sppp", 4}}));
    EXPECT_NE(msg.find("r.json: /render/sppp: unknown key 'sppp'"), std::string::npos) << msg;
    msg = loadError(project({{"mode", "bidir"}}));
    EXPECT_NE(msg.find("r.json: /render/mode: unknown render mode 'bidir'"), std::string::npos) << msg;
    msg = loadError(project({{"spp", 0}}));
    EXPECT_NE(msg.find("r.json: /render/spp: integer 0 out of range"), std::string::npos) << msg;
    msg = loadError(project({{"seed", -1}}));
    EXPECT_NE(msg.find("r.json: /render/seed: expected non-negative integer"), std::string::npos) << msg;
}

TEST(Project, VersionAndKindAreChecked) {
    const std::string dir = freshDir("version");
    std::string msg = loadError(writeText(dir + "/v2.json", R"({"rrf_project": 2, "scene": "x.json"})"));
    EXPECT_NE(msg.find("v2.json: /rrf_project: unsupported project version 2"), std::string::npos) << msg;
    msg = loadError(writeText(dir + "/none.json", R"({"name": "neither"})"));
    EXPECT_NE(msg.find("none.json: neither a project"), std::string::npos) << msg;
    msg = loadError(writeText(dir + "/noversion.json", R"({"scene": "x.json"})"));
    EXPECT_NE(msg.find("noversion.json: missing required field 'rrf_project'"), std::string::npos) << msg;
}
