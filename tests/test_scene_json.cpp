#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/util/error.h"
#include "core/scene/scene_json.h"

namespace test_scene_json {

using namespace rrf;
using nlohmann::json;

namespace {

const std::string kCornell = std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/scene.json";
const std::string kData = std::string(RRF_SOURCE_DIR) + "/tests/data";

std::string tempDir() {
    const std::string dir = ::testing::TempDir() + "rrf_scene_json_tests";
    std::filesystem::create_directories(dir);
    return dir;
}

std::string writeTemp(const std::string& name, const std::string& text) {
    const std::string path = tempDir() + "/" + name;
    std::ofstream(path) << text;
    return path;
}

/// A small valid scene; each bad-input test breaks exactly one thing in it.
json validScene() {
    return json::parse(R"({
      "camera": {"eye": [0, 0, 4], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y": 40, "width": 32, "height": 24},
      "materials": {
        "white": {"type": "lambert", "albedo": [0.8, 0.8, 0.8]},
        "red": {"type": "lambert", "albedo": [0.6, 0.1, 0.1]},
        "green": {"type": "lambert", "albedo": [0.1, 0.6, 0.1]}
      },
      "shapes": [
        {"type": "quad", "name": "floor", "material": "white",
         "corner": [-1, -1, -1], "edge1": [0, 0, 2], "edge2": [2, 0, 0]}
      ],
      "lights": [
        {"type": "rect", "corner": [-0.2, 0.9, -0.2], "edge1": [0.4, 0, 0], "edge2": [0, 0, 0.4],
         "radiance": [5, 5, 5], "movable": true}
      ],
      "light_region": {"min": [-0.5, 0.5, -0.5], "max": [0.5, 0.9, 0.5]}
    })");
}

/// Loads `text` from a file named `name` and returns the InputError message ("" if it loaded).
std::string loadErrorText(const std::string& name, const std::string& text) {
    const std::string path = writeTemp(name, text);
    try {
        loadScene(path);
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << name << " loaded although it is invalid";
    return "";
}

std::string loadError(const std::string& name, const json& doc) { return loadErrorText(name, doc.dump(2)); }

/// Asserts that `msg` names the file, the JSON path and every key word.
void expectMessage(const std::string& msg, const std::string& file, const std::string& path,
                   const std::vector<std::string>& words) {
    EXPECT_NE(msg.find(file), std::string::npos) << msg;
    EXPECT_NE(msg.find(path + ":"), std::string::npos) << "path " << path << " missing in: " << msg;
    for (const std::string& w : words) EXPECT_NE(msg.find(w), std::string::npos) << "'" << w << "' missing in: " << msg;
}

Vec3 quadNormal(const Object& o, size_t q) {
    const Vec3& v0 = o.positions[o.indices[4 * q]];
    const Vec3& v1 = o.positions[o.indices[4 * q + 1]];
    const Vec3& v3 = o.positions[o.indices[4 * q + 3]];
    return normalize(cross(v1 - v0, v3 - v0));
}

const Object& byName(const Scene& s, const std::string& name) {
    for (const Object& o : s.objects)
        if (o.name == name) return o;
    throw std::runtime_error("no object " + name);
}

}  // namespace

TEST(SceneJson, CornellBoxHasObjectsInFileOrder) {
    const Scene s = loadScene(kCornell);
    EXPECT_EQ(s.sourcePath, kCornell);
    const std::vector<std::string> names = {"floor",      "ceiling",   "back-wall", "left-wall",
                                            "right-wall", "short-box", "tall-box"};
    ASSERT_EQ(s.objects.size(), names.size());
    for (size_t i = 0; i < names.size(); ++i) {
        EXPECT_EQ(s.objects[i].id, int(i));
        EXPECT_EQ(s.objects[i].name, names[i]);
        EXPECT_EQ(s.objects[i].kind, Object::Kind::Quads);
    }
    for (size_t i = 0; i < 5; ++i) {
        EXPECT_EQ(s.objects[i].primitiveCount(), 1u);
        EXPECT_FALSE(s.objects[i].closed);
    }
    EXPECT_EQ(s.objects[5].primitiveCount(), 6u);
    EXPECT_TRUE(s.objects[5].closed);
    EXPECT_EQ(s.objects[6].primitiveCount(), 6u);
    EXPECT_TRUE(s.warnings.empty());
}

TEST(SceneJson, CornellBoxAlbedos) {
    const Scene s = loadScene(kCornell);
    ASSERT_EQ(s.materials.size(), 3u);
    auto albedo = [&](const std::string& object) { return s.materials[size_t(byName(s, object).material)].kd; };
    const Vec3 white(0.885809f, 0.698859f, 0.666422f), red(0.570068f, 0.0430135f, 0.0443706f),
        green(0.105421f, 0.37798f, 0.076425f);
    for (const char* w : {"floor", "ceiling", "back-wall", "short-box", "tall-box"}) EXPECT_EQ(albedo(w), white) << w;
    EXPECT_EQ(albedo("left-wall"), red);
    EXPECT_EQ(albedo("right-wall"), green);
    for (const Material& m : s.materials) {
        EXPECT_EQ(m.type, Material::Type::Lambert);
        EXPECT_EQ(m.ks, Vec3(0.f));
    }
}

TEST(SceneJson, CornellBoxWallsFaceInward) {
    const Scene s = loadScene(kCornell);
    EXPECT_EQ(quadNormal(byName(s, "floor"), 0), Vec3(0, 1, 0));
    EXPECT_EQ(quadNormal(byName(s, "ceiling"), 0), Vec3(0, -1, 0));
    EXPECT_EQ(quadNormal(byName(s, "back-wall"), 0), Vec3(0, 0, 1));
    EXPECT_EQ(quadNormal(byName(s, "left-wall"), 0), Vec3(1, 0, 0));
    EXPECT_EQ(quadNormal(byName(s, "right-wall"), 0), Vec3(-1, 0, 0));
    const Bounds3 b = s.bounds();
    EXPECT_EQ(b.lo, Vec3(-1, -1.01f, -1));
    EXPECT_EQ(b.hi, Vec3(1, 1, 1));
}

TEST(SceneJson, CornellBoxLightAndCamera) {
    const Scene s = loadScene(kCornell);
    ASSERT_EQ(s.lights.size(), 1u);
    const Light& l = s.lights[0];
    EXPECT_EQ(l.type, Light::Type::Rect);
    EXPECT_EQ(l.name, "ceiling-light");
    EXPECT_TRUE(l.oneSided);
    EXPECT_NEAR(l.area(), 0.46 * 0.38, 1e-6);
    EXPECT_NEAR(l.normal().y, -1.f, 1e-7);
    EXPECT_EQ(l.radiance, Vec3(18.387f, 13.9873f, 6.75357f));
    EXPECT_FLOAT_EQ(l.corner.x, -0.23f);
    EXPECT_FLOAT_EQ(l.corner.y, 0.99f);
    EXPECT_FLOAT_EQ(l.corner.z, -0.18f);
    EXPECT_FLOAT_EQ((l.corner + l.edge1 + l.edge2).x, 0.23f);
    EXPECT_FLOAT_EQ((l.corner + l.edge1 + l.edge2).z, 0.20f);
    EXPECT_EQ(l.material, -1);  // black emitter
    EXPECT_EQ(s.movableLight, 0);
    EXPECT_EQ(s.camera.eye, Vec3(0, 0, 3.9f));
    EXPECT_EQ(s.camera.target, Vec3(0, 0, 0));
    EXPECT_EQ(s.camera.up, Vec3(0, 1, 0));
    EXPECT_FLOAT_EQ(s.camera.fovYDegrees, 39.3077f);
    EXPECT_EQ(s.camera.width, 256);
    EXPECT_EQ(s.camera.height, 256);
}

TEST(SceneJson, CornellBoxCornersMatchDesign) {
    const Scene s = loadScene(kCornell);
    struct Ref {
        const char* name;
        float footprint[4][2];
        float y0, y1;
    };
    const Ref refs[2] = {
        {"short-box", {{0.135820f, 0.005397f}, {-0.039603f, 0.579180f}, {0.534180f, 0.754603f}, {0.709603f, 0.180820f}},
         -1.f, -0.4f},
        {"tall-box", {{-0.708859f, -0.470961f}, {-0.520961f, 0.098859f}, {0.048859f, -0.089039f}, {-0.139039f, -0.658859f}},
         -1.01f, 0.21f}};
    for (const Ref& ref : refs) {
        const Object& o = byName(s, ref.name);
        ASSERT_EQ(o.positions.size(), 8u);
        // Every reference corner (4 footprint points at both heights) is a vertex, and vice versa.
        for (float y : {ref.y0, ref.y1}) {
            for (const auto& f : ref.footprint) {
                const Vec3 want(f[0], y, f[1]);
                float best = INFINITY;
                for (const Vec3& p : o.positions) best = std::min(best, length(p - want));
                EXPECT_LT(best, 1e-4f) << ref.name << " corner " << want;
            }
        }
    }
}

TEST(SceneJson, BoxFacesPointOutward) {
    const Scene s = loadScene(kCornell);
    for (const char* name : {"short-box", "tall-box"}) {
        const Object& o = byName(s, name);
        const Vec3 c = o.bounds().center();
        for (size_t q = 0; q < 6; ++q) {
            Vec3 faceCenter(0.f);
            for (size_t k = 0; k < 4; ++k) faceCenter += o.positions[o.indices[4 * q + k]] * 0.25f;
            EXPECT_GT(dot(quadNormal(o, q), faceCenter - c), 0.f) << name << " face " << q;
        }
    }
}

TEST(SceneJson, CornellLightRegionKeepsLightInsideBox) {
    Scene s = loadScene(kCornell);
    ASSERT_FALSE(s.lightRegion.empty());
    EXPECT_TRUE(s.lightRegion.contains(s.lightPosition()));
    const Bounds3 r = s.lightRegion;
    for (int i = 0; i < 8; ++i) {
        s.setLightPosition(Vec3(i & 1 ? r.hi.x : r.lo.x, i & 2 ? r.hi.y : r.lo.y, i & 4 ? r.hi.z : r.lo.z));
        const Light& l = s.lights[0];
        for (const Vec3& p : {l.corner, l.corner + l.edge1, l.corner + l.edge2, l.corner + l.edge1 + l.edge2}) {
            EXPECT_GT(p.x, -1.f);
            EXPECT_LT(p.x, 1.f);
            EXPECT_GT(p.y, 0.21f) << "light would cut into the tall box";
            EXPECT_LT(p.y, 1.f);
            EXPECT_GT(p.z, -1.f);
            EXPECT_LT(p.z, 1.f);
        }
    }
}

TEST(SceneJson, ObjWithTransformAndRelativePath) {
    const Scene s = loadScene(kData + "/obj_scene.json");
    ASSERT_EQ(s.objects.size(), 2u);
    const Object& pyramid = s.objects[0];
    EXPECT_EQ(pyramid.kind, Object::Kind::Triangles);
    EXPECT_TRUE(pyramid.closed);
    EXPECT_EQ(pyramid.primitiveCount(), 6u);  // the quad base is triangulated
    // (-1,0,-1) scaled by 2, turned 90 degrees about +y, moved by (10,0,0).
    EXPECT_NEAR(pyramid.positions[0].x, 8.f, 1e-6);
    EXPECT_NEAR(pyramid.positions[0].y, 0.f, 1e-6);
    EXPECT_NEAR(pyramid.positions[0].z, 2.f, 1e-6);
    EXPECT_NEAR(pyramid.positions[4].y, 2.f, 1e-6);
    EXPECT_EQ(s.lights[0].type, Light::Type::Point);
    EXPECT_EQ(s.lights[0].name, "light-0");
    EXPECT_TRUE(s.lightRegion.empty());
}

TEST(SceneJson, ObjDegenerateTrianglesDroppedWithWarning) {
    const Scene s = loadScene(kData + "/obj_scene.json");
    const Object& sheet = s.objects[1];
    EXPECT_EQ(sheet.primitiveCount(), 2u);
    EXPECT_FALSE(sheet.closed);
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_NE(s.warnings[0].find("dropped 2 zero-area triangles"), std::string::npos) << s.warnings[0];
    EXPECT_NE(s.warnings[0].find("/shapes/1"), std::string::npos) << s.warnings[0];
}

TEST(SceneJson, InlineShapesPhongAndDefaults) {
    json doc = validScene();
    doc["materials"]["shiny"] = {{"type", "phong"}, {"kd", {0.3, 0.3, 0.3}}, {"ks", {0.7, 0.7, 0.7}}, {"exponent", 1e6}};
    doc["shapes"].push_back({{"type", "sphere"}, {"material", "shiny"}, {"center", {0, 0, 0}}, {"radius", 0.25}});
    doc["shapes"].push_back({{"type", "triangles"}, {"material", "red"}, {"closed", true},
                             {"positions", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}}},
                             {"indices", {{0, 1, 2}, {0, 1, 3}}},
                             {"transform", {{"translate", {0, 0, -0.5}}}}});
    doc["lights"][0]["material"] = "white";
    doc["shapes"].push_back({{"type", "quad"}, {"material", "green"},
                             {"points", {{-1, 1, -1}, {1, 1, -1}, {0.8, 1, 1}, {-0.8, 1, 1}}}});
    const Scene s = parseScene(doc, "inline.json", "");
    ASSERT_EQ(s.objects.size(), 4u);
    EXPECT_EQ(s.objects[1].name, "sphere-1");
    EXPECT_EQ(s.objects[1].kind, Object::Kind::Sphere);
    EXPECT_TRUE(s.objects[1].closed);
    EXPECT_FLOAT_EQ(s.materials[size_t(s.objects[1].material)].exponent, 1e6f);
    EXPECT_EQ(s.objects[2].name, "triangles-2");
    EXPECT_EQ(s.objects[2].primitiveCount(), 1u);  // the collinear triangle is dropped
    EXPECT_TRUE(s.objects[2].closed);
    EXPECT_FLOAT_EQ(s.objects[2].positions[0].z, -0.5f);
    EXPECT_EQ(s.warnings.size(), 1u);
    EXPECT_EQ(s.objects[3].name, "quad-3");
    EXPECT_EQ(s.objects[3].primitiveCount(), 1u);
    EXPECT_EQ(quadNormal(s.objects[3], 0), Vec3(0, -1, 0));
    EXPECT_EQ(s.materials[size_t(s.lights[0].material)].name, "white");
}

