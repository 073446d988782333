// White-furnace tests of the path tracer and basic properties of trace()/shade().
//
// Furnace: six one-sided emitters (Le = 0.5) close a cube; each also reflects with a Lambert albedo
// a = 0.5. Every camera ray then sees L = Le / (1 − a) = 1 exactly. Split by bounces:
// direct = Le + a·Le = 0.75 (emission seen + one reflection), indirect = a²Le/(1 − a) = 0.25.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/scene/accel.h"
#include "core/render/path_tracer.h"
#include "core/render/renderer.h"
#include "core/scene/camera_rays.h"
#include "core/scene/scene_json.h"
#include "scene_builders.h"

namespace test_path_tracer {

using namespace rrf;
using namespace rrf::test;

namespace {

Material lambertWall(float albedo) {
    Material m;
    m.type = Material::Type::Lambert;
    m.kd = Vec3(albedo);
    return m;
}

Material phongWall(float kd, float ks, float n) {
    Material m;
    m.type = Material::Type::Phong;
    m.kd = Vec3(kd);
    m.ks = Vec3(ks);
    m.exponent = n;
    return m;
}

/// direct + indirect == global per pixel, exactly: the renderer stores global as the float sum of the
/// stored direct and indirect images.
void expectSumIsGlobal(const RenderSnapshot& s) {
    for (size_t i = 0; i < s.global.data.size(); ++i) {
        const float g = s.global.data[i], sum = s.direct.data[i] + s.indirect.data[i];
        ASSERT_EQ(sum, g) << "pixel value " << i;
    }
}

void lambertFurnace(Estimator estimator, int spp, int traceSamples) {
    const Scene scene = furnaceScene(0.5f, lambertWall(0.5f));
    const Accel accel(scene);
    // Renderer: image mean and every pixel.
    const RenderSnapshot snap = render(scene, accel, estimator, spp);
    EXPECT_EQ(snap.nonFinite, 0u);
    EXPECT_EQ(snap.global.nonFiniteCount(), 0u);
    const double sigma = imageMeanSigma(snap);
    EXPECT_LE(5 * sigma, 0.01) << "too few samples for a 1% check";
    EXPECT_NEAR(snap.global.mean().x, 1.0, 0.01);
    for (int y = 0; y < snap.global.height; ++y)
        for (int x = 0; x < snap.global.width; ++x) {
            // Each pixel within 6 of its own standard errors (256 pixels: a correct renderer fails
            // this with probability < 1e-6).
            const double sd = std::sqrt(double(snap.variance.at(x, y).x));
            EXPECT_NEAR(snap.global.at(x, y).x, 1.0, 6 * sd + 1e-6) << "pixel " << x << "," << y;
        }
    expectSumIsGlobal(snap);
    // The split: i.i.d. samples of the image mean give exact standard errors for direct and indirect.
    const ImageMeanStats st = traceImageMean(scene, accel, estimator, traceSamples, 7);
    EXPECT_EQ(st.nonFinite, 0u);
    EXPECT_LE(5 * st.direct.sigma(), 0.01 * 0.75);
    EXPECT_NEAR(st.direct.mean, 0.75, 0.01 * 0.75) << "σ = " << st.direct.sigma();
    EXPECT_NEAR(st.indirect.mean, 0.25, 5 * st.indirect.sigma()) << "σ = " << st.indirect.sigma();
    EXPECT_NEAR(st.global.mean, 1.0, 0.01);
}

/// Directional albedo a(μ) = ∫ f(ωo, ωi) cosθi dωi of the modified Phong BRDF at cosθo = μ, by
/// quadrature in the lobe's own coordinates: with s = cos^{n+1}α the lobe's weight
/// (n+2)/(2π) cos^n α dω becomes (n+2)/(2π(n+1)) ds dφ, smooth in s even for n = 1000, and the
/// horizon (cosθi ≤ 0) is clipped by the integrand. The diffuse part contributes kd exactly.
double phongAlbedo(double kd, double ks, double n, double mu) {
    const double pi = 3.14159265358979323846, sinO = std::sqrt(std::max(0.0, 1 - mu * mu));
    static const GaussLegendre gl(8);
    const double lobe = gl.integrate(
        [&](double sv) {
            const double cosA = std::pow(sv, 1 / (n + 1)), sinA = std::sqrt(std::max(0.0, -std::expm1(2 * std::log(sv) / (n + 1))));
            return gl.integrate([&](double phi) { return std::max(0.0, sinA * std::cos(phi) * sinO + cosA * mu); }, 0,
                                2 * pi, 32);
        },
        0, 1, 32);
    return kd + ks * (n + 2) / (2 * pi * (n + 1)) * lobe;
}

}  // namespace

// Sample counts: the naive estimator's per-sample standard deviation here is ≈ 0.6, NEE's ≈ 2 for
// the global value (uniform area sampling of the emitter on the adjacent face has a variance that
// grows like 1/ε² for points ε from a cube edge, so its tail is heavy), ≈ 0.6 for direct.
// 1% ≥ 5σ needs σ ≤ 0.002: 16×16 pixels × 1024 spp (naive), × 4096 spp (NEE); 4e5 traced samples
// for the direct/indirect split (naive direct is exact: its first bounce always hits an emitter).
TEST(PathTracer, WhiteFurnaceNEE) { lambertFurnace(Estimator::NEE, 4096, 400000); }

TEST(PathTracer, WhiteFurnaceNaive) { lambertFurnace(Estimator::Naive, 1024, 100000); }

TEST(PathTracer, PhongFurnaceNeverExceedsOne) {
    // Walls with kd + ks = 0.5: at normal incidence the albedo is exactly 0.5, elsewhere less
    // (modified Phong loses energy towards grazing), so Le ≤ ... ≤ L ≤ Le/(1 − 0.5) = 1; the diffuse
    // part alone guarantees L ≥ Le/(1 − kd). Bounds checked with 5 standard errors of slack.
    for (const float n : {1.f, 10.f, 1000.f}) {
        const Scene scene = furnaceScene(0.5f, phongWall(0.2f, 0.3f, n));
        const Accel accel(scene);
        for (const Estimator e : {Estimator::NEE, Estimator::Naive}) {
            const RenderSnapshot snap = render(scene, accel, e, 64, 3);
            EXPECT_EQ(snap.nonFinite, 0u);
            EXPECT_EQ(snap.global.nonFiniteCount(), 0u);
            const double mean = snap.global.mean().x, sigma = imageMeanSigma(snap);
            EXPECT_LE(mean, 1.0 + 5 * sigma) << "n = " << n;
            EXPECT_GE(mean, 0.5 / (1 - 0.2) - 5 * sigma) << "n = " << n;
            EXPECT_GE(snap.direct.mean().x, 0.5) << "emission alone is 0.5";
            expectSumIsGlobal(snap);
        }
    }
}

TEST(PathTracer, PhongFurnaceDirectLightIsEmissionTimesOnePlusAlbedo) {
    // In the furnace every wall point receives Le from its whole hemisphere, so the direct radiance
    // (emission seen + one reflection of it) is exactly Le (1 + a(θo)), with a the directional
    // albedo at the camera ray's angle to the wall it hits. The camera sits at the cube's centre, so
    // cosθo = the largest |component| of the unit ray direction. The image mean of that closed form
    // (a table of a(μ) by quadrature, averaged over the renderer's own pixel and jitter distribution)
    // must match the renderer's direct image; ignoring ks, or misplacing the lobe, cannot.
    const float le = 0.5f, kd = 0.2f, ks = 0.3f;
    for (const float n : {1.f, 10.f, 1000.f}) {
        std::vector<double> table(129);
        for (size_t i = 0; i < table.size(); ++i) table[i] = phongAlbedo(kd, ks, n, double(i) / 128.0);
        const Scene scene = furnaceScene(le, phongWall(kd, ks, n));
        const CameraRays cam(scene.camera, scene.camera.width, scene.camera.height);
        RunningStat expected;
        for (int i = 0; i < 20000; ++i) {
            Rng rng(12, uint64_t(i));
            const int px = int(rng.uniformInt(uint32_t(scene.camera.width))), py = int(rng.uniformInt(uint32_t(scene.camera.height)));
            const float jx = rng.uniform(), jy = rng.uniform();
            const Vec3 d = normalize(cam.generate(px, py, jx, jy).dir);
            const double mu = std::max({std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)}) * 128.0;
            const size_t k = std::min<size_t>(size_t(mu), 127);
            const double a = table[k] + (mu - double(k)) * (table[k + 1] - table[k]);
            expected.add(le * (1 + a));
        }
        const Accel accel(scene);
        // The naive estimator samples the lobe and always hits an emitter, so its direct estimate is
        // nearly noise-free. (NEE samples the emitters' area: near the cube's edges its variance grows
        // like 1/ε², README's known limitations, so its standard error here does not shrink usefully
        // with more samples; NEE ≡ naive on glossy surfaces is test_glossy_transport.cpp's job.)
        const RenderSnapshot snap = render(scene, accel, Estimator::Naive, 64, 5);
        double directVar = 0;
        for (const float v : snap.directVariance.data) directVar += v;
        const double sigma =
            std::hypot(std::sqrt(directVar / 3) / double(snap.directVariance.pixelCount()), expected.sigma());
        EXPECT_LT(5 * sigma, 0.01 * expected.mean) << "n = " << n;
        EXPECT_NEAR(snap.direct.mean().x, expected.mean, 5 * sigma + 2e-3 * expected.mean)
            << "n = " << n << "; ignoring ks would give "
            << le * (1 + kd);
    }
}

