// Exact direct light in GLSL (shaders/direct_light.glsl) against the CPU estimator
// (core/predict/exact_direct.h) on the Cornell box (with its rect lamp, and with triangle emitters),
// and the CPU fallback for scenes too big for the shader's brute-force shadow rays.
//
// The bound: the shader repeats the CPU's random numbers and arithmetic in float, so a pixel differs
// only by rounding — relative 1e-3 allowed (measured at most 1.7e-4 with llvmpipe, from the float
// projected solid angle near the light) — unless a shadow ray passes within rounding of an edge and
// the two ray tests disagree, which changes one sample of the visibility ratio (≤ 1/N of the pixel).
// At most 0.5 % of the compared pixels may differ by more than 1e-3 relative (measured: none), and
// the mean over pixels of the relative difference must stay below 1e-4 (measured 5e-6).

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "app/gl/glsl_predictor.h"
#include "core/predict/exact_direct.h"
#include "core/predict/predictor.h"
#include "core/scene/scene_json.h"
#include "tests/gl/gl_test_env.h"
#include "tests/gl/test_models.h"

namespace rrf::test_glsl_direct {
namespace {

PredictionSettings exactSettings(int samples, uint64_t seed) {
    PredictionSettings s;
    s.direct = PredictionSettings::Direct::Exact;
    s.directSamples = samples;
    s.seed = seed;
    return s;
}

struct DirectComparison {
    size_t compared = 0, beyondRounding = 0;
    double meanRelative = 0, maxRelative = 0;
};

/// GLSL direct image against the CPU estimator evaluated at the GLSL G-buffer's own points (so the
/// comparison is of the estimators, not of two rasterisations), pixel keys y·width + x.
DirectComparison compareWithCpu(const Scene& scene, const GlslPredictor& gp, const PredictionSettings& s) {
    const GlGBuffer g = gp.readGBuffer();
    const Image gl = gp.read(Term::Direct);
    Scene moved = scene;
    moved.setLightPosition(gp.lightPosition());
    const Accel accel(moved);
    const PathTracer tracer(moved, accel, Estimator::NEE, 1);
    const ExactDirect direct(tracer, s.directSamples, s.seed);
    const Light movable = tracer.movableLightAt(gp.lightPosition());
    DirectComparison c;
    TraceCounters counters;
    double sum = 0;
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
            const size_t i = size_t(y) * size_t(g.width) + size_t(x);
            if (g.objectId[i] < 0) continue;
            const Vec3 p(g.position[3 * i], g.position[3 * i + 1], g.position[3 * i + 2]);
            const Vec3 n(g.normal[3 * i], g.normal[3 * i + 1], g.normal[3 * i + 2]);
            const Vec3 cpu = direct.radiance(p, n, normalize(scene.camera.eye - p), g.objectId[i], movable, i, counters);
            const Vec3 shader = gl.at(x, y);
            double rel = 0;
            for (int k = 0; k < 3; ++k)
                rel = std::max(rel, std::fabs(double(shader[k]) - double(cpu[k])) / (std::fabs(double(cpu[k])) + 1e-2));
            ++c.compared;
            sum += rel;
            c.maxRelative = std::max(c.maxRelative, rel);
            if (rel > 1e-3) ++c.beyondRounding;
        }
    c.meanRelative = c.compared ? sum / double(c.compared) : 0.0;
    return c;
}

TEST(GlslDirect, ExactDirectMatchesCpuCornellBox) {
    RRF_REQUIRE_GL();
    Scene scene = test::cornellBox();
    scene.camera.width = scene.camera.height = 64;
    const ModelSet set = test::mixedModelSet(scene);
    GlslPredictor gp(scene, set);
    for (const int samples : {4, 16}) {
        const PredictionSettings s = exactSettings(samples, 3);
        gp.setPrediction(s);
        EXPECT_TRUE(gp.directLightNote().empty()) << gp.directLightNote();
        for (const Vec3& light : {scene.lightPosition(), scene.lightRegion.lo}) {
            gp.setLightPosition(light);
            gp.render();
            const DirectComparison c = compareWithCpu(scene, gp, s);
            std::printf("  %d samples: %zu pixels, %zu beyond rounding, mean relative %.3g, max %.3g\n", samples,
                        c.compared, c.beyondRounding, c.meanRelative, c.maxRelative);
            EXPECT_GT(c.compared, size_t(0.8 * 64 * 64));
            EXPECT_LE(double(c.beyondRounding), 0.005 * double(c.compared));
            EXPECT_LT(c.meanRelative, 1e-4);
        }
    }
}

TEST(GlslDirect, GlossyLobesMatchCpu) {
    // The glossy Cornell box, its back wall sharpened to exponent 300 so that the lamp's highlight
    // near its top exercises the lobe quadrature's footprint, closed form and panels; the boxes'
    // lobes (100, 1000) miss the lamp or graze it. Same bound as the Lambert scene.
    RRF_REQUIRE_GL();
    Scene scene = loadScene(std::string(RRF_SOURCE_DIR) + "/projects/cornell-glossy/scene.json");
    for (Material& m : scene.materials)
        if (m.name == "glossy-back") m.exponent = 300.f;
    scene.camera.width = scene.camera.height = 64;
    const ModelSet set = test::mixedModelSet(scene);
    GlslPredictor gp(scene, set);
    const PredictionSettings s = exactSettings(16, 4);
    gp.setPrediction(s);
    EXPECT_TRUE(gp.directLightNote().empty()) << gp.directLightNote();
    for (const Vec3& light : {scene.lightPosition(), scene.lightRegion.lo}) {
        gp.setLightPosition(light);
        gp.render();
        const DirectComparison c = compareWithCpu(scene, gp, s);
        std::printf("  glossy: %zu pixels, %zu beyond rounding, mean relative %.3g, max %.3g\n", c.compared,
                    c.beyondRounding, c.meanRelative, c.maxRelative);
        EXPECT_GT(c.compared, size_t(0.8 * 64 * 64));
        EXPECT_LE(double(c.beyondRounding), 0.005 * double(c.compared));
        EXPECT_LT(c.meanRelative, 1e-4);
    }
}

TEST(GlslDirect, TriangleLightsMatchCpu) {
    // The Cornell box lit by triangle emitters (an OBJ's Ke faces): its lamp split into two triangles
    // (the first one movable) and a third, tilted triangle on the back wall. The shader's area-light
    // texels mark triangles (edge2.w = 1): sampling by the fold, Lambert's formula over three corners.
    RRF_REQUIRE_GL();
    Scene scene = test::cornellBox();
    scene.camera.width = scene.camera.height = 64;
    const Light lamp = scene.lights[0];
    scene.lights.clear();
    auto triangle = [&](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& le) {
        Light l;
        l.type = Light::Type::Triangle;
        l.name = "tri" + std::to_string(scene.lights.size());
        l.corner = a;
        l.edge1 = b - a;
        l.edge2 = c - a;
        l.radiance = le;
        scene.lights.push_back(l);
    };
    const Vec3 a = lamp.corner, b = a + lamp.edge1, c = b + lamp.edge2, d = a + lamp.edge2;
    triangle(a, b, c, lamp.radiance);
    triangle(a, c, d, lamp.radiance);
    triangle(Vec3(-0.3f, 0.2f, -0.98f), Vec3(0.3f, 0.1f, -0.95f), Vec3(0.f, 0.6f, -0.97f), Vec3(3.f));
    scene.movableLight = 0;
    ASSERT_LT(scene.lights[0].normal().y, -0.99f);
    ASSERT_GT(scene.lights[2].normal().z, 0.f);
    const ModelSet set = test::mixedModelSet(scene);
    GlslPredictor gp(scene, set);
    const PredictionSettings s = exactSettings(9, 5);
    gp.setPrediction(s);
    EXPECT_TRUE(gp.directLightNote().empty()) << gp.directLightNote();
    for (const Vec3& light : {scene.lightPosition(), scene.lightRegion.lo}) {
        gp.setLightPosition(light);
        gp.render();
        const DirectComparison cmp = compareWithCpu(scene, gp, s);
        std::printf("  triangles: %zu pixels, %zu beyond rounding, mean relative %.3g, max %.3g\n", cmp.compared,
                    cmp.beyondRounding, cmp.meanRelative, cmp.maxRelative);
        EXPECT_GT(cmp.compared, size_t(0.8 * 64 * 64));
        EXPECT_LE(double(cmp.beyondRounding), 0.005 * double(cmp.compared));
        EXPECT_LT(cmp.meanRelative, 1e-4);
    }
}

TEST(GlslDirect, NetworkModeStillUsesTheNetworks) {
    RRF_REQUIRE_GL();
    Scene scene = test::cornellBox();
    scene.camera.width = scene.camera.height = 32;
    const ModelSet set = test::mixedModelSet(scene);
    GlslPredictor gp(scene, set);
    gp.render();
    const Image learned = gp.read(Term::Direct);
    gp.setPrediction(exactSettings(4, 1));
    gp.render();
    const Image exact = gp.read(Term::Direct);
    PredictionSettings network = exactSettings(4, 1);
    network.direct = PredictionSettings::Direct::Network;
    gp.setPrediction(network);
    gp.render();
    const Image again = gp.read(Term::Direct);
    EXPECT_EQ(again.data, learned.data) << "back to the networks' direct light";
    EXPECT_NE(exact.data, learned.data);
}

TEST(GlslDirect, LargeScenesFallBackToCpuDirectLight) {
    RRF_REQUIRE_GL();
    // A floor of 2 × 33 × 33 = 2178 triangles under the Cornell light: above the shader's limit.
    Scene scene = test::cornellBox();
    Object floor;
    floor.kind = Object::Kind::Triangles;
    floor.name = "tessellated floor";
    floor.id = int(scene.objects.size());
    floor.material = 0;
    const int k = 33;
    for (int j = 0; j <= k; ++j)
        for (int i = 0; i <= k; ++i) floor.positions.push_back(Vec3(-0.9f + 1.8f * i / k, -0.5f, -0.9f + 1.8f * j / k));
    for (int j = 0; j < k; ++j)
        for (int i = 0; i < k; ++i) {
            const uint32_t a = uint32_t(j * (k + 1) + i), b = a + 1, c = a + uint32_t(k + 1), d = c + 1;
            floor.indices.insert(floor.indices.end(), {a, c, b, b, c, d});
        }
    scene.objects.push_back(floor);
    scene.camera.width = scene.camera.height = 32;
    const ModelSet set = test::mixedModelSet(scene);
    GlslPredictor gp(scene, set);
    const PredictionSettings s = exactSettings(8, 2);
    gp.setPrediction(s);
    EXPECT_NE(gp.directLightNote().find("on the CPU"), std::string::npos) << gp.directLightNote();
    gp.render();
    const DirectComparison c = compareWithCpu(scene, gp, s);
    EXPECT_GT(c.compared, 0u);
    EXPECT_EQ(c.maxRelative, 0.0) << "the CPU's own values, uploaded";
}

}  // namespace
}  // namespace rrf::test_glsl_direct
