// The rendering hard cases of docs/design.md §7: Phong exponents up to 1e6, grazing incidence, points on or
// next to the light's plane, tiny and huge lights, scene scales 1e-3 … 1e4, degenerate geometry and
// rays exactly along edges. Everything must stay finite, and where a closed form exists, right.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "core/scene/accel.h"
#include "core/render/brdf.h"
#include "core/render/path_tracer.h"
#include "core/render/renderer.h"
#include "scene_builders.h"

namespace test_hard_cases {

using namespace rrf;
using namespace rrf::test;

namespace {

constexpr double kPiD = 3.14159265358979323846;

RenderSnapshot render(const Scene& scene, Estimator estimator, int spp, uint64_t seed = 1) {
    const Accel accel(scene);
    return rrf::test::render(scene, accel, estimator, spp, seed);
}

void expectAllFinite(const RenderSnapshot& s, const char* what) {
    EXPECT_EQ(s.nonFinite, 0u) << what;
    EXPECT_EQ(s.global.nonFiniteCount(), 0u) << what;
    EXPECT_EQ(s.direct.nonFiniteCount(), 0u) << what;
    EXPECT_EQ(s.indirect.nonFiniteCount(), 0u) << what;
    EXPECT_EQ(s.variance.nonFiniteCount(), 0u) << what;
}

/// NEE estimate of the floor's direct radiance at p against ρE/π (Lambert's polygon formula),
/// within `rel` where the sample count makes `rel` at least 5 standard errors.
void expectFloorIrradiance(const Scene& scene, float rho, const Vec3& p, int samples, uint64_t seed, const char* what,
                           double rel = 0.01) {
    const double expected = rho / kPiD * polygonIrradiance(scene.lights[0], p, Vec3(0, 1, 0));
    const FloorShading st = shadeFloor(scene, p, samples, seed);
    EXPECT_EQ(st.nonFinite, 0u) << what;
    EXPECT_LE(5 * st.direct.sigma(), rel * expected) << what << ": too few samples";
    EXPECT_NEAR(st.direct.mean, expected, rel * expected) << what << " at " << p;
}

}  // namespace

TEST(HardCases, PhongExponentsUpToOneMillionAreFiniteAndUnbiased) {
    // Directional albedo ∫ f cos θ dω = E[sample weight] (failed samples weigh 0).
    // Normal incidence: exactly kd + ks for any n (see test_brdf). At θo = 60° and n = 1e6 the lobe
    // is a near-delta around the mirror direction: ks (n+2)/(n+1) E[cos θ] = ks cos θo (1 + O(1/n)).
    // The weights are bounded, so 5 standard errors of 20000 samples are a tight, stable bound.
    for (const float n : {1.f, 1e3f, 1e6f}) {
        for (const auto& [kd, ks] : {std::pair{0.3f, 0.5f}, std::pair{0.f, 0.8f}}) {
            const Brdf b = phong(kd, ks, n);
            for (const double thetaO : {0.0, 60.0}) {
                if (thetaO > 0 && n < 1e6f) continue;  // closed form only for the delta-like lobe
                const double c = std::cos(thetaO * kPiD / 180.0);
                const Vec3 wo(float(std::sqrt(1 - c * c)), 0.f, float(c));
                RunningStat st;
                for (int i = 0; i < 20000; ++i) {
                    Rng rng(900, uint64_t(i));
                    Vec3 wi, w;
                    const bool ok = b.sample(wo, rng.uniform(), rng.uniform(), rng.uniform(), wi, w);
                    ASSERT_TRUE(!ok || (w.isFinite() && wi.isFinite() && w.x >= 0.f));
                    ASSERT_TRUE(std::isfinite(b.pdf(wo, wi)) && b.eval(wo, wi).isFinite());
                    st.add(ok ? w.x : 0.0);
                }
                const double expected = kd + ks * c;
                EXPECT_NEAR(st.mean, expected, 5 * st.sigma() + 1e-4 * expected)
                    << "kd " << kd << " ks " << ks << " n " << n << " θo " << thetaO;
            }
        }
    }
    // Furnace with Phong walls at huge exponents: radiance finite, between Le/(1 − kd) and 1.
    for (const float n : {1e3f, 1e6f}) {
        Material m;
        m.type = Material::Type::Phong;
        m.kd = Vec3(0.2f);
        m.ks = Vec3(0.3f);
        m.exponent = n;
        const Scene scene = furnaceScene(0.5f, m, 12);
        for (const Estimator e : {Estimator::NEE, Estimator::Naive}) {
            const RenderSnapshot s = render(scene, e, 32, 4);
            expectAllFinite(s, "Phong furnace");
            const double mean = s.global.mean().x, sigma = imageMeanSigma(s);
            EXPECT_LE(mean, 1.0 + 5 * sigma) << "n = " << n;
            EXPECT_GE(mean, 0.5 / 0.8 - 5 * sigma) << "n = " << n;
        }
    }
}

TEST(HardCases, GrazingIncidence) {
    // ωo a hair above the surface: weights, pdfs and values stay finite; ωo exactly in the plane
    // reflects nothing.
    for (const float n : {1.f, 100.f, 1e6f}) {
        const Brdf b = phong(0.3f, 0.5f, n);
        for (const float z : {1e-7f, 1e-4f, 1e-2f}) {
            const Vec3 wo = normalize(Vec3(1.f, 0.f, z));
            for (int i = 0; i < 2000; ++i) {
                Rng rng(910, uint64_t(i));
                Vec3 wi, w;
                if (b.sample(wo, rng.uniform(), rng.uniform(), rng.uniform(), wi, w)) {
                    ASSERT_TRUE(w.isFinite()) << "n " << n << " z " << z;
                    ASSERT_GT(wi.z, 0.f);
                }
                ASSERT_TRUE(std::isfinite(b.pdf(wo, wi)));
                ASSERT_TRUE(b.eval(wo, wi).isFinite());
            }
        }
    }
    // A glossy floor lit by a rect light, seen at grazing angles: finite; Lambert part unchanged.
    Scene s;
    const int m = addPhong(s, Vec3(0.3f), Vec3(0.5f), 1e6f);
    addQuads(s, {{{-5, 0, -5}, {0, 0, 10}, {10, 0, 0}}}, m, "floor");
    addCeilingLight(s, 0, 0, 1.f, 1.f);
    for (const float z : {0.f, 1e-7f, 1e-3f}) {
        const FloorShading st = shadeFloor(s, Vec3(0.3f, 0, 0.1f), 2000, 911, normalize(Vec3(1.f, z, 0.2f)));
        EXPECT_EQ(st.nonFinite, 0u);
        if (z == 0.f) {
            EXPECT_EQ(st.direct.mean, 0.0) << "ωo in the plane: no reflection";
        }
    }
    // Camera rays skimming the floor: finite image.
    s.camera.eye = Vec3(-4.9f, 1e-4f, 0.f);
    s.camera.target = Vec3(5.f, 0.f, 0.f);
    s.camera.fovYDegrees = 10.f;
    s.camera.width = s.camera.height = 16;
    expectAllFinite(render(s, Estimator::NEE, 16), "grazing camera");
    expectAllFinite(render(s, Estimator::Naive, 16), "grazing camera (naive)");
}

TEST(HardCases, PointsOnOrNextToTheLightPlane) {
    Scene s = floorScene(0.6f, 5.f);
    addCeilingLight(s, 0, 0, 1.f, 1.f);  // covers x, z ∈ [-0.5, 0.5] at y = 1, facing down
    // On the light's plane beside the light (cos θ' = 0 for every light point): exactly 0.
    for (const Vec3 p : {Vec3(2.f, 1.f, 0.f), Vec3(0.5f, 1.f, 0.f), Vec3(-0.5f, 1.f, -0.5f)}) {
        const FloorShading st = shadeFloor(s, p, 1000, 920);
        EXPECT_EQ(st.nonFinite, 0u) << p;
        EXPECT_EQ(st.direct.mean, 0.0) << p;
    }
    // Just below the light's centre (d² → 0): E → πL, finite and never above ρL.
    for (const float h : {1e-3f, 1e-6f}) {
        const FloorShading st = shadeFloor(s, Vec3(0.f, 1.f - h, 0.f), 20000, 921);
        EXPECT_EQ(st.nonFinite, 0u) << h;
        EXPECT_GT(st.direct.mean, 0.0);
        // The estimator is heavy-tailed here (variance ∝ A/h²), so only a loose 6σ upper bound.
        EXPECT_LE(st.direct.mean, 0.6 * 4.0 + 6 * st.direct.sigma()) << h;
    }
    // Above a one-sided light that faces down: its back, exactly 0.
    EXPECT_EQ(shadeFloor(s, Vec3(0.1f, 1.5f, 0.f), 1000, 922).direct.mean, 0.0);
    // A surface lying in the light's plane facing it sideways (normal +x, light to its +x side):
    // every light point has cos θ' = 0, so 0.
    EXPECT_EQ(shadeFloor(s, Vec3(-2.f, 1.f, 0.f), 1000, 923, Vec3(1, 0, 0), Vec3(1, 0, 0)).direct.mean, 0.0);
}

TEST(HardCases, TinyAndHugeLightsMatchTheClosedForm) {
    // Tiny: 1e-4 × 1e-4 (area 1e-8) at height 1; the estimator's relative σ is ≈ 1e-4 per sample
    // under the light, so a few thousand samples suffice for 1% at 5σ.
    {
        Scene s = floorScene(0.6f, 5.f);
        addCeilingLight(s, 0, 0, 1.f, 1e-4f, 1e6f);
        expectFloorIrradiance(s, 0.6f, Vec3(0, 0, 0), 5000, 930, "under a tiny light");
        expectFloorIrradiance(s, 0.6f, Vec3(2.f, 0, 1.f), 5000, 931, "beside a tiny light");
    }
    // Huge: 1e4 × 1e4 (area 1e8) at height 5e3 over a 10 × 10 floor: the light dwarfs the scene.
    // Relative variance ≈ A/(3π h²) ≈ 0.4 per sample: 2e5 samples give σ ≈ 0.15%.
    {
        Scene s = floorScene(0.6f, 5.f);
        addCeilingLight(s, 0, 0, 5e3f, 1e4f, 1.f);
        expectFloorIrradiance(s, 0.6f, Vec3(0, 0, 0), 200000, 932, "under a huge light");
        expectFloorIrradiance(s, 0.6f, Vec3(4.f, 0, -3.f), 200000, 933, "under a huge light, off centre");
    }
}

TEST(HardCases, SceneScaleKeepsTheImage) {
    // Radiance is scale-invariant: the Cornell-like scene scaled by s (camera too, radiance
    // unchanged) renders the same image. Too-small ray offsets (acne) darken it, too-large ones leak
    // light under the block. Paired samples: sample i uses the same camera ray parameters and the
    // same random numbers at every scale, so the per-sample differences d_i = L_s − L_1 are i.i.d.
    // and mostly tiny; the bound is 5 standard errors of d plus 0.5% for float-level divergence.
    const std::vector<float> scales = {1.f, 1e-3f, 1e-1f, 1e2f, 1e4f};
    std::vector<Scene> scenes;
    for (const float sc : scales) scenes.push_back(cornellLike(sc, 24));
    std::vector<std::unique_ptr<Accel>> accels;
    std::vector<std::unique_ptr<PathTracer>> tracers;
    for (const Scene& sc : scenes) {
        accels.push_back(std::make_unique<Accel>(sc));
        tracers.push_back(std::make_unique<PathTracer>(sc, *accels.back(), Estimator::NEE));
    }
    std::vector<RunningStat> diff(scales.size());
    RunningStat ref;
    TraceCounters counters;
    for (int i = 0; i < 100000; ++i) {
        Rng pick(970, uint64_t(i));
        const int px = int(pick.uniformInt(24)), py = int(pick.uniformInt(24));
        const float jx = pick.uniform(), jy = pick.uniform();
        double l1 = 0;
        for (size_t k = 0; k < scales.size(); ++k) {
            const CameraRays cam(scenes[k].camera, 24, 24);
            Rng rng(971, uint64_t(i));
            const Radiance L = tracers[k]->trace(cam.generate(px, py, jx, jy), rng, counters);
            ASSERT_TRUE(L.direct.isFinite() && L.indirect.isFinite()) << "scale " << scales[k];
            const double g = double(L.direct.x) + double(L.indirect.x);
            if (k == 0) {
                l1 = g;
                ref.add(g);
            } else {
                diff[k].add(g - l1);
            }
        }
    }
    for (size_t k = 1; k < scales.size(); ++k) {
        EXPECT_NEAR(diff[k].mean, 0.0, 5 * diff[k].sigma() + 0.005 * ref.mean)
            << "scale " << scales[k] << ": image mean " << ref.mean + diff[k].mean << " vs " << ref.mean;
    }
    // The renderer at the extreme scales: no sample dropped as NaN/Inf.
    for (const float sc : {1e-3f, 1e4f}) {
        expectAllFinite(render(cornellLike(sc, 16), Estimator::NEE, 8), "scaled scene (NEE)");
        expectAllFinite(render(cornellLike(sc, 16), Estimator::Naive, 8), "scaled scene (naive)");
    }
}

TEST(HardCases, ContactShadowsAndLitPointsAtEveryScale) {
    // At each scale s: a floor, a closed block standing on it, a thin plate hovering 1e-3·s above the
    // floor, and a light low beside the block. A floor point under the plate is in its shadow and
    // gets exactly 0 — a ray offset larger than the gap would start the shadow ray above the plate
    // (leak). A lit floor point right beside the block's face gets the closed-form irradiance — an
    // offset too small for the coordinates' float precision self-shadows it (acne).
    for (const float scale : {1e-3f, 1.f, 1e4f}) {
        Scene s = floorScene(0.6f, 2.f * scale);
        const int white = addLambert(s, Vec3(0.7f));
        const float k = scale;
        // Block [0, 0.2] × [0, 1] × [-1, 1] (× s), faces outwards.
        addQuads(s, {{Vec3(0, 0, -1) * k, Vec3(0, 0, 2) * k, Vec3(0, 1, 0) * k},
                     {Vec3(0.2f, 0, -1) * k, Vec3(0, 1, 0) * k, Vec3(0, 0, 2) * k},
                     {Vec3(0, 1, -1) * k, Vec3(0, 0, 2) * k, Vec3(0.2f, 0, 0) * k},
                     {Vec3(0, 0, -1) * k, Vec3(0.2f, 0, 0) * k, Vec3(0, 0, 2) * k},
                     {Vec3(0, 0, -1) * k, Vec3(0, 1, 0) * k, Vec3(0.2f, 0, 0) * k},
                     {Vec3(0, 0, 1) * k, Vec3(0.2f, 0, 0) * k, Vec3(0, 1, 0) * k}},
                 white, "block");
        // Plate x ∈ [-1.5, 0], z ∈ [0.6, 1.6] at height 1e-3 (× s), a single quad.
        addQuads(s, {{Vec3(-1.5f, 1e-3f, 0.6f) * k, Vec3(0, 0, 1) * k, Vec3(1.5f, 0, 0) * k}}, white, "plate");
        // Light on the −x side of the block, facing down: x ∈ [-1, -0.5], z ∈ [-0.25, 0.25], height 0.5.
        s.lights.clear();
        addRectLight(s, Vec3(-1.f, 0.5f, -0.25f) * k, Vec3(0.5f, 0, 0) * k, Vec3(0, 0, 0.5f) * k, Vec3(4.f));
        // Shadowed: under the plate (every ray to the light meets the plate at height 1e-3·s).
        const FloorShading plate = shadeFloor(s, Vec3(-0.75f, 0.f, 1.1f) * k, 2000, 939);
        EXPECT_EQ(plate.nonFinite, 0u);
        EXPECT_EQ(plate.direct.mean, 0.0) << "light leaks under the plate at scale " << scale;
        // Shadowed: just beyond the block's +x face, at its base.
        const FloorShading shadow = shadeFloor(s, Vec3(0.2f + 1e-3f, 0.f, 0.f) * k, 2000, 940);
        EXPECT_EQ(shadow.nonFinite, 0u);
        EXPECT_EQ(shadow.direct.mean, 0.0) << "light leaks through the block at scale " << scale;
        // Lit: floor points just before the block's −x face, found by rays from far above at
        // oblique angles so that each hit point carries the float error of origin + t·dir (≈ 2e-3
        // at s = 1e4, above or below the floor at random), as every real hit does. The NEE estimate
        // divided by the closed form at each hit averages to 1 (5σ ≤ 1% asserted).
        const Accel accel(s);
        const PathTracer tracer(s, accel, Estimator::NEE, 8);
        std::vector<Hit> hits;
        std::vector<Ray> rays;
        std::vector<double> expected;
        for (int j = 0; j < 64; ++j) {
            Ray r;
            r.origin = Vec3(-3.7f + 0.01f * float(j), 2.9f, 1.3f - 0.013f * float(j)) * k;
            r.dir = normalize(Vec3(-0.013f - 0.0003f * float(j), 0.f, 0.007f * float(j % 8)) * k - r.origin);
            Hit hit;
            ASSERT_TRUE(accel.intersect(r, hit));
            ASSERT_EQ(hit.object, 0);
            hits.push_back(hit);
            rays.push_back(r);
            expected.push_back(0.6 / kPiD * polygonIrradiance(s.lights[0], hit.p, Vec3(0, 1, 0)));
        }
        TraceCounters counters;
        RunningStat ratio;
        for (int i = 0; i < 128000; ++i) {
            const size_t j = size_t(i) % hits.size();
            Rng rng(941, uint64_t(i));
            const Radiance L = tracer.shade(hits[j], -rays[j].dir, rng, counters);
            ASSERT_TRUE(L.direct.isFinite());
            ratio.add(L.direct.x / expected[j]);
        }
        EXPECT_LE(5 * ratio.sigma(), 0.01);
        EXPECT_NEAR(ratio.mean, 1.0, 0.01) << "acne at scale " << scale;
    }
}

TEST(HardCases, SharedEdgesAndVerticesAreWatertight) {
    // A floor of 2 × 2 quads sharing edges x = 0, z = 0 and the vertex (0, 0, 0); rays aimed exactly
    // at the shared edges and vertex from random points above must hit (robust Embree traversal),
    // at the right distance and with the floor's normal.
    Scene s;
    const int m = addLambert(s, Vec3(0.5f));
    addQuads(s, {{{-1, 0, -1}, {0, 0, 1}, {1, 0, 0}},
                 {{0, 0, -1}, {0, 0, 1}, {1, 0, 0}},
                 {{-1, 0, 0}, {0, 0, 1}, {1, 0, 0}},
                 {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}}},
             m, "tiles");
    const Accel accel(s);
    int misses = 0;
    for (int i = 0; i < 20000; ++i) {
        Rng rng(950, uint64_t(i));
        const float a = 2.f * rng.uniform() - 1.f;
        Vec3 target;
        switch (i % 3) {
            case 0: target = Vec3(0.f, 0.f, 0.9f * a); break;   // on the edge x = 0
            case 1: target = Vec3(0.9f * a, 0.f, 0.f); break;   // on the edge z = 0
            default: target = Vec3(0.f, 0.f, 0.f); break;       // the shared vertex
        }
        const Vec3 origin(4.f * rng.uniform() - 2.f, 0.05f + 3.f * rng.uniform(), 4.f * rng.uniform() - 2.f);
        Ray r;
        r.origin = origin;
        r.dir = normalize(target - origin);
        Hit h;
        if (!accel.intersect(r, h)) {
            ++misses;
            continue;
        }
        ASSERT_EQ(h.object, 0);
        ASSERT_EQ(h.ng, Vec3(0, 1, 0));
        ASSERT_NEAR(h.t, length(target - origin), 1e-4f * length(target - origin));
    }
    EXPECT_EQ(misses, 0) << "rays slipped between quads sharing an edge or vertex";
}

