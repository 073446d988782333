// G-buffer of the Cornell box: values at known pixels, the record layout, emitter pixels and the
// light position column.
#include <cmath>

#include <gtest/gtest.h>

#include "core/predict/gbuffer.h"
#include "core/project/project.h"
#include "core/project/project_file.h"

namespace test_gbuffer {

using namespace rrf;

namespace {
const std::string kCornell = std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/project.json";

int objectId(const Scene& s, const std::string& name) {
    for (const Object& o : s.objects)
        if (o.name == name) return o.id;
    return -1;
}

struct Fixture {
    Project project = loadProjectOrScene(kCornell);
    Accel accel{project.scene};
    PathTracer tracer{project.scene, accel, Estimator::NEE, 1};
    RecordLayout layout = RecordLayout::forScene(project.scene);
};

/// Where the ray through the centre of pixel (x, y) meets the plane z = zPlane (pinhole maths
/// written out independently of CameraRays).
Vec3 onPlaneZ(const Camera& c, int w, int h, int x, int y, float zPlane) {
    const float t = std::tan(0.5f * c.fovYDegrees * kPi / 180.f);
    const float sx = (2.f * (float(x) + 0.5f) / float(w) - 1.f) * t * float(w) / float(h);
    const float sy = (1.f - 2.f * (float(y) + 0.5f) / float(h)) * t;
    // Camera at (0,0,3.9) looking down -z with +y up: direction (sx, sy, -1).
    const float k = (c.eye.z - zPlane);
    return Vec3(c.eye.x + sx * k, c.eye.y + sy * k, zPlane);
}
}  // namespace

TEST(GBuffer, BackWallPixelHoldsTheRecordLayout) {
    Fixture f;
    const Scene& s = f.project.scene;
    const Vec3 light(0.1f, 0.8f, -0.2f);
    const GBuffer g = buildGBuffer(f.tracer, f.layout, light, 256, 256);
    ASSERT_EQ(g.numInputs, 15);  // Lambert-only scene: 12 + albedo
    // Pixel (128, 80) looks above the tall box (top at y = 0.21) onto the back wall z = -1.
    const size_t i = 80 * 256 + 128;
    ASSERT_EQ(g.object[i], objectId(s, "back-wall"));
    EXPECT_EQ(g.light[i], -1);
    const float* r = g.input(i);
    const Vec3 expected = onPlaneZ(s.camera, 256, 256, 128, 80, -1.f);
    EXPECT_NEAR(r[0], expected.x, 1e-5);
    EXPECT_NEAR(r[1], expected.y, 1e-5);
    EXPECT_NEAR(r[2], -1.f, 1e-5);
    const Vec3 view = normalize(s.camera.eye - expected);  // from the hit point to the eye
    EXPECT_NEAR(r[3], view.x, 1e-5);
    EXPECT_NEAR(r[4], view.y, 1e-5);
    EXPECT_NEAR(r[5], view.z, 1e-5);
    EXPECT_EQ(Vec3(r[6], r[7], r[8]), light);
    EXPECT_EQ(Vec3(r[9], r[10], r[11]), Vec3(0.f, 0.f, 1.f));  // facing the viewer
    const Material& white = s.materials[size_t(s.objects[size_t(g.object[i])].material)];
    EXPECT_EQ(Vec3(r[12], r[13], r[14]), white.kd);
    // The footprint mask's per-pixel normal and distance from the eye agree with the record.
    EXPECT_EQ(g.normal[i], Vec3(r[9], r[10], r[11]));
    EXPECT_EQ(g.position(i), Vec3(r[0], r[1], r[2]));
    EXPECT_NEAR(g.distance[i], length(expected - s.camera.eye), 1e-5);
}

TEST(GBuffer, NormalsFaceTheViewerAndWallsKeepTheirMaterial) {
    Fixture f;
    const Scene& s = f.project.scene;
    const GBuffer g = buildGBuffer(f.tracer, f.layout, s.lightPosition(), 64, 64);
    // Bottom-centre pixel sees the floor (normal +y); left edge the red wall (+x); right the green (-x).
    const struct {
        int x, y;
        const char* name;
        Vec3 normal;
    } cases[] = {{32, 62, "floor", {0, 1, 0}}, {1, 32, "left-wall", {1, 0, 0}}, {62, 32, "right-wall", {-1, 0, 0}}};
    for (const auto& c : cases) {
        const size_t i = size_t(c.y) * 64 + size_t(c.x);
        ASSERT_EQ(g.object[i], objectId(s, c.name)) << c.name;
        const float* r = g.input(i);
        EXPECT_EQ(Vec3(r[9], r[10], r[11]), c.normal) << c.name;
        EXPECT_GT(dot(Vec3(r[3], r[4], r[5]), c.normal), 0.f) << c.name;
        const Material& m = s.materials[size_t(s.objects[size_t(g.object[i])].material)];
        EXPECT_EQ(Vec3(r[12], r[13], r[14]), m.kd) << c.name;
    }
    // Every pixel is exactly one of: object, emitter, background; the masks list the object pixels.
    size_t objectPixels = 0;
    for (size_t id = 0; id < g.pixelsByObject.size(); ++id) {
        for (uint32_t p : g.pixelsByObject[id]) EXPECT_EQ(g.object[p], int(id));
        objectPixels += g.pixelsByObject[id].size();
    }
    EXPECT_EQ(objectPixels + g.emitterPixels.size() + g.backgroundPixels, g.pixelCount());
}

TEST(GBuffer, EmitterPixelsCarryTheLightsRadianceAndFollowTheLight) {
    Fixture f;
    const Scene& s = f.project.scene;
    const Light& l = s.lights[size_t(s.movableLight)];
    const Vec3 a(0.f, 0.99f, 0.f), b(0.3f, 0.9f, 0.3f);
    const GBuffer ga = buildGBuffer(f.tracer, f.layout, a, 128, 128);
    const GBuffer gb = buildGBuffer(f.tracer, f.layout, b, 128, 128);
    ASSERT_FALSE(ga.emitterPixels.empty());
    ASSERT_FALSE(gb.emitterPixels.empty());
    for (uint32_t p : ga.emitterPixels) {
        EXPECT_EQ(ga.light[p], s.movableLight);
        EXPECT_EQ(ga.object[p], -1);
        EXPECT_EQ(ga.emitted[p], l.radiance);  // seen from below: the emitting side
        EXPECT_EQ(ga.normal[p], Vec3(0.f));  // no surface for the footprint mask to compare
        EXPECT_EQ(ga.distance[p], 0.f);
    }
    EXPECT_NE(ga.emitterPixels, gb.emitterPixels);
    // The light column is the requested position on every covered pixel.
    for (size_t i = 0; i < gb.pixelCount(); ++i)
        if (gb.covered(i)) {
            ASSERT_EQ(Vec3(gb.input(i)[6], gb.input(i)[7], gb.input(i)[8]), b);
        }
}

}  // namespace test_gbuffer
