// GLSL prediction against the CPU on a small scene with the paths the Cornell box does not take:
// a sphere (ray-cast in the G-buffer pass), a free triangle, a smooth mesh, a Phong material (19
// network inputs), a one-sided light seen from behind and a wide-aspect camera.

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "app/gl/glsl_predictor.h"
#include "tests/gl/gl_test_env.h"
#include "tests/gl/glsl_comparison.h"
#include "tests/gl/test_models.h"

namespace rrf::test_glsl_sphere_scene {
namespace {

using test::compareGBuffer;
using test::expectEquivalent;
using test::GBufferComparison;

/// A small scene with a sphere, a triangle, a floor quad, a Phong material (19 network inputs) and a
/// wide-aspect camera: the paths the Cornell box does not take.
Scene sphereScene() {
    Scene s;
    s.camera.eye = Vec3(0.2f, 0.9f, 3.f);
    s.camera.target = Vec3(0.f, 0.5f, 0.f);
    s.camera.fovYDegrees = 45.f;
    s.camera.width = 160;
    s.camera.height = 96;
    Material lambert;
    lambert.name = "floor";
    lambert.kd = Vec3(0.6f, 0.5f, 0.4f);
    Material phong;
    phong.name = "glossy";
    phong.type = Material::Type::Phong;
    phong.kd = Vec3(0.3f, 0.4f, 0.5f);
    phong.ks = Vec3(0.4f);
    phong.exponent = 80.f;
    s.materials = {lambert, phong};
    Object floor;
    floor.kind = Object::Kind::Quads;
    floor.name = "floor";
    floor.id = 0;
    floor.material = 0;
    floor.positions = {Vec3(-2, 0, -2), Vec3(-2, 0, 2), Vec3(2, 0, 2), Vec3(2, 0, -2)};
    floor.indices = {0, 1, 2, 3};
    Object ball;
    ball.kind = Object::Kind::Sphere;
    ball.name = "ball";
    ball.id = 1;
    ball.material = 1;
    ball.center = Vec3(-0.3f, 0.45f, 0.1f);
    ball.radius = 0.45f;
    ball.closed = true;
    Object tri;
    tri.kind = Object::Kind::Triangles;
    tri.name = "fin";
    tri.id = 2;
    tri.material = 1;
    tri.positions = {Vec3(0.4f, 0.f, -0.5f), Vec3(1.2f, 0.f, 0.2f), Vec3(0.7f, 1.1f, -0.1f)};
    tri.indices = {0, 1, 2};
    s.objects = {floor, ball, tri};
    Light l;
    l.name = "panel";
    l.corner = Vec3(-0.4f, 1.3f, -0.9f);
    l.edge1 = Vec3(0.8f, 0.f, 0.f);  // normal = edge1 × edge2 points down, towards the floor and the eye
    l.edge2 = Vec3(0.f, 0.f, 0.5f);
    l.radiance = Vec3(5.f, 4.f, 3.f);
    s.lights = {l};
    s.movableLight = 0;
    s.lightRegion.expand(Vec3(-1.f, 1.2f, -1.f));
    s.lightRegion.expand(Vec3(1.f, 1.8f, 0.5f));
    return s;
}

TEST(GlslPredictor, SphereTrianglePhongAndWideCamera) {
    RRF_REQUIRE_GL();
    const Scene scene = sphereScene();
    ASSERT_EQ(RecordLayout::forScene(scene).inputCount(), 19);
    const ModelSet set = test::mixedModelSet(scene, Activation::Tanh, {16, 9}, 31);
    GlslPredictor gp(scene, set);
    gp.render();
    const GlGBuffer g = gp.readGBuffer();
    ASSERT_EQ(g.width, 160);
    ASSERT_EQ(g.height, 96);
    const GBufferComparison c = compareGBuffer(scene, g);
    std::printf("  %zu id mismatches (%zu off silhouettes), max |dp| %.3g, max |dn| %.3g\n", c.idMismatches,
                c.idMismatchesOffSilhouette, c.maxPositionError, c.maxNormalError);
    EXPECT_EQ(c.idMismatchesOffSilhouette, 0u);
    EXPECT_LE(c.maxPositionError, 1e-5 * double(scene.scale()));
    EXPECT_LE(c.maxNormalError, 1e-5);  // sphere normals: (p − c)/r from slightly different p
    size_t sphere = 0, background = 0;
    for (int id : g.objectId) {
        sphere += id == 1;
        background += id == GlGBuffer::kBackgroundPixel;
    }
    EXPECT_GT(sphere, 500u);
    EXPECT_GT(background, 0u);
    size_t lights = 0;
    for (int id : g.objectId) lights += id == GlGBuffer::kLightPixel;
    EXPECT_GT(lights, 0u);
    expectEquivalent(scene, set, gp, 0.3);
}

TEST(GlslPredictor, SmoothMeshNormalsInterpolateLikeTheCpu) {
    // The fin becomes a smooth triangle: vertex normals tilted ~0.3 rad from its face normal in
    // three different directions, so a G-buffer that kept the flat normal would be ~0.3 off.
    RRF_REQUIRE_GL();
    Scene scene = sphereScene();
    Object& fin = scene.objects[2];
    const Vec3 face = normalize(cross(fin.positions[1] - fin.positions[0], fin.positions[2] - fin.positions[0]));
    fin.normals = {normalize(face + Vec3(0.3f, 0.f, 0.f)), normalize(face + Vec3(0.f, 0.3f, 0.f)),
                   normalize(face + Vec3(0.f, 0.f, -0.3f))};
    GlslPredictor gp(scene, test::mixedModelSet(scene, Activation::Tanh, {16, 9}, 31));
    gp.render();
    const GlGBuffer g = gp.readGBuffer();
    const GBufferComparison c = compareGBuffer(scene, g);
    std::printf("  %zu pixels compared, max |dn| %.3g\n", c.compared, c.maxNormalError);
    EXPECT_EQ(c.idMismatchesOffSilhouette, 0u);
    EXPECT_LE(c.maxNormalError, 1e-5);
    size_t finPixels = 0;
    double spread = 0;  // largest angle between a fin pixel's normal and the face normal
    for (size_t i = 0; i < g.objectId.size(); ++i) {
        if (g.objectId[i] != 2) continue;
        ++finPixels;
        const Vec3 n(g.normal[3 * i], g.normal[3 * i + 1], g.normal[3 * i + 2]);
        spread = std::max(spread, std::acos(std::min(1.0, std::fabs(double(dot(n, face))))));
    }
    EXPECT_GT(finPixels, 100u);
    EXPECT_GT(spread, 0.1) << "the fin's normals must vary across it";
}

TEST(GlslPredictor, OneSidedLightIsDarkFromBehind) {
    RRF_REQUIRE_GL();
    Scene scene = sphereScene();
    std::swap(scene.lights[0].edge1, scene.lights[0].edge2);  // the light now faces up, away from the eye
    GlslPredictor gp(scene, test::mixedModelSet(scene));
    gp.render();
    const GlGBuffer g = gp.readGBuffer();
    const Image direct = gp.read(Term::Direct);
    size_t lightPixels = 0;
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x)
            if (g.objectId[size_t(y) * size_t(g.width) + size_t(x)] == GlGBuffer::kLightPixel) {
                ++lightPixels;
                EXPECT_TRUE(g.emission.at(x, y).isZero());
                EXPECT_TRUE(direct.at(x, y).isZero());
            }
    EXPECT_GT(lightPixels, 0u);  // the light still occludes what lies behind it
}

}  // namespace
}  // namespace rrf::test_glsl_sphere_scene