TEST(HardCases, DegenerateGeometryAndRaysAlongEdges) {
    // Cornell-like scene plus a mesh with a zero-area triangle (repeated vertex), a collinear
    // (needle) triangle and one regular triangle, lying on the floor; and camera-independent rays
    // along quad edges and inside a quad's plane. Nothing may be NaN.
    Scene s = cornellLike(1.f, 16);
    const int white = 0;
    Object mesh;
    mesh.kind = Object::Kind::Triangles;
    mesh.name = "degenerate";
    mesh.id = int(s.objects.size());
    mesh.material = white;
    mesh.positions = {{0.2f, -0.5f, 0.2f}, {0.6f, -0.5f, 0.2f}, {0.4f, -0.5f, 0.2f}, {0.4f, -0.3f, 0.5f},
                      {0.3f, -0.5f, 0.6f}, {0.7f, -0.2f, 0.4f}};
    mesh.indices = {0, 1, 1,   // zero area: repeated vertex
                    0, 2, 1,   // zero area: collinear
                    0, 3, 1,   // regular
                    4, 5, 4};  // zero area
    s.objects.push_back(mesh);
    for (const Estimator e : {Estimator::NEE, Estimator::Naive}) {
        const RenderSnapshot snap = render(s, e, 16);
        expectAllFinite(snap, "degenerate mesh");
    }
    const Accel accel(s);
    const PathTracer tracer(s, accel, Estimator::NEE);
    TraceCounters counters;
    // Rays aimed at the degenerate triangles' vertices and edges.
    for (const Vec3& target : mesh.positions) {
        for (int i = 0; i < 50; ++i) {
            Rng rng(960, uint64_t(i));
            Ray r;
            r.origin = Vec3(0.f, 0.5f, 2.5f) + Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 0.2f;
            r.dir = normalize(target - r.origin);
            const Radiance L = tracer.trace(r, rng, counters);
            ASSERT_TRUE(L.direct.isFinite() && L.indirect.isFinite());
        }
    }
    // Rays exactly along the floor's edges and inside the floor's plane (y = −1): whatever Embree
    // reports for an edge-on quad, the radiance is finite.
    const Vec3 origins[] = {{-1.f, -1.f, 2.f}, {-1.f, -1.f, -1.f}, {-2.f, -1.f, 0.f}, {1.f, -1.f, 1.f}};
    const Vec3 dirs[] = {{0, 0, -1}, {1, 0, 0}, {1, 0, 0}, normalize(Vec3(-1, 0, -1))};
    for (size_t i = 0; i < 4; ++i) {
        Rng rng(961, i);
        Ray r;
        r.origin = origins[i];
        r.dir = dirs[i];
        Hit h;
        if (accel.intersect(r, h)) {
            ASSERT_TRUE(std::isfinite(h.t));
            ASSERT_TRUE(h.p.isFinite() && h.ng.isFinite());
        }
        const Radiance L = tracer.trace(r, rng, counters);
        ASSERT_TRUE(L.direct.isFinite() && L.indirect.isFinite()) << "ray " << i;
    }
}

}  // namespace test_hard_cases