TEST(SceneJson, MirroringTransformKeepsBoxNormalsOutward) {
    json doc = validScene();
    doc["shapes"].push_back({{"type", "box"}, {"material", "white"}, {"transform", {{"scale", {-1, 2, 1}}}}});
    const Scene s = parseScene(doc, "mirror.json", "");
    const Object& box = s.objects[1];
    for (size_t q = 0; q < 6; ++q) {
        Vec3 fc(0.f);
        for (size_t k = 0; k < 4; ++k) fc += box.positions[box.indices[4 * q + k]] * 0.25f;
        EXPECT_GT(dot(quadNormal(box, q), fc), 0.f) << "face " << q;
    }
}

TEST(SceneJson, TinyLightsAndLargeScalesAreAccepted) {
    json doc = validScene();
    doc["lights"][0]["edge1"] = {1e-4, 0, 0};  // area 1e-8
    doc["lights"][0]["edge2"] = {0, 0, 1e-4};
    doc["shapes"].push_back({{"type", "box"}, {"material", "white"},
                             {"transform", {{"scale", 1e4}, {"translate", {0, -6000, 0}}}}});
    doc["shapes"].push_back({{"type", "quad"}, {"material", "white"},
                             {"corner", {5000, 0, 0}}, {"edge1", {1e-3, 0, 0}}, {"edge2", {0, 1e-3, 0}}});
    const Scene s = parseScene(doc, "scales.json", "");
    EXPECT_NEAR(s.lights[0].area(), 1e-8, 1e-12);
    EXPECT_EQ(s.objects.size(), 3u);
    EXPECT_TRUE(s.warnings.empty());
}