TEST(PathTracer, MissAndBlackEmitterBack) {
    // A ray that hits nothing carries no radiance; a one-sided black emitter seen from behind is black.
    Scene s;
    addRectLight(s, Vec3(-1, -1, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), Vec3(3.f));  // normal +z
    const Accel accel(s);
    const PathTracer tracer(s, accel, Estimator::NEE);
    TraceCounters counters;
    Rng rng(1, 0);
    Ray miss;
    miss.origin = Vec3(0, 0, 5);
    miss.dir = Vec3(0, 0, 1);
    EXPECT_TRUE(tracer.trace(miss, rng, counters).global().isZero());
    Ray front = miss;
    front.dir = Vec3(0, 0, -1);  // from the +z side: sees the emitting face
    EXPECT_EQ(tracer.trace(front, rng, counters).direct, Vec3(3.f));
    Ray back;
    back.origin = Vec3(0, 0, -5);
    back.dir = Vec3(0, 0, 1);
    EXPECT_TRUE(tracer.trace(back, rng, counters).global().isZero());
    EXPECT_EQ(counters.rays, 3u);
}

/// traceBatch() against trace() sample by sample: the packets (camera rays, first shadow rays) must
/// not change a path's random numbers, its arithmetic or what its rays hit. Batches are whole rows of
/// 16 pixels and one pixel's 16 samples, as the renderer forms them.
void expectBatchIsTrace(const Scene& scene, Estimator estimator, const std::string& what, path_lanes::Isa lanes,
                        int maxDepth = 64, const std::string& embree = "") {
    const Accel accel(scene, embree);
    PathTracer tracer(scene, accel, estimator, maxDepth);
    tracer.setLanes(lanes);
    if (tracer.lanes() != lanes) return;  // this scene or estimator runs no lanes: the portable run covers it
    const int w = 48, h = 48;
    const CameraRays cam(scene.camera, w, h);
    TraceCounters one, batch;
    int compared = 0, lit = 0;
    for (int y = 0; y < h; ++y)
        for (int x0 = 0; x0 < w; x0 += 16) {
            const int width = y % 2 == 0 ? 16 : 1;  // a row of 16 pixels, or one pixel's 16 samples
            Ray rays[16];
            Rng rngs[16] = {Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0),
                            Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0)};
            Radiance expected[16], got[16];
            uint64_t after[16];
            const int count = y % 3 == 0 ? 16 : 7 + x0 / 16;  // partial packets too
            for (int i = 0; i < count; ++i) {
                const int x = x0 + (width == 16 ? i : 0);
                Rng rng(5, uint64_t(y * w + x), uint64_t(i));
                const float jx = rng.uniform(), jy = rng.uniform();
                rays[i] = cam.generate(x, y, jx, jy);
                rngs[i] = rng;
                expected[i] = tracer.trace(rays[i], rng, one);
                after[i] = rng.state();
            }
            tracer.traceBatch(rays, rngs, count, batch, got);
            for (int i = 0; i < count; ++i) {
                ASSERT_EQ(got[i].direct, expected[i].direct) << what << ", pixel row " << y << ", path " << i;
                ASSERT_EQ(got[i].indirect, expected[i].indirect) << what << ", pixel row " << y << ", path " << i;
                ASSERT_EQ(rngs[i].state(), after[i]) << what << ": the path drew other random numbers, row " << y << ", path " << i;
                ++compared;
                lit += !expected[i].global().isZero();
            }
        }
    EXPECT_EQ(batch.rays, one.rays) << what;
    EXPECT_EQ(batch.shadowRays, one.shadowRays) << what;
    // Not a comparison of zeros: with NEE most samples carry light, naive ones only where a bounce
    // happens to hit the light.
    if (estimator == Estimator::NEE) {
        EXPECT_GT(lit, compared / 2) << what;
        EXPECT_GE(2 * one.shadowRays, uint64_t(compared)) << what;  // shadow rays were traced
    } else {
        EXPECT_GT(lit, 0) << what;
    }
}

