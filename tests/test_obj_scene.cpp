// Scenes whose shapes come from an OBJ file with its MTL library: objects per group (or per
// material), Lambert/Phong materials from Kd/Ks/Ns (clamped to energy conservation), area lights
// from Ke (a parallelogram quad → rect light, other faces → triangle lights), vertex normals, the
// derived light region, JSON overrides, and errors that name the OBJ line.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "core/scene/accel.h"
#include "core/scene/effects.h"
#include "core/scene/scene_json.h"
#include "core/util/error.h"

namespace test_obj_scene {

using namespace rrf;
using nlohmann::json;

namespace {

/// A directory per test: CTest runs the tests of this file in parallel processes, and a shared
/// directory let one test's room.obj meet another's room.mtl half-written.
std::string tempDir() {
    const std::string dir = ::testing::TempDir() + "rrf_obj_scene_tests_" +
                            ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::filesystem::create_directories(dir);
    return dir;
}

void writeFile(const std::string& name, const std::string& text) { std::ofstream(tempDir() + "/" + name) << text; }

const char* const kMtl = R"(newmtl white
Kd 0.8 0.8 0.8
newmtl red
Kd 0.6 0.1 0.1
newmtl shiny
Kd 0.5 0.5 0.5
Ks 0.7 0.7 0.7
Ns 100
newmtl lamp
Kd 0 0 0
Ke 10 8 6
)";

// Line numbers matter: the error tests below refer to them.
const char* const kObj = R"(mtllib room.mtl
v -1 0 -1
v 1 0 -1
v 1 0 1
v -1 0 1
v -0.2 0.99 -0.2
v 0.2 0.99 -0.2
v 0.2 0.99 0.2
v -0.2 0.99 0.2
v 0.5 0.5 0.5
v 0.7 0.5 0.5
v 0.6 0.7 0.5
v 0.5 0.99 0.5
v 0.6 0.99 0.5
v 0.5 0.99 0.6
vn 0 0 1
vn 0 0.6 0.8
g floor
usemtl white
f 1 4 3 2
g ball
usemtl shiny
f 9//1 10//1 11//2
g lamp
usemtl lamp
f 5 6 7 8
f 12 13 14
g mixed
usemtl white
f 1 2 11
usemtl red
f 2 3 11
)";

json sceneWith(const json& objShape) {
    return json{{"camera", {{"eye", {0, 0.5, 4}}, {"target", {0, 0.5, 0}}, {"fov_y", 40}, {"width", 16}, {"height", 16}}},
                {"shapes", json::array({objShape})}};
}

Scene load(const json& doc) {
    const std::string path = tempDir() + "/scene.json";
    std::ofstream(path) << doc.dump(1);
    return loadScene(path);
}

const Object& objectNamed(const Scene& s, const std::string& name) {
    for (const Object& o : s.objects)
        if (o.name == name) return o;
    throw std::runtime_error("no object '" + name + "'");
}

