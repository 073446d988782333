// The bundled OBJ + MTL project (projects/mesh-room) through the real executable: `rrf inspect` and
// render.json list the OBJ's groups, MTL materials and Ke lamp by name, and the whole pipeline runs
// on it at tiny sizes (a few seconds).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "tests/cli_runner.h"

namespace test_cli_obj {

namespace fs = std::filesystem;

namespace {

const std::string kMeshRoom = std::string(RRF_SOURCE_DIR) + "/projects/mesh-room/project.json";

fs::path tempDir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("rrf_cli_obj_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

}  // namespace

TEST(CliObj, InspectListsObjectsMaterialsAndLights) {
    const rrf::test::CliResult r = rrf::test::runCli("inspect " + kMeshRoom);
    ASSERT_EQ(r.code, 0) << r.output;
    for (const char* line : {"7 objects", "left-wall: 2 triangles, material red (Lambert",
                             "ball: 320 triangles (smooth normals), material ivory", "1 lights",
                             "lamp: rect, area 0.1748", "movable", "light region: (-0.46, 0.49, -0.37) .. (0.46, 0.99, 0.39)"})
        EXPECT_NE(r.output.find(line), std::string::npos) << line << "\n" << r.output;
}

TEST(CliObj, RenderJsonListsTheSceneContents) {
    const fs::path out = tempDir("render");
    const rrf::test::CliResult r =
        rrf::test::runCli("render " + kMeshRoom + " --spp 2 --width 16 --height 16 --format pfm --out " + out.string());
    ASSERT_EQ(r.code, 0) << r.output;
    std::ifstream meta(out / "render.json");
    const nlohmann::json j = nlohmann::json::parse(meta).at("scene_contents");
    ASSERT_EQ(j.at("objects").size(), 7u);
    const nlohmann::json& ball = j.at("objects").at(6);
    EXPECT_EQ(ball.at("name"), "ball");
    EXPECT_EQ(ball.at("primitives"), 320);
    EXPECT_TRUE(ball.at("smooth_normals").get<bool>());
    EXPECT_EQ(ball.at("material").at("name"), "ivory");
    EXPECT_EQ(ball.at("material").at("type"), "lambert");
    ASSERT_EQ(j.at("lights").size(), 1u);
    EXPECT_EQ(j.at("lights").at(0).at("name"), "lamp");
    EXPECT_EQ(j.at("lights").at(0).at("type"), "rect");
    EXPECT_TRUE(j.at("lights").at(0).at("movable").get<bool>());
    EXPECT_FALSE(j.at("light_region").is_null());
    fs::remove_all(out);
}

TEST(CliObj, PipelineRunsOnTheMeshProject) {
    const fs::path out = tempDir("pipeline");
    // A copy of the project: the pipeline keeps its held-out references in the project's folder.
    const fs::path project = out / "mesh-room";
    fs::create_directories(project);
    for (const char* f : {"project.json", "scene.json", "room.obj", "room.mtl"})
        fs::copy_file(fs::path(kMeshRoom).parent_path() / f, project / f);
    const rrf::test::CliResult r = rrf::test::runCli(
        "pipeline " + (project / "project.json").string() + " --quick --width 16 --height 16 --spp 4 --spp-cap 16 --held-out 1 --grid 2,2,2 --dirs 16 "
        "--data-spp 4 --hidden 3 --epochs 2 --threads 2 --out " + (out / "run").string());
    ASSERT_EQ(r.code, 0) << r.output;
    size_t files = 0;
    for (const auto& e : fs::recursive_directory_iterator(out / "run")) files += e.is_regular_file();
    EXPECT_GT(files, 5u) << r.output;
    fs::remove_all(out);
}

}  // namespace test_cli_obj