/// expectBatchIsTrace() with the portable lockstep and each of the lanes this build and CPU run.
void expectBatchIsTrace(const Scene& scene, Estimator estimator, const std::string& what, int maxDepth = 64,
                        const std::string& embree = "") {
    for (path_lanes::Isa isa : {path_lanes::Isa::None, path_lanes::Isa::Avx2, path_lanes::Isa::Avx512})
        if (path_lanes::isaSupported(isa))
            expectBatchIsTrace(scene, estimator, what + ", " + path_lanes::isaName(isa), isa, maxDepth, embree);
}

TEST(PathTracer, BatchIsTracePerSampleOnTheBundledScenes) {
    for (const char* name : {"cornell-box", "cornell-glossy", "mesh-room"}) {
        const Scene scene = loadScene(std::string(RRF_SOURCE_DIR) + "/projects/" + name + "/scene.json");
        for (Estimator e : {Estimator::NEE, Estimator::Naive}) {
            expectBatchIsTrace(scene, e, std::string(name) + (e == Estimator::NEE ? " nee" : " naive"));
        }
    }
}

TEST(PathTracer, BatchIsTracePerSampleWithSeveralLightsOfEveryKind) {
    // Two rect lights and a point light: three light samples per vertex, traced as packets by light.
    Scene s = cornellLike();
    addRectLight(s, Vec3(-0.9f, -0.5f, -0.99f), Vec3(0.3f, 0, 0), Vec3(0, 0.3f, 0), Vec3(4.f));  // before the back wall, facing +z
    addPointLight(s, Vec3(0.5f, 0.5f, 0.2f), Vec3(1.5f));
    expectBatchIsTrace(s, Estimator::NEE, "cornell-like, three lights");
    s.materials[0] = phongWall(0.4f, 0.3f, 200.f);  // the white walls glossy: MIS on every light sample
    expectBatchIsTrace(s, Estimator::NEE, "cornell-like, three lights, glossy");
}