std::string errorOf(const json& doc) {
    try {
        load(doc);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

// Outside the anonymous namespace: the TEST_F classes derive from it (GCC warns otherwise when the
// file is part of a unity batch); namespace test_obj_scene keeps the name unique.
class ObjScene : public ::testing::Test {
protected:
    void SetUp() override {
        writeFile("room.mtl", kMtl);
        writeFile("room.obj", kObj);
    }
};

TEST_F(ObjScene, GroupsBecomeObjectsWithTheirMaterials) {
    const Scene s = load(sceneWith({{"type", "obj"}, {"file", "room.obj"}}));
    std::vector<std::string> names;
    for (const Object& o : s.objects) names.push_back(o.name);
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"ball", "floor", "mixed.red", "mixed.white"}));
    for (size_t i = 0; i < s.objects.size(); ++i) EXPECT_EQ(s.objects[i].id, int(i));

    const Object& floor = objectNamed(s, "floor");
    EXPECT_EQ(floor.kind, Object::Kind::Triangles);
    EXPECT_EQ(floor.primitiveCount(), 2u) << "the quad is split into two triangles";
    EXPECT_TRUE(floor.normals.empty()) << "no vn: flat shading";
    const Material& white = s.materials[size_t(floor.material)];
    EXPECT_EQ(white.name, "white");
    EXPECT_EQ(white.type, Material::Type::Lambert);
    EXPECT_FLOAT_EQ(white.kd.x, 0.8f);

    // Kd + Ks = 1.2 > 1: both scaled by 1/1.2, with a warning naming the material.
    const Material& shiny = s.materials[size_t(objectNamed(s, "ball").material)];
    EXPECT_EQ(shiny.type, Material::Type::Phong);
    EXPECT_NEAR(shiny.kd.x, 0.5 / 1.2, 1e-6);
    EXPECT_NEAR(shiny.ks.x, 0.7 / 1.2, 1e-6);
    EXPECT_FLOAT_EQ(shiny.exponent, 100.f);
    EXPECT_TRUE(std::any_of(s.warnings.begin(), s.warnings.end(), [](const std::string& w) {
        return w.find("'shiny'") != std::string::npos && w.find("energy conservation") != std::string::npos;
    }));
    EXPECT_EQ(s.materials[size_t(objectNamed(s, "mixed.red").material)].name, "red");

    // The ball's vertex normals (vn 1 and 2, unit length) are kept per vertex.
    const Object& ball = objectNamed(s, "ball");
    ASSERT_EQ(ball.normals.size(), ball.positions.size());
    EXPECT_NEAR(ball.normals[2].y, 0.6f, 1e-6);

    const Effects e = Effects::derive(s);
    EXPECT_TRUE(e.glossy);
    EXPECT_TRUE(e.rectLights);
    EXPECT_TRUE(e.triangleLights);
    EXPECT_DOUBLE_EQ(e.maxPhongExponent, 100.0);
}

TEST_F(ObjScene, EmittersBecomeRectAndTriangleLightsWithARegion) {
    const Scene s = load(sceneWith({{"type", "obj"}, {"file", "room.obj"}}));
    ASSERT_EQ(s.lights.size(), 2u);
    const Light& quad = s.lights[0];
    const Light& tri = s.lights[1];
    EXPECT_EQ(quad.name, "lamp.0");
    EXPECT_EQ(quad.type, Light::Type::Rect);
    EXPECT_NEAR(quad.area(), 0.16f, 1e-6);
    EXPECT_EQ(quad.radiance, Vec3(10, 8, 6));
    EXPECT_LT(quad.normal().y, -0.99f) << "f 5 6 7 8 winds towards -y: the lamp faces the floor";
    EXPECT_EQ(tri.type, Light::Type::Triangle);
    EXPECT_NEAR(tri.area(), 0.005f, 1e-6);
    EXPECT_EQ(s.movableLight, 0) << "the emitter of largest power moves";
    // The lamp's own faces are not geometry: no object "lamp".
    for (const Object& o : s.objects) EXPECT_NE(o.name, "lamp");
    // Region (light_region.h): from the centre down a quarter of the room's height (0.99 · 0.25),
    // across twice the half-size (±0.4), inside the room shrunk by the lamp's half-size (±0.8).
    const Bounds3& r = s.lightRegion;
    EXPECT_NEAR(r.hi.y, 0.99f, 1e-6);
    EXPECT_NEAR(r.lo.y, 0.99f - 0.25f * 0.99f, 1e-5);
    EXPECT_NEAR(r.lo.x, -0.4f, 1e-6);
    EXPECT_NEAR(r.hi.z, 0.4f, 1e-6);
    EXPECT_TRUE(r.contains(quad.center()));
}

TEST_F(ObjScene, MillimetreSceneScalesTheRegion) {
    const Scene m = load(sceneWith({{"type", "obj"}, {"file", "room.obj"}}));
    const Scene mm = load(sceneWith({{"type", "obj"}, {"file", "room.obj"}, {"transform", {{"scale", 1000}}}}));
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(mm.lightRegion.lo[i], 1000 * m.lightRegion.lo[i], 1e-2);
        EXPECT_NEAR(mm.lightRegion.hi[i], 1000 * m.lightRegion.hi[i], 1e-2);
    }
    EXPECT_NEAR(mm.lights[0].area(), 1e6f * m.lights[0].area(), 1.f);
    // Vertex normals stay unit under the scale.
    EXPECT_NEAR(length(objectNamed(mm, "ball").normals[0]), 1.f, 1e-6);
}