// ---- bad input: each case names the file, the JSON path and what is wrong -----------------------

TEST(SceneJsonError, MalformedJson) {
    const std::string msg = loadErrorText("malformed.json", "{\n  \"camera\": {\n    \"eye\": [0, 0, 4],\n  }\n}\n");
    expectMessage(msg, "malformed.json", "malformed.json", {"malformed JSON", "line 4", "byte"});
}

TEST(SceneJsonError, UnknownShapeType) {
    json doc = validScene();
    doc["shapes"][0]["type"] = "cube";
    expectMessage(loadError("shape_type.json", doc), "shape_type.json", "/shapes/0/type", {"unknown shape type 'cube'", "box"});
}

TEST(SceneJsonError, UnknownMaterialType) {
    json doc = validScene();
    doc["materials"]["red"]["type"] = "mirror";
    expectMessage(loadError("material_type.json", doc), "material_type.json", "/materials/red/type",
                  {"unknown material type 'mirror'", "lambert, phong"});
}

TEST(SceneJsonError, UnknownMaterialName) {
    json doc = validScene();
    doc["shapes"][0]["material"] = "wite";
    expectMessage(loadError("material_name.json", doc), "material_name.json", "/shapes/0/material",
                  {"unknown material 'wite'", "known: green, red, white"});
}

