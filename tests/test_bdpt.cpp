// Bidirectional path tracing (core/render/bdpt.h) against closed forms and against the path tracer,
// never against itself: equal in expectation to NEE per image block (diffuse and glossy boxes), the
// white furnace, Lambert's polygon irradiance (camera and records), a caustic of a near-mirror
// against the mirrored light's irradiance, and identical bits for any thread count, pass split and
// row split.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include <tbb/global_control.h>

#include "core/render/bdpt.h"
#include "core/render/renderer.h"
#include "core/scene/accel.h"
#include "scene_builders.h"

namespace test_bdpt {

using namespace rrf;
using namespace rrf::test;

namespace {

RenderOptions bdptOptions(const Scene& scene, int spp, int samplesPerPass = 0, Estimator e = Estimator::BDPT) {
    RenderOptions o = renderOptions(scene, e, spp, samplesPerPass);
    o.tileSize = 8;
    return o;
}

/// The glossy variant of cornellLike: the block is a near-mirror (exponent 1000, as the glossy
/// box's short box) and the back wall a broad lobe, so the image has caustics on the ceiling.
Scene glossyBox(int size) {
    Scene s = cornellLike(1.f, size, 2.f);
    const int mirror = addPhong(s, Vec3(0.1f), Vec3(0.8f), 1000.f, "near-mirror");
    const int broad = addPhong(s, Vec3(0.45f), Vec3(0.3f), 10.f, "broad");
    for (Object& o : s.objects) {
        if (o.name == "block") o.material = mirror;
        if (o.name == "white walls") o.material = broad;
    }
    return s;
}

/// Per-block z-tests of two renders' means: `blocks` × `blocks` blocks, every channel. Returns the
/// largest |z| and checks that the test could see a bias of 3 % in the typical block.
double largestBlockZ(const RenderSnapshot& a, const RenderSnapshot& b, Term term, int blocks, double& typicalRelSigma) {
    const int w = a.global.width, h = a.global.height, bw = w / blocks, bh = h / blocks;
    double worst = 0.0;
    std::vector<double> rel;
    for (int by = 0; by < blocks; ++by)
        for (int bx = 0; bx < blocks; ++bx)
            for (int c = 0; c < 3; ++c) {
                double ma = 0, mb = 0, va = 0, vb = 0;
                for (int y = by * bh; y < (by + 1) * bh; ++y)
                    for (int x = bx * bw; x < (bx + 1) * bw; ++x) {
                        const size_t i = 3 * (size_t(y) * size_t(w) + size_t(x)) + size_t(c);
                        ma += a.image(term).data[i];
                        mb += b.image(term).data[i];
                        va += a.varianceOf(term).data[i];
                        vb += b.varianceOf(term).data[i];
                    }
                const double sigma = std::sqrt(va + vb);
                if (!(sigma > 0)) continue;
                worst = std::max(worst, std::fabs(ma - mb) / sigma);
                if (mb > 0) rel.push_back(sigma / mb);
            }
    std::sort(rel.begin(), rel.end());
    typicalRelSigma = rel.empty() ? 1.0 : rel[rel.size() / 2];
    return worst;
}

void expectSameAsPathTracer(const Scene& scene, int bdptSpp, int neeSpp) {
    const Accel accel(scene);
    const RenderSnapshot bd = render(scene, accel, bdptOptions(scene, bdptSpp));
    const RenderSnapshot pt = render(scene, accel, bdptOptions(scene, neeSpp, 0, Estimator::NEE));
    EXPECT_EQ(bd.nonFinite, 0u);
    for (Term t : kTerms) {
        double typical = 0;
        const double z = largestBlockZ(bd, pt, t, 2, typical);
        // 12 z-tests per term (2 × 2 blocks, 3 channels): |z| > 4.5 has probability 7e-6 each for
        // equal means.
        EXPECT_LT(z, 4.5) << termName(t);
        EXPECT_LT(typical, 0.01) << termName(t) << ": the blocks must be able to show a 3 % bias";
    }
}

bool sameBits(const Image& a, const Image& b) {
    return a.data.size() == b.data.size() && std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)) == 0;
}

}  // namespace

TEST(Bdpt, EqualsThePathTracerPerBlockOnTheDiffuseBox) { expectSameAsPathTracer(cornellLike(1.f, 16, 2.f), 1024, 4096); }

TEST(Bdpt, EqualsThePathTracerPerBlockOnTheGlossyBox) { expectSameAsPathTracer(glossyBox(16), 1024, 4096); }

