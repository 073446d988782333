// The shadow casters of exact direct light (core/predict/shadow_casters.h) against Embree and against
// closed forms: every verdict agrees with the Embree shadow ray of every light sample it stands for,
// on the bundled scenes (boxes, walls, a mesh room, a sphere); a light half hidden by a wall has the
// visible fraction Lambert's formula gives for the visible part; a room seen from inside shadows
// itself.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/predict/exact_direct.h"
#include "core/predict/predictor.h"
#include "core/project/project.h"
#include "core/project/project_file.h"
#include "scene_builders.h"

namespace test_shadow_casters {

using namespace rrf;
using namespace rrf::test;
using Verdict = ShadowCasters::Casters::Verdict;

namespace {

struct Agreement {
    uint64_t pairs[4] = {0, 0, 0, 0};  ///< (receiver, light) pairs per verdict
    uint64_t rays = 0, wrong = 0;      ///< sample rays checked; rays whose answer the verdict gets wrong
    uint64_t segmentRays = 0, segmentWrong = 0;
};

/// For every object pixel of a size × size G-buffer of `scene`, the casters' verdict for every area
/// light against `samples` Embree shadow rays to uniform points of the light above the horizon.
Agreement checkScene(const Scene& scene, int size, int samples) {
    ModelSet none;
    const Predictor pred(scene, none, PredictionSettings{});
    const GBuffer gb = pred.gbuffer(scene.lightPosition(), size, size);
    const PathTracer& tracer = pred.tracer();
    const Accel& accel = tracer.accel();
    const ShadowCasters casters(tracer);
    const Light movable = tracer.movableLightAt(gb.lightPosition);
    Agreement a;
    TraceCounters counters;
    for (size_t i = 0; i < gb.pixelCount(); ++i) {
        if (gb.object[i] < 0) continue;
        const float* r = gb.input(i);
        const Vec3 p(r[0], r[1], r[2]), n(r[9], r[10], r[11]);
        const Vec3 origin = accel.spawnOrigin(p, n, n);
        for (size_t li = 0; li < scene.lights.size(); ++li) {
            const Light& l = int(li) == scene.movableLight ? movable : scene.lights[li];
            if (!l.isArea()) continue;
            ClippedLight clipped;
            if (!(projectedSolidAngle(l, p, n, nullptr, &clipped) > 0.0)) continue;
            ShadowCasters::Casters c;
            casters.find(origin, n, clipped, gb.object[i], int(li), movable, counters, c);
            ++a.pairs[int(c.verdict)];
            Rng rng(7, i, li);
            for (int s = 0; s < samples; ++s) {
                const Vec3 x = l.pointAt(rng.uniform(), rng.uniform());
                if (dot(x - p, n) <= 0.f) continue;
                Ray ray;
                ray.origin = origin;
                const Vec3 d = x - origin;
                const float dist = length(d);
                ray.dir = d / dist;
                ray.tmax = dist * (1.f - 1e-4f) - accel.offset(x);  // as ExactDirect's sample rays
                if (!(ray.tmax > 0.f)) continue;
                const bool embree = tracer.occluded(ray, movable);
                ++a.rays;
                if (c.verdict == Verdict::Unoccluded) a.wrong += embree;
                if (c.verdict == Verdict::Occluded) a.wrong += !embree;
                if (c.verdict == Verdict::Segments) {
                    float dx[ShadowCasters::kBatch] = {d.x}, dy[ShadowCasters::kBatch] = {d.y},
                          dz[ShadowCasters::kBatch] = {d.z}, end[ShadowCasters::kBatch] = {ray.tmax / dist};
                    int32_t blocked[ShadowCasters::kBatch];
                    ShadowCasters::blocked(c, origin, dx, dy, dz, end, blocked);
                    ++a.segmentRays;
                    a.segmentWrong += (blocked[0] != 0) != embree;
                }
            }
        }
    }
    return a;
}

Scene projectScene(const char* name) {
    return loadProjectOrScene(std::string(RRF_SOURCE_DIR) + "/projects/" + name + "/project.json").scene;
}

}  // namespace

TEST(ShadowCasters, VerdictsAgreeWithEmbreeOnTheBundledScenes) {
    for (const char* name : {"cornell-box", "mesh-room"}) {
        const Agreement a = checkScene(projectScene(name), 48, 32);
        std::printf("  %s: unoccluded %llu, occluded %llu, segments %llu, rays %llu pairs; %llu rays checked, "
                    "%llu of %llu segment answers differ\n",
                    name, (unsigned long long)a.pairs[0], (unsigned long long)a.pairs[1],
                    (unsigned long long)a.pairs[2], (unsigned long long)a.pairs[3], (unsigned long long)a.rays,
                    (unsigned long long)a.segmentWrong, (unsigned long long)a.segmentRays);
        EXPECT_EQ(a.wrong, 0u) << name << ": a proof contradicted by a ray";
        // Clipping a ray against a convex part and Embree's watertight triangles may disagree only
        // for a ray through an edge, to rounding.
        EXPECT_LE(double(a.segmentWrong), 1e-4 * double(a.segmentRays)) << name;
        if (std::string(name) == "cornell-box") {
            EXPECT_GT(a.pairs[int(Verdict::Unoccluded)], 0u);
            EXPECT_GT(a.pairs[int(Verdict::Occluded)], 0u);
            EXPECT_GT(a.pairs[int(Verdict::Segments)], 0u);
        }
    }
}

TEST(ShadowCasters, SpheresAndLightsAsCasters) {
    // A sphere and a second (static) rect light hang between a floor and the movable light.
    Scene s = floorScene(0.5f, 3.f);
    addCeilingLight(s, 0.f, 0.f, 2.f, 1.f);
    addRectLight(s, Vec3(0.4f, 1.2f, -0.3f), Vec3(0.5f, 0, 0), Vec3(0, 0, 0.4f), Vec3(2.f));
    Object ball;
    ball.kind = Object::Kind::Sphere;
    ball.name = "ball";
    ball.id = int(s.objects.size());
    ball.center = Vec3(-0.3f, 0.9f, 0.2f);
    ball.radius = 0.25f;
    ball.closed = true;
    s.objects.push_back(ball);
    s.camera.eye = Vec3(0, 3.f, 3.5f);
    s.camera.target = Vec3(0, 0, 0);
    s.camera.fovYDegrees = 50.f;
    const Agreement a = checkScene(s, 40, 32);
    EXPECT_EQ(a.wrong, 0u);
    EXPECT_LE(double(a.segmentWrong), 1e-4 * double(a.segmentRays));
    EXPECT_GT(a.pairs[int(Verdict::Segments)], 0u);
}

TEST(ShadowCasters, HalfHiddenLightHasTheVisibleFractionOfLambertsFormula) {
    // A floor point under a 1×1 light at height 2; an opaque quad at height 1 covers x < 0. Seen from
    // p = (0.3, 0, 0.1) its edge x = 0 falls on the light's plane at x = 0.3 + (0 − 0.3)·2 = −0.3, so
    // the visible light is the part x ∈ [−0.3, 0.5]: its projected solid angle over the whole light's
    // is the visibility ratio, in closed form.
    Scene s = floorScene(0.6f, 4.f);
    addCeilingLight(s, 0.f, 0.f, 2.f, 1.f, 5.f);
    const int blocker = addLambert(s, Vec3(0.5f), "blocker");
    addQuads(s, {{{-3.f, 1.f, -3.f}, {0, 0, 6.f}, {3.f, 0, 0}}}, blocker, "wall");
    const Vec3 p(0.3f, 0.f, 0.1f), n(0, 1, 0);
    Light visible = s.lights[0];
    visible.corner.x = -0.3f;
    visible.edge1.x = 0.8f;
    const double fraction = projectedSolidAngle(visible, p, n) / projectedSolidAngle(s.lights[0], p, n);
    ASSERT_GT(fraction, 0.6);
    ASSERT_LT(fraction, 0.95);

    const Accel accel(s);
    const PathTracer tracer(s, accel, Estimator::NEE, 1);
    const Light movable = tracer.movableLightAt(s.lightPosition());
    const ShadowCasters casters(tracer);
    ClippedLight clipped;
    projectedSolidAngle(s.lights[0], p, n, nullptr, &clipped);
    ShadowCasters::Casters c;
    TraceCounters counters;
    casters.find(accel.spawnOrigin(p, n, n), n, clipped, 0, 0, movable, counters, c);
    EXPECT_EQ(c.verdict, Verdict::Segments);
    EXPECT_EQ(c.count, 1);

    // The estimator's ratio over many pixel keys: its mean converges on the fraction (256 stratified
    // samples leave a per-pixel error of a few 1e-3 and a bias of order 1/N).
    const double lit = 0.6 / 3.14159265358979 * 5.0 * projectedSolidAngle(s.lights[0], p, n);
    for (const bool proofs : {true, false}) {
        ExactDirect::Options o;
        o.proofs = proofs;
        const ExactDirect direct(tracer, 256, 3, o);
        RunningStat st;
        for (uint64_t pixel = 0; pixel < 300; ++pixel)
            st.add(direct.radiance(p, n, Vec3(0, 1, 0), 0, movable, pixel, counters).x / lit);
        EXPECT_NEAR(st.mean, fraction, std::max(4 * st.sigma(), 1e-3)) << (proofs ? "casters" : "Embree");
        EXPECT_LT(st.sigma() * std::sqrt(300.0), 0.01) << "per-pixel spread of the ratio";
    }
}

TEST(ShadowCasters, ARoomSeenFromInsideShadowsItself) {
    // A closed convex box (a room) with the light above it, outside: its own ceiling hides the light
    // from a point on its inside floor, so its own hull may not be left out there.
    Scene s;
    const int white = addLambert(s, Vec3(0.7f));
    std::vector<QuadSpec> faces = inwardCubeFaces(1.f);
    addQuads(s, faces, white, "room");
    s.objects[0].closed = true;
    addCeilingLight(s, 0.f, 0.f, 3.f, 1.f);
    const Accel accel(s);
    const PathTracer tracer(s, accel, Estimator::NEE, 1);
    const Light movable = tracer.movableLightAt(s.lightPosition());
    const ShadowCasters casters(tracer);
    const Vec3 p(0.f, -1.f, 0.f), n(0, 1, 0);  // inside floor, looking up
    ClippedLight clipped;
    ASSERT_GT(projectedSolidAngle(s.lights[0], p, n, nullptr, &clipped), 0.0);
    ShadowCasters::Casters c;
    TraceCounters counters;
    casters.find(accel.spawnOrigin(p, n, n), n, clipped, 0, 0, movable, counters, c);
    EXPECT_NE(c.verdict, Verdict::Unoccluded);
    const ExactDirect direct(tracer, 16, 1);
    EXPECT_EQ(direct.radiance(p, n, Vec3(0, 1, 0), 0, movable, 0, counters).x, 0.f);
}

}  // namespace test_shadow_casters
