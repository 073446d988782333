// The radiometric range (core/scene/radiometric_range.h, issue 31): emission, Phong exponents and
// light sizes beyond the bounds within which the tracers' float products stay finite are refused
// when the scene is read — JSON scenes, an OBJ's MTL library, scene_overrides — naming the file,
// the field and the light or material; and at the bounds themselves every image a render writes,
// variances included, and exact direct light stay finite, while an emitter far beyond them (set
// behind the reader's back) gives the NaN/Inf variance images the bound exists to prevent.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "core/predict/exact_direct.h"
#include "core/project/scene_overrides.h"
#include "core/project/scene_overrides_json.h"
#include "core/render/render_outputs.h"
#include "core/render/render_settings.h"
#include "core/render/renderer.h"
#include "core/render/term.h"
#include "core/scene/accel.h"
#include "core/scene/radiometric_range.h"
#include "core/scene/scene_json.h"
#include "core/util/error.h"
#include "core/util/json_reader.h"
#include "scene_builders.h"
#include "tests/test_dirs.h"

namespace test_radiometric_range {

using namespace rrf;
using namespace rrf::test;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

fs::path testDir() { return freshTestDir("rrf_radiometric"); }

/// A floor under a rect light and a point light, written to `dir`/scene.json; returns the path.
std::string writeScene(const fs::path& dir, const json& changes) {
    json s = {{"camera", {{"eye", {0, 1, 3}}, {"target", {0, 0, 0}}, {"fov_y", 50}, {"width", 8}, {"height", 8}}},
              {"materials",
               {{"white", {{"type", "lambert"}, {"albedo", {0.8, 0.8, 0.8}}}},
                {"shiny", {{"type", "phong"}, {"kd", {0.2, 0.2, 0.2}}, {"ks", {0.7, 0.7, 0.7}}, {"exponent", 50}}}}},
              {"shapes",
               {{{"type", "quad"}, {"name", "floor"}, {"material", "shiny"}, {"corner", {-1, 0, -1}}, {"edge1", {0, 0, 2}}, {"edge2", {2, 0, 0}}}}},
              {"lights",
               {{{"type", "rect"}, {"name", "lamp"}, {"corner", {-0.2, 1, -0.2}}, {"edge1", {0.4, 0, 0}}, {"edge2", {0, 0, 0.4}},
                 {"radiance", {5, 5, 5}}},
                {{"type", "point"}, {"name", "bulb"}, {"position", {0, 0.5, 0}}, {"intensity", {1, 1, 1}}}}}};
    s.merge_patch(changes);
    const fs::path p = dir / "scene.json";
    std::ofstream(p) << s.dump(2);
    return p.string();
}

std::string loadError(const std::string& path) {
    try {
        loadScene(path);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

json lightsWith(const json& lamp, const json& bulb) {
    json l = json::array({{{"type", "rect"}, {"name", "lamp"}, {"corner", {-0.2, 1, -0.2}}, {"edge1", {0.4, 0, 0}},
                           {"edge2", {0, 0, 0.4}}, {"radiance", {5, 5, 5}}},
                          {{"type", "point"}, {"name", "bulb"}, {"position", {0, 0.5, 0}}, {"intensity", {1, 1, 1}}}});
    // An empty brace is JSON null, which merge_patch would take for "replace with null".
    if (lamp.is_object()) l[0].merge_patch(lamp);
    if (bulb.is_object()) l[1].merge_patch(bulb);
    return l;
}

}  // namespace

TEST(RadiometricRange, JsonEmittersAndExponentsBeyondTheBoundsNameTheFieldAndTheLight) {
    const fs::path dir = testDir();
    const std::string ok = writeScene(dir, {{"lights", lightsWith({{"radiance", {1e10, 1e10, 1e10}}}, {{"intensity", {1e10, 0, 0}}})},
                                            {"materials", {{"shiny", {{"exponent", 1e6}}}}}});
    EXPECT_EQ(loadError(ok), "") << "the bounds themselves are accepted";

    std::string e = loadError(writeScene(dir, {{"lights", lightsWith({{"radiance", {5, 2e10, 5}}}, {})}}));
    EXPECT_TRUE(contains(e, "scene.json: /lights/0/radiance: light 'lamp': radiance must lie in [0, 1e+10]")) << e;
    EXPECT_TRUE(contains(e, "green component is 2e+10")) << e;

    e = loadError(writeScene(dir, {{"lights", lightsWith({}, {{"intensity", {1e30, 1, 1}}})}}));
    EXPECT_TRUE(contains(e, "scene.json: /lights/1/intensity: light 'bulb': intensity must lie in [0, 1e+10]")) << e;

    e = loadError(writeScene(dir, {{"materials", {{"shiny", {{"exponent", 1e7}}}}}}));
    EXPECT_TRUE(contains(e, "scene.json: /materials/shiny/exponent: exponent (Phong exponent) must lie in [0, 1000000], got 1e+07"))
        << e;
    fs::remove_all(dir);
}

TEST(RadiometricRange, LightsTooSmallForAFloatNormalAreRefused) {
    const fs::path dir = testDir();
    // 1e-10 × 1e-10: not degenerate in shape (a square), but |e1 × e2|² = 1e-40 is below the
    // smallest normal float, so the light's normal would be 0/0.
    const std::string tiny =
        writeScene(dir, {{"lights", lightsWith({{"edge1", {1e-10, 0, 0}}, {"edge2", {0, 0, 1e-10}}}, {})}});
    const std::string e = loadError(tiny);
    EXPECT_TRUE(contains(e, "scene.json: /lights/0: light 'lamp': the light is too small: |edge1 x edge2| = 1e-20")) << e;
    // The tiny light of the hard cases (area 1e-8) stays far inside.
    EXPECT_EQ(loadError(writeScene(dir, {{"lights", lightsWith({{"edge1", {1e-4, 0, 0}}, {"edge2", {0, 0, 1e-4}}}, {})}})), "");
    fs::remove_all(dir);
}

TEST(RadiometricRange, MtlEmitterBeyondTheBoundIsRefusedBeforeAnyWork) {
    // The issue's case: `Ke 1e30 1e30 1e30` was accepted and the whole image rendered before the
    // variance images could not be written. Now the scene does not load.
    const fs::path dir = testDir();
    std::ofstream(dir / "room.mtl") << "newmtl white\nKd 0.8 0.8 0.8\n\nnewmtl lamp\nKd 0 0 0\nKe 1e30 1e30 1e30\n";
    std::ofstream(dir / "room.obj") << "mtllib room.mtl\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\n"
                                       "v -0.2 1 -0.2\nv 0.2 1 -0.2\nv 0.2 1 0.2\nv -0.2 1 0.2\n"
                                       "usemtl white\nf 1 4 3 2\nusemtl lamp\nf 5 6 7 8\n";
    const fs::path scene = dir / "scene.json";
    std::ofstream(scene) << json{{"camera", {{"eye", {0, 0.5, 3}}, {"target", {0, 0.5, 0}}, {"fov_y", 40}}},
                                 {"shapes", {{{"type", "obj"}, {"file", "room.obj"}}}}}
                                .dump();
    const std::string e = loadError(scene.string());
    EXPECT_TRUE(contains(e, scene.string() + ": /shapes/0/file: MTL file '" + (dir / "room.mtl").string() +
                                "' line 6: material 'lamp': Ke must lie in [0, 1e+10]"))
        << e;
    EXPECT_TRUE(contains(e, "red component is 1e+30")) << e;
    fs::remove_all(dir);
}

TEST(RadiometricRange, OverridesBeyondTheExponentBoundAreIgnoredWithAWarning) {
    const json doc = json::parse(R"({"materials": {"shiny": {"exponent": 1e7, "kd": [0.1, 0.1, 0.1]}}})");
    std::vector<std::string> warnings;
    const SceneOverrides o = sceneOverridesFromJson(JsonReader(doc, "project.json", "/scene_overrides"), warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_TRUE(contains(warnings[0], "project.json: /scene_overrides/materials/shiny/exponent: value 1e+07 out of range")) << warnings[0];
    // The workbench's typed value is clamped, like kd + ks.
    Material m;
    m.type = Material::Type::Phong;
    m.kd = Vec3(0.2f);
    m.ks = Vec3(0.5f);
    m.exponent = 1e9f;
    EXPECT_TRUE(enforceEnergyConservation(m, true));
    EXPECT_EQ(m.exponent, kMaxPhongExponent);
}

TEST(RadiometricRange, AtTheBoundsEveryImageOfARenderAndExactDirectLightStayFinite) {
    // The Cornell-like box with its light at the largest radiance and a Phong block of the largest
    // exponent: every sample, every variance image and every written file is finite.
    Scene scene = cornellLike(1.f, 16);
    scene.lights[0].radiance = Vec3(kMaxRadiance);
    const int sharp = addPhong(scene, Vec3(0.2f), Vec3(0.8f), kMaxPhongExponent, "sharp");
    scene.objects.back().material = sharp;  // the block
    const Accel accel(scene);
    // Every estimator: NEE's Le·f·G, the naive estimator's β·Le, and bidirectional light tracing's
    // splats, which multiply by the camera's importance too.
    for (const Estimator e : {Estimator::NEE, Estimator::Naive, Estimator::BDPT}) {
        const RenderSnapshot at = render(scene, accel, e, 16);
        EXPECT_EQ(at.nonFinite, 0u) << estimatorName(e);
        for (Term t : kTerms) {
            EXPECT_EQ(at.image(t).nonFiniteCount(), 0u) << estimatorName(e) << " " << termName(t);
            EXPECT_EQ(at.varianceOf(t).nonFiniteCount(), 0u) << estimatorName(e) << " " << termName(t);
        }
    }
    const PathTracer tracer(scene, accel, Estimator::NEE);
    const ExactDirect exact(tracer, 256, 7);
    TraceCounters counters;
    // The floor, a point 1 % of the light's size below it (a large geometry factor) and the block's top.
    for (const Vec3& p : {Vec3(0, -1, 0), Vec3(0.1f, 0.985f, 0.05f), Vec3(-0.35f, -0.2f, -0.25f)}) {
        const Vec3 L = exact.radiance(p, Vec3(0, 1, 0), normalize(Vec3(0, 0.3f, 1)), int(scene.objects.size()) - 1,
                                      scene.lights[0], 1, counters);
        EXPECT_TRUE(L.isFinite()) << p;
        EXPECT_GT(L.maxComponent(), 0.f) << p;
    }

    // Far beyond the bound (no reader accepts it): the squares of the samples leave float range.
    scene.lights[0].radiance = Vec3(1e30f);
    const Accel accel2(scene);
    const RenderSnapshot beyond = render(scene, accel2, Estimator::NEE, 16);
    EXPECT_GT(beyond.varianceOf(Term::Global).nonFiniteCount(), 0u) << "the bound guards against nothing";
}

}  // namespace test_radiometric_range