TEST(Bdpt, LightTracingWithPathTracingEqualsThePathTracer) {
    const Scene scene = glossyBox(16);
    const Accel accel(scene);
    const PathTracer nee(scene, accel, Estimator::NEE);
    const BidirectionalTracer full(nee, 64, false), light(nee, 64, true);
    EXPECT_FALSE(full.lightTracingOnly());
    EXPECT_TRUE(light.lightTracingOnly());
    // Records: the two strategy sets against NEE at one glossy-lit point of the floor.
    Hit hit;
    Ray r;
    r.origin = Vec3(0.3f, 0.5f, 0.5f);
    r.dir = normalize(Vec3(0.f, -1.f, -0.2f));
    ASSERT_TRUE(nee.intersect(r, hit));
    RunningStat sNee, sFull, sLight;
    TraceCounters c;
    for (int i = 0; i < 200000; ++i) {
        Rng a(7, 1, uint64_t(i)), b(7, 2, uint64_t(i)), d(7, 3, uint64_t(i));
        sNee.add(nee.shade(hit, -r.dir, a, c).global().x);
        sFull.add(full.shade(hit, -r.dir, nee.light(0, nee.scene().lights[0]), b, c).global().x);
        sLight.add(light.shade(hit, -r.dir, nee.light(0, nee.scene().lights[0]), d, c).global().x);
    }
    EXPECT_NEAR(sFull.mean, sNee.mean, 4.5 * std::hypot(sFull.sigma(), sNee.sigma()));
    EXPECT_NEAR(sLight.mean, sNee.mean, 4.5 * std::hypot(sLight.sigma(), sNee.sigma()));
    EXPECT_LT(sNee.sigma(), 0.01 * sNee.mean);
}

TEST(Bdpt, WhiteFurnace) {
    // Closed cube of emitters (Le = 1) that also reflect (albedo 0.5): every ray sees Le / (1 − a) = 2.
    Material wall;
    wall.kd = Vec3(0.5f);
    const Scene scene = furnaceScene(1.f, wall, 8);
    const Accel accel(scene);
    const RenderSnapshot s = render(scene, accel, bdptOptions(scene, 256));
    EXPECT_EQ(s.nonFinite, 0u);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(s.global.mean()[c], 2.0, 5 * imageMeanSigma(s, c) + 1e-3);
        EXPECT_LT(imageMeanSigma(s, c), 0.005);
        EXPECT_NEAR(s.direct.mean()[c], 1.5, 0.02) << "emission seen (1) plus one reflection (0.5)";
    }
}

TEST(Bdpt, LambertPolygonIrradianceSeenByTheCameraAndByRecords) {
    // A floor under a square light: radiance ρ/π · E(p), E from Lambert's polygon formula. The floor is
    // the only surface, so there is no indirect light; the camera looks straight down at a small patch.
    const float rho = 0.6f;
    Scene scene = floorScene(rho, 4.f);
    addCeilingLight(scene, 0.3f, -0.2f, 1.f, 0.5f, 4.f);
    scene.camera.eye = Vec3(0.f, 0.8f, 0.f);
    scene.camera.target = Vec3(0.f, 0.f, 0.f);
    scene.camera.up = Vec3(0, 0, -1);
    scene.camera.fovYDegrees = 2.f;
    scene.camera.width = scene.camera.height = 8;
    const Accel accel(scene);
    const double expected = rho / kPi * polygonIrradiance(scene.lights[0], Vec3(0.f), Vec3(0, 1, 0));
    const RenderSnapshot s = render(scene, accel, bdptOptions(scene, 512));
    EXPECT_NEAR(s.global.mean()[0], expected, 5 * imageMeanSigma(s) + 2e-3 * expected);
    EXPECT_EQ(s.indirect.mean()[0], 0.f);
    const PathTracer nee(scene, accel, Estimator::NEE);
    const BidirectionalTracer bd(nee, 64);
    RunningStat st;
    TraceCounters c;
    for (int i = 0; i < 100000; ++i) {
        Rng rng(3, 9, uint64_t(i));
        st.add(bd.shade(surfaceHit(Vec3(0.f)), Vec3(0, 1, 0), scene.lights[0], rng, c).direct.x);
    }
    EXPECT_NEAR(st.mean, expected, 5 * st.sigma() + 1e-4);
    EXPECT_LT(st.sigma(), 0.003 * expected);
}