/// A diffuse scene whose bounce rays arrive everywhere the lanes (render/path_lanes.h) tell apart:
/// flat quads from their tables, a sphere and a mesh with vertex normals set up one by one, the
/// movable light, a second light that reflects (its own material) and a black emitter that ends the
/// path, beside a point light. Embree's sphere test answers a packet and a single ray differently
/// in the last bit now and then, so the comparison with trace() leaves the sphere out.
Scene everyArrival(bool withSphere) {
    Scene s = cornellLike();
    Object ball;
    ball.kind = Object::Kind::Sphere;
    ball.name = "ball";
    ball.id = int(s.objects.size());
    ball.material = 0;
    ball.center = Vec3(0.45f, -0.7f, 0.1f);
    ball.radius = 0.3f;
    ball.closed = true;
    if (withSphere) s.objects.push_back(ball);
    // A smooth tent of two triangles whose vertex normals lean away from the face normal.
    Object tent;
    tent.kind = Object::Kind::Triangles;
    tent.name = "tent";
    tent.id = int(s.objects.size());
    tent.material = 1;
    tent.positions = {Vec3(0.2f, -1.f, -0.9f), Vec3(0.9f, -1.f, -0.9f), Vec3(0.55f, 0.f, -0.6f), Vec3(0.55f, -1.f, -0.3f)};
    tent.indices = {0, 1, 2, 1, 3, 2};
    tent.normals = {normalize(Vec3(-0.3f, 0.2f, 1.f)), normalize(Vec3(0.3f, 0.2f, 1.f)), normalize(Vec3(0.f, 1.f, 0.4f)),
                    normalize(Vec3(0.4f, 0.1f, 1.f))};
    s.objects.push_back(tent);
    s.movableLight = 0;  // the ceiling light
    addRectLight(s, Vec3(-0.99f, -0.6f, -0.6f), Vec3(0, 0, 0.4f), Vec3(0, 0.3f, 0), Vec3(2.f), false, 0);  // two-sided, reflects
    addRectLight(s, Vec3(0.98f, 0.2f, -0.5f), Vec3(0, 0.3f, 0), Vec3(0, 0, 0.3f), Vec3(1.f, 2.f, 3.f), true, -1);  // black emitter
    addPointLight(s, Vec3(0.3f, 0.6f, 0.4f), Vec3(0.8f));
    return s;
}