TEST_F(ObjScene, ShadingNormalsAreInterpolated) {
    const Scene s = load(sceneWith({{"type", "obj"}, {"file", "room.obj"}}));
    const Accel accel(s);
    // The ball triangle lies in z = 0.5 (normal +z); its third vertex has normal (0, 0.6, 0.8).
    // A ray at the third vertex's side sees an interpolated normal tilted towards +y.
    Ray ray;
    ray.origin = Vec3(0.6f, 0.65f, 3.f);
    ray.dir = Vec3(0, 0, -1);
    Hit hit;
    ASSERT_TRUE(accel.intersect(ray, hit));
    ASSERT_EQ(s.objects[size_t(hit.object)].name, "ball");
    EXPECT_NEAR(hit.ng.z, 1.f, 1e-6);
    const Vec3 ns = hit.shading();
    EXPECT_GT(ns.y, 0.3f);
    EXPECT_NEAR(length(ns), 1.f, 1e-5);
    // Barycentric weight of vertex 3 at y = 0.65 is 0.75: n ∝ 0.25·(0,0,1) + 0.75·(0,0.6,0.8).
    EXPECT_NEAR(ns.y / ns.z, 0.45f / 0.85f, 1e-4);
}

TEST_F(ObjScene, SplitByMaterial) {
    const Scene s = load(sceneWith({{"type", "obj"}, {"file", "room.obj"}, {"split", "materials"}}));
    std::vector<std::string> names;
    for (const Object& o : s.objects) names.push_back(o.name);
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"red", "shiny", "white"}));
    EXPECT_EQ(objectNamed(s, "white").primitiveCount(), 3u) << "floor's two triangles and mixed's white one";
}

TEST_F(ObjScene, JsonEntriesOverride) {
    json doc = sceneWith({{"type", "obj"}, {"file", "room.obj"}});
    doc["materials"] = {{"white", {{"type", "lambert"}, {"albedo", {0.3, 0.3, 0.3}}}}};
    doc["lights"] = json::array({{{"type", "point"}, {"position", {0, 0.5, 0}}, {"intensity", {1, 1, 1}}}});
    doc["light_region"] = {{"min", {-0.1, 0.4, -0.1}}, {"max", {0.1, 0.6, 0.1}}};
    const Scene s = load(doc);
    EXPECT_FLOAT_EQ(s.materials[size_t(objectNamed(s, "floor").material)].kd.x, 0.3f) << "JSON 'white' wins";
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].type, Light::Type::Point);
    EXPECT_NEAR(s.lightRegion.hi.y, 0.6f, 1e-6);
    // The lamp's faces stay as a black surface, with a warning.
    EXPECT_FLOAT_EQ(s.materials[size_t(objectNamed(s, "lamp").material)].kd.x, 0.f);
    EXPECT_TRUE(std::any_of(s.warnings.begin(), s.warnings.end(),
                            [](const std::string& w) { return w.find("replace the OBJ's emitters") != std::string::npos; }));
    // A "material" on the shape: one object, the MTL unread (the pre-MTL form).
    json one = sceneWith({{"type", "obj"}, {"file", "room.obj"}, {"name", "all"}, {"material", "white"}});
    one["materials"] = doc["materials"];
    one["lights"] = doc["lights"];
    const Scene t = load(one);
    ASSERT_EQ(t.objects.size(), 1u);
    EXPECT_EQ(t.objects[0].name, "all");
    EXPECT_EQ(t.objects[0].primitiveCount(), 2u + 1u + 2u + 1u + 1u + 1u);
}