TEST(Bdpt, CausticOfANearMirrorMatchesTheMirroredLightsIrradiance) {
    // A near-mirror floor (Phong exponent 1e4, ks 0.9, y = 0) reflects a downward light (y = 1) onto a
    // diffuse ceiling beside it (y = 1, facing down): the ceiling sees the light only in the mirror.
    // For a lobe this narrow the mirror reflects ks · L · cosθ along the mirror direction, so the
    // ceiling's irradiance is E = ks Le ∫_image ω_y² dω over the light's mirror image (y = −1), the
    // ceiling's radiance ρ/π · E. Depth 2 keeps paths of the caustic only (light, mirror, ceiling).
    const float rho = 0.7f, ks = 0.9f, le = 10.f;
    const Scene s = mirrorCausticScene(1e4f, ks, rho, le, 32);
    const Accel accel(s);
    RenderOptions o = bdptOptions(s, 1024);
    o.maxDepth = 2;
    const RenderSnapshot snap = render(s, accel, o);
    EXPECT_EQ(snap.nonFinite, 0u);
    // Expected radiance per pixel at its centre's ceiling point (E is smooth across the view).
    const CameraRays rays(s.camera, 32, 32);
    double sumExpected = 0, sumImage = 0, sumVar = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            const Ray r = rays.generate(x, y, 0.5f, 0.5f);
            const float t = (1.f - r.origin.y) / r.dir.y;
            const Vec3 p = r.origin + r.dir * t;
            sumExpected += rho / kPi * ks * le * mirroredLightIntegral(p);
            const size_t k = 3 * (size_t(y) * 32 + size_t(x));
            sumImage += snap.global.data[k];
            sumVar += snap.variance.data[k];
        }
    const double sigma = std::sqrt(sumVar);
    EXPECT_LT(sigma, 0.01 * sumExpected) << "the test must see a 3 % error";
    EXPECT_NEAR(sumImage, sumExpected, 4 * sigma + 0.01 * sumExpected);
    EXPECT_EQ(snap.direct.mean()[0], 0.f) << "the ceiling is edge-on to the light: nothing direct";
}

TEST(Bdpt, IdenticalForAnyThreadCountPassSplitAndRowSplit) {
    const Scene scene = glossyBox(16);
    const Accel accel(scene);
    RenderSnapshot one, many, split;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = render(scene, accel, bdptOptions(scene, 8, 8));
    }
    many = render(scene, accel, bdptOptions(scene, 8, 8));
    split = render(scene, accel, bdptOptions(scene, 8, 3));
    EXPECT_TRUE(sameBits(one.global, many.global));
    EXPECT_TRUE(sameBits(one.variance, many.variance));
    EXPECT_TRUE(sameBits(one.global, split.global));
    EXPECT_TRUE(sameBits(one.indirectVariance, split.indirectVariance));
    // Rows split across two parts: each part's rows are the whole render's.
    for (int part = 0; part < 2; ++part) {
        RenderOptions o = bdptOptions(scene, 8, 8);
        o.rowOffset = part;
        o.rowStride = 2;
        const RenderSnapshot rows = render(scene, accel, o);
        for (int y = part; y < 16; y += 2)
            EXPECT_EQ(0, std::memcmp(&rows.global.data[size_t(y) * 48], &one.global.data[size_t(y) * 48], 48 * sizeof(float)))
                << "row " << y;
    }
}

TEST(Bdpt, AutoChoosesItForCausticsOnly) {
    const Scene diffuse = cornellLike(1.f, 8);
    const Scene glossy = glossyBox(8);
    EXPECT_EQ(chooseEstimator(Estimator::Auto, Effects::derive(diffuse)).estimator, Estimator::NEE);
    const EstimatorChoice g = chooseEstimator(Estimator::Auto, Effects::derive(glossy));
    EXPECT_EQ(g.estimator, Estimator::BDPT);
    EXPECT_NE(g.reason.find("caustics"), std::string::npos);
    EXPECT_EQ(chooseEstimator(Estimator::NEE, Effects::derive(glossy)).estimator, Estimator::NEE);
    EXPECT_EQ(chooseEstimator(Estimator::BDPT, Effects::derive(diffuse)).estimator, Estimator::BDPT);
    // Broad lobes only (exponent 10): the path tracer's MIS finds them.
    Scene broad = cornellLike(1.f, 8);
    const int m = addPhong(broad, Vec3(0.4f), Vec3(0.3f), 10.f);
    broad.objects[0].material = m;
    EXPECT_EQ(chooseEstimator(Estimator::Auto, Effects::derive(broad)).estimator, Estimator::NEE);
    const Accel accel(glossy);
    const Renderer r(glossy, accel, bdptOptions(glossy, 1, 1, Estimator::Auto));
    EXPECT_EQ(r.estimatorChoice().estimator, Estimator::BDPT);
    EXPECT_EQ(r.options().estimator, Estimator::BDPT);
}

}  // namespace test_bdpt