TEST(PathTracer, LanesRunWhereTheBuildAndCpuHaveThem) {
    const Scene cornell = loadScene(std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/scene.json");
    const Accel accel(cornell);
    // Diffuse NEE takes the lanes wherever they exist, so the batch tests above compare them with trace().
    EXPECT_EQ(PathTracer(cornell, accel, Estimator::NEE).lanes(), path_lanes::bestIsa());
    EXPECT_EQ(PathTracer(cornell, accel, Estimator::Naive).lanes(), path_lanes::Isa::None);
    const Scene glossy = loadScene(std::string(RRF_SOURCE_DIR) + "/projects/cornell-glossy/scene.json");
    const Accel glossyAccel(glossy);
    EXPECT_EQ(PathTracer(glossy, glossyAccel, Estimator::NEE).lanes(), path_lanes::Isa::None);
    const Scene every = everyArrival(true);
    const Accel everyAccel(every);
    EXPECT_EQ(PathTracer(every, everyAccel, Estimator::NEE).lanes(), path_lanes::bestIsa());
}

TEST(PathTracer, BatchIsTracePerSampleWhereverABounceArrives) {
    expectBatchIsTrace(everyArrival(false), Estimator::NEE, "every arrival");
    expectBatchIsTrace(everyArrival(false), Estimator::Naive, "every arrival, naive");
}

TEST(PathTracer, BatchIsTracePerSampleAtEveryDepthLimit) {
    // Limits inside the lanes' lockstep end paths there (no bounce at the last vertex).
    for (int maxDepth : {1, 2, 3, 4, 5})
        expectBatchIsTrace(everyArrival(false), Estimator::NEE, "max depth " + std::to_string(maxDepth), maxDepth);
    // A floor alone under its light: no light travels between surfaces, so no vertex bounces.
    Scene floor;
    const int white = addLambert(floor, Vec3(0.7f), "white");
    addQuads(floor, {QuadSpec{Vec3(-3, -1, -3), Vec3(0, 0, 6), Vec3(6, 0, 0)}}, white, "floor");
    addRectLight(floor, Vec3(-0.25f, 0.9f, -0.25f), Vec3(0.5f, 0, 0), Vec3(0, 0, 0.5f), Vec3(5.f));
    floor.camera = cornellLike().camera;
    floor.camera.eye = Vec3(0.f, 1.5f, 2.5f);
    floor.camera.target = Vec3(0.f, -1.f, 0.f);
    ASSERT_FALSE(Effects::derive(floor).indirect);
    expectBatchIsTrace(floor, Estimator::NEE, "floor alone");
}

TEST(PathTracer, BatchIsTracePerSampleOnEmbreesNarrowerKernels) {
    // Without 16-wide kernels (CPUs without AVX-512) Embree splits a packet and tells its active rays
    // by their interval, not by the valid mask: lanes off must carry an empty one.
    const Scene cornell = loadScene(std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/scene.json");
    expectBatchIsTrace(cornell, Estimator::NEE, "cornell-box, Embree at AVX2", 64, "max_isa=avx2");
    expectBatchIsTrace(everyArrival(false), Estimator::NEE, "every arrival, Embree at AVX2", 64, "max_isa=avx2");
}

TEST(PathTracer, LanesAreThePortableBatchWithASphere) {
    // The lanes trace deeper vertices as packets than the portable lockstep does, so the sphere's
    // last bits may differ (above); everything else agrees.
    const Scene scene = everyArrival(true);
    const Accel accel(scene);
    for (path_lanes::Isa isa : {path_lanes::Isa::Avx2, path_lanes::Isa::Avx512}) {
        if (!path_lanes::isaSupported(isa)) continue;
        SCOPED_TRACE(path_lanes::isaName(isa));
        PathTracer lanes(scene, accel, Estimator::NEE), portable(scene, accel, Estimator::NEE);
        lanes.setLanes(isa);
        portable.setLanes(path_lanes::Isa::None);
        ASSERT_EQ(lanes.lanes(), isa);
        const int w = 48, h = 48;
        const CameraRays cam(scene.camera, w, h);
        TraceCounters a, b;
        int lit = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                Ray rays[16];
                Rng ra[16] = {Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0),
                              Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0)};
                Rng rb[16] = {Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0),
                              Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0)};
                for (int i = 0; i < 16; ++i) {
                    Rng rng(11, uint64_t(y * w + x), uint64_t(i));
                    const float jx = rng.uniform(), jy = rng.uniform();
                    rays[i] = cam.generate(x, y, jx, jy);
                    ra[i] = rb[i] = rng;
                }
                Radiance got[16], expected[16];
                lanes.traceBatch(rays, ra, 16, a, got);
                portable.traceBatch(rays, rb, 16, b, expected);
                auto near = [](const Vec3& g, const Vec3& e) {
                    for (int c = 0; c < 3; ++c)
                        if (!(std::fabs(g[c] - e[c]) <= 1e-5f * std::fabs(e[c]))) return false;
                    return true;
                };
                for (int i = 0; i < 16; ++i) {
                    ASSERT_TRUE(near(got[i].direct, expected[i].direct)) << got[i].direct << " against " << expected[i].direct << ", pixel " << x << ", " << y << ", sample " << i;
                    ASSERT_TRUE(near(got[i].indirect, expected[i].indirect)) << got[i].indirect << " against " << expected[i].indirect << ", pixel " << x << ", " << y << ", sample " << i;
                    lit += !expected[i].indirect.isZero();
                }
            }
        EXPECT_EQ(a.rays, b.rays);
        EXPECT_EQ(a.shadowRays, b.shadowRays);
        EXPECT_GT(lit, w * h * 16 / 2);
    }
}