TEST(SceneJsonError, MissingField) {
    json doc = validScene();
    doc["shapes"][0].erase("edge2");
    expectMessage(loadError("missing.json", doc), "missing.json", "/shapes/0", {"missing required field 'edge2'"});
}

TEST(SceneJsonError, MistypedField) {
    json doc = validScene();
    doc["shapes"][0]["corner"] = "origin";
    expectMessage(loadError("mistyped.json", doc), "mistyped.json", "/shapes/0/corner",
                  {"expected array of 3 numbers, got string"});
}

TEST(SceneJsonError, NegativeAlbedo) {
    json doc = validScene();
    doc["materials"]["red"]["albedo"] = {0.5, -0.1, 0.1};
    expectMessage(loadError("negative.json", doc), "negative.json", "/materials/red/albedo", {">= 0", "green", "-0.1"});
}

TEST(SceneJsonError, PhongNotEnergyConserving) {
    json doc = validScene();
    doc["materials"]["shiny"] = {{"type", "phong"}, {"kd", {0.5, 0.5, 0.5}}, {"ks", {0.4, 0.4, 0.6}}, {"exponent", 20}};
    expectMessage(loadError("energy.json", doc), "energy.json", "/materials/shiny",
                  {"kd + ks", "> 1", "blue", "energy conservation"});
}