TEST_F(ObjScene, ErrorsNameTheObjLine) {
    writeFile("bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n# comment\nf 1 2 3\nf 1 2 9\n");
    std::string e = errorOf(sceneWith({{"type", "obj"}, {"file", "bad_index.obj"}}));
    EXPECT_NE(e.find("bad_index.obj' line 6"), std::string::npos) << e;
    EXPECT_NE(e.find("vertex index 9"), std::string::npos) << e;
    EXPECT_NE(e.find("/shapes/0/file"), std::string::npos) << e;

    writeFile("no_mtl.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nmtllib missing.mtl\nusemtl white\nf 1 2 3\n");
    e = errorOf(sceneWith({{"type", "obj"}, {"file", "no_mtl.obj"}}));
    EXPECT_NE(e.find("no_mtl.obj' line 4"), std::string::npos) << e;
    EXPECT_NE(e.find("'missing.mtl' not found"), std::string::npos) << e;

    writeFile("unknown_mtl.obj", "mtllib room.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl chrome\nf 1 2 3\n");
    e = errorOf(sceneWith({{"type", "obj"}, {"file", "unknown_mtl.obj"}}));
    EXPECT_NE(e.find("unknown_mtl.obj' line 5: usemtl 'chrome'"), std::string::npos) << e;

    writeFile("zero_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
    e = errorOf(sceneWith({{"type", "obj"}, {"file", "zero_index.obj"}}));
    EXPECT_NE(e.find("line 4: vertex index 0"), std::string::npos) << e;

    writeFile("bad_normal.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n");
    e = errorOf(sceneWith({{"type", "obj"}, {"file", "bad_normal.obj"}}));
    EXPECT_NE(e.find("line 5: normal index 2"), std::string::npos) << e;
}

TEST_F(ObjScene, FacesWithoutMaterialGetTheDefault) {
    // No mtllib at all: nothing to miss; faces get 'default' (Lambert 0.5), with a warning.
    writeFile("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const Scene s = load(sceneWith({{"type", "obj"}, {"file", "plain.obj"}}));
    ASSERT_EQ(s.objects.size(), 1u);
    EXPECT_EQ(s.objects[0].name, "plain") << "faces before any g/o are named after the file";
    const Material& m = s.materials[size_t(s.objects[0].material)];
    EXPECT_EQ(m.name, "default");
    EXPECT_FLOAT_EQ(m.kd.x, 0.5f);
    EXPECT_TRUE(s.lights.empty());
}

TEST_F(ObjScene, MirroredLampStaysOneRectFacingTheFloor) {
    // A mirroring transform swaps the winding back; the lamp quad must still be recognised as one
    // parallelogram (one movable rect light), not two triangles, and still face -y.
    const Scene s = load(sceneWith({{"type", "obj"}, {"file", "room.obj"}, {"transform", {{"scale", {-1, 1, 1}}}}}));
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[0].type, Light::Type::Rect);
    EXPECT_NEAR(s.lights[0].area(), 0.16f, 1e-6);
    EXPECT_LT(s.lights[0].normal().y, -0.99f);
    EXPECT_LT(s.lights[1].normal().y, 0.f) << "the triangle lamp keeps its side too";
}

TEST_F(ObjScene, LightNamesStayUniqueAcrossShapes) {
    // Three OBJ shapes whose only faces are the same emitting triangle: their lights get distinct names.
    writeFile("lamp.obj", "mtllib room.mtl\nv 0 0.99 0\nv 0.1 0.99 0\nv 0 0.99 0.1\ng lamp\nusemtl lamp\nf 1 3 2\n");
    json doc = sceneWith({{"type", "obj"}, {"file", "lamp.obj"}});
    doc["shapes"].push_back({{"type", "obj"}, {"file", "lamp.obj"}, {"transform", {{"translate", {0.2, 0, 0}}}}});
    doc["shapes"].push_back({{"type", "obj"}, {"file", "lamp.obj"}, {"transform", {{"translate", {0.4, 0, 0}}}}});
    doc["shapes"].push_back({{"type", "obj"}, {"file", "room.obj"}});
    const Scene s = load(doc);
    std::set<std::string> names;
    for (const Light& l : s.lights) EXPECT_TRUE(names.insert(l.name).second) << "repeated light name " << l.name;
    EXPECT_EQ(s.lights.size(), 5u);
}

}  // namespace test_obj_scene