/// shadeBatch() against shade() path by path, from the hits of camera rays and with the movable light
/// moved as the data generator moves it: the lanes start every path at one vertex and carry the moved
/// light; the portable route is shade() itself.
void expectShadeBatchIsShade(const Scene& scene, const std::string& what) {
    const Accel accel(scene);
    PathTracer tracer(scene, accel, Estimator::NEE);
    const CameraRays cam(scene.camera, 12, 12);
    const Vec3 moves[] = {scene.lights[size_t(scene.movableLight)].center(), Vec3(0.3f, 0.9f, -0.2f), Vec3(-0.4f, 0.8f, 0.5f)};
    for (path_lanes::Isa isa : {path_lanes::Isa::None, path_lanes::Isa::Avx2, path_lanes::Isa::Avx512}) {
        if (!path_lanes::isaSupported(isa)) continue;
        tracer.setLanes(isa);
        SCOPED_TRACE(what + ", " + path_lanes::isaName(isa));
        TraceCounters one, batch;
        int lit = 0;
        for (int y = 0; y < 12; ++y)
            for (int x = 0; x < 12; ++x) {
                const Light movable = tracer.movableLightAt(moves[(x + y) % 3]);
                const Ray ray = cam.generate(x, y, 0.5f, 0.5f);
                Hit hit;
                if (!tracer.intersect(ray, movable, hit)) continue;
                const int n = 1 + (x * 7 + y) % 16;  // partial batches too
                Rng rngs[16] = {Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0),
                                Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0)};
                Radiance expected[16], got[16];
                for (int i = 0; i < n; ++i) {
                    rngs[i] = Rng(3, uint64_t(y * 12 + x), uint64_t(i));
                    Rng rng = rngs[i];
                    expected[i] = tracer.shade(hit, -ray.dir, movable, rng, one);
                }
                tracer.shadeBatch(hit, -ray.dir, movable, rngs, n, batch, got);
                for (int i = 0; i < n; ++i) {
                    ASSERT_EQ(got[i].direct, expected[i].direct) << "pixel " << x << ", " << y << ", path " << i;
                    ASSERT_EQ(got[i].indirect, expected[i].indirect) << "pixel " << x << ", " << y << ", path " << i;
                    lit += !expected[i].indirect.isZero();
                }
            }
        EXPECT_EQ(batch.rays, one.rays);
        EXPECT_EQ(batch.shadowRays, one.shadowRays);
        EXPECT_GT(lit, 100);
    }
}

TEST(PathTracer, ShadeBatchIsShadePerPathWithTheLightMoved) {
    expectShadeBatchIsShade(loadScene(std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/scene.json"), "cornell-box");
    expectShadeBatchIsShade(everyArrival(false), "every arrival");
    // The movable light a point light: moved, its paths go one by one; where the scene puts it, in lanes.
    Scene point = everyArrival(false);
    point.movableLight = int(point.lights.size()) - 1;
    ASSERT_EQ(point.lights[size_t(point.movableLight)].type, Light::Type::Point);
    expectShadeBatchIsShade(point, "every arrival, a point light moved");
}

}  // namespace test_path_tracer