TEST(SceneJsonError, ZeroAreaQuad) {
    json doc = validScene();
    doc["shapes"][0]["edge2"] = {0, 0, 4};  // parallel to edge1
    expectMessage(loadError("zero_quad.json", doc), "zero_quad.json", "/shapes/0", {"degenerate quad", "zero area"});
}

TEST(SceneJsonError, NonPlanarQuad) {
    json doc = validScene();
    doc["shapes"][0] = {{"type", "quad"}, {"material", "white"},
                        {"points", {{-1, -1, -1}, {1, -1, -1}, {1, -0.5, 1}, {-1, -1, 1}}}};
    expectMessage(loadError("bent_quad.json", doc), "bent_quad.json", "/shapes/0/points", {"not planar", "point"});
}

TEST(SceneJsonError, FlattenedBox) {
    json doc = validScene();
    doc["shapes"].push_back({{"type", "box"}, {"material", "white"}, {"transform", {{"scale", {1, 1e-30, 1}}}}});
    expectMessage(loadError("flat_box.json", doc), "flat_box.json", "/shapes/1/transform", {"flattens the box"});
}

TEST(SceneJsonError, MissingObjFile) {
    json doc = validScene();
    doc["shapes"].push_back({{"type", "obj"}, {"material", "white"}, {"file", "does-not-exist.obj"}});
    expectMessage(loadError("missing_obj.json", doc), "missing_obj.json", "/shapes/1/file",
                  {"cannot open OBJ file", "does-not-exist.obj"});
}

TEST(SceneJsonError, ObjWithOnlyDegenerateTriangles) {
    json doc = validScene();
    doc["shapes"].push_back({{"type", "triangles"}, {"material", "white"},
                             {"positions", {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}}, {"indices", {{0, 1, 2}}}});
    expectMessage(loadError("flat_mesh.json", doc), "flat_mesh.json", "/shapes/1", {"no triangles with non-zero area"});
}

TEST(SceneJsonError, TriangleIndexOutOfRange) {
    json doc = validScene();
    doc["shapes"].push_back({{"type", "triangles"}, {"material", "white"},
                             {"positions", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {"indices", {{0, 1, 3}}}});
    expectMessage(loadError("index.json", doc), "index.json", "/shapes/1/indices/0/2",
                  {"vertex index 3 out of range", "3 entries"});
}

TEST(SceneJsonError, UnknownKeyTypo) {
    json doc = validScene();
    doc["materials"]["white"]["albdo"] = doc["materials"]["white"]["albedo"];
    expectMessage(loadError("typo.json", doc), "typo.json", "/materials/white/albdo", {"unknown key 'albdo'", "albedo"});
}

TEST(SceneJsonError, UnknownTopLevelKey) {
    json doc = validScene();
    doc["light"] = json::array();
    expectMessage(loadError("top.json", doc), "top.json", "/light", {"unknown key 'light'", "lights"});
}

TEST(SceneJsonError, LightRegionMinAboveMax) {
    json doc = validScene();
    doc["light_region"]["min"] = {-0.5, 1.0, -0.5};
    expectMessage(loadError("region.json", doc), "region.json", "/light_region", {"min > max", "y axis"});
}

TEST(SceneJsonError, LightRegionMustContainLight) {
    json doc = validScene();
    doc["light_region"] = {{"min", {2, 2, 2}}, {"max", {3, 3, 3}}};
    expectMessage(loadError("outside.json", doc), "outside.json", "/light_region", {"must contain", "centre"});
}

TEST(SceneJsonError, TwoMovableLights) {
    json doc = validScene();
    doc["lights"].push_back({{"type", "point"}, {"position", {0, 0.5, 0}}, {"intensity", {1, 1, 1}}, {"movable", true}});
    expectMessage(loadError("two_movable.json", doc), "two_movable.json", "/lights/1/movable",
                  {"only one light can be movable", "/lights/0"});
}

TEST(SceneJsonError, ZeroAreaRectLight) {
    json doc = validScene();
    doc["lights"][0]["edge2"] = {0, 0, 0};
    expectMessage(loadError("zero_light.json", doc), "zero_light.json", "/lights/0", {"zero area"});
}

}  // namespace test_scene_json
