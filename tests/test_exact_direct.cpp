// Exact direct light of prediction (core/predict/exact_direct.h) against independent computations:
// the closed-form projected solid angle against a 2-D quadrature over the light, unoccluded points
// against the closed form with no variance, a Phong receiver against a quadrature of its BRDF, and a
// Cornell-like image against a high-spp path-traced direct image; the shadow casters against Embree
// over a whole image, and the image against itself on one thread.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/eval/error_metrics.h"
#include "core/predict/exact_direct.h"
#include "core/predict/footprint_mask.h"
#include "core/predict/predictor.h"
#include "core/scene/scene_json.h"

#include <tbb/global_control.h>
#include "scene_builders.h"

namespace test_exact_direct {

using namespace rrf;
using namespace rrf::test;

namespace {

constexpr double kPiD = 3.14159265358979323846;

/// ∫ over the light's area of Le·g(ωi)·max(0, n·ωi)·cosθ'/d² dA by the midpoint rule on m × m cells,
/// in double: an independent computation of what the closed form and the estimator return. g = 1
/// gives the projected solid angle (times Le).
template <class G>
double lightQuadrature(const Light& l, const Vec3& pf, const Vec3& nf, int m, G g) {
    const D3 p = toD(pf), n = toD(nf), c = toD(l.corner), e1 = toD(l.edge1), e2 = toD(l.edge2);
    const D3 nl = crossD(e1, e2);
    const double area = lenD(nl);
    double sum = 0;
    for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j) {
            const double u = (i + 0.5) / m, v = (j + 0.5) / m;
            const D3 x{c.x + u * e1.x + v * e2.x, c.y + u * e1.y + v * e2.y, c.z + u * e1.z + v * e2.z};
            const D3 d = sub(x, p);
            const double dist = lenD(d);
            const D3 w{d.x / dist, d.y / dist, d.z / dist};
            const double cosTheta = dotD(w, n);
            double cosL = -dotD(w, nl) / area;
            if (!l.oneSided) cosL = std::fabs(cosL);
            if (cosTheta <= 0 || cosL <= 0) continue;
            sum += g(w) * cosTheta * cosL / (dist * dist);
        }
    return sum * area / (double(m) * m);
}

double solidAngleQuadrature(const Light& l, const Vec3& p, const Vec3& n) {
    return lightQuadrature(l, p, n, 1000, [](const D3&) { return 1.0; });
}

struct Receiver {
    Vec3 p, n;
    const char* what;
};

/// 1×1 light at height 1 above the origin, facing down.
Scene lightOverFloor() {
    Scene s = floorScene(0.6f, 5.f);
    addCeilingLight(s, 0, 0, 1.f, 1.f, 4.f);
    return s;
}

}  // namespace

TEST(ExactDirect, ProjectedSolidAngleMatchesQuadratureIncludingTheHorizon) {
    const Scene s = lightOverFloor();
    const Light& l = s.lights[0];
    const Receiver cases[] = {
        {{0, 0, 0}, {0, 1, 0}, "centred below"},
        {{2, 0, 0.5f}, {0, 1, 0}, "off to the side"},
        {{0, 0.5f, 0}, normalize(Vec3(1, 0.3f, 0)), "tilted, light partly below the horizon"},
        {{0.2f, 0.3f, 0.1f}, normalize(Vec3(0.3f, -0.2f, 1)), "oblique"},
        {{0, 0.5f, 0}, {0, 0, 1}, "wall: the horizon halves the light"},
        {{0.4f, 0.95f, 0.3f}, normalize(Vec3(-1, 0.1f, -0.2f)), "close to the light's plane"},
    };
    for (const Receiver& r : cases) {
        const double expected = solidAngleQuadrature(l, r.p, r.n);
        ASSERT_GT(expected, 1e-3) << r.what;
        EXPECT_NEAR(projectedSolidAngle(l, r.p, r.n), expected, 2e-5 * expected) << r.what;
    }
    EXPECT_EQ(projectedSolidAngle(l, Vec3(0, 0, 0), Vec3(0, -1, 0)), 0.0) << "light entirely below the horizon";
    EXPECT_EQ(projectedSolidAngle(l, Vec3(0, 2, 0), Vec3(0, -1, 0)), 0.0) << "behind a one-sided light";
    Light twoSided = l;
    twoSided.oneSided = false;
    EXPECT_NEAR(projectedSolidAngle(twoSided, Vec3(0, 2, 0), Vec3(0, -1, 0)),
                polygonIrradiance(twoSided, Vec3(0, 2, 0), Vec3(0, -1, 0)) / double(l.radiance.x), 1e-9)
        << "a two-sided light seen from behind: Lambert's formula";
}

TEST(ExactDirect, UnoccludedPointsAreExactWithoutVariance) {
    const Scene s = lightOverFloor();
    const Accel accel(s);
    const PathTracer tracer(s, accel, Estimator::NEE, 1);
    const Light movable = tracer.movableLightAt(s.lightPosition());
    TraceCounters counters;
    const Receiver cases[] = {{{0, 0, 0}, {0, 1, 0}, "centred"},
                              {{1.5f, 0, -0.7f}, {0, 1, 0}, "off-centre"},
                              {{3, 0, 2}, {0, 1, 0}, "far"}};
    for (const Receiver& r : cases) {
        const double expected = 0.6 / kPiD * polygonIrradiance(s.lights[0], r.p, r.n);
        for (int samples : {1, 16, 61}) {
            const ExactDirect a(tracer, samples, 1), b(tracer, samples, 99);
            const Vec3 la = a.radiance(r.p, r.n, Vec3(0, 1, 0), 0, movable, 7, counters);
            const Vec3 lb = b.radiance(r.p, r.n, Vec3(0, 1, 0), 0, movable, 12345, counters);
            EXPECT_EQ(la.x, lb.x) << r.what << ": other seed and pixel, same value (no variance)";
            EXPECT_NEAR(la.x, expected, 1e-5 * expected) << r.what << ", " << samples << " samples";
        }
    }
}

TEST(ExactDirect, PhongReceiverMatchesQuadratureOfItsBrdf) {
    // Floor with a Phong material, viewed so that the mirror lobe points into the light: the diffuse
    // part is Lambert's closed form and the glossy part a quadrature of the lobe, so the unshadowed
    // receiver matches an independent quadrature of its BRDF with no variance at all.
    Scene s = lightOverFloor();
    s.materials[0] = Material{Material::Type::Phong, "phong", Vec3(0.3f), Vec3(0.5f), 40.f};
    const Accel accel(s);
    const PathTracer tracer(s, accel, Estimator::NEE, 1);
    const Light movable = tracer.movableLightAt(s.lightPosition());
    const Vec3 p(0.6f, 0, 0.2f), n(0, 1, 0), wo = normalize(Vec3(0.9f, 1.f, 0.3f));
    const Vec3 mirror = reflect(wo, n);
    const double glossy = lightQuadrature(s.lights[0], p, n, 1500, [&](const D3& w) {
        const double c = w.x * mirror.x + w.y * mirror.y + w.z * mirror.z;
        return c > 0 ? 0.5 * (40.0 + 2) / (2 * kPiD) * std::pow(c, 40.0) : 0.0;
    });
    const double expected = 4.0 * (0.3 / kPiD * solidAngleQuadrature(s.lights[0], p, n) + glossy);
    TraceCounters counters;
    const ExactDirect a(tracer, 16, 5), b(tracer, 64, 77);
    const float la = a.radiance(p, n, wo, 0, movable, 3, counters).x;
    EXPECT_NEAR(la, expected, 1e-4 * expected) << "glossy share " << 4.0 * glossy / expected;
    EXPECT_EQ(b.radiance(p, n, wo, 0, movable, 12345, counters).x, la) << "other seed, samples and pixel: no variance";
}

TEST(ExactDirect, CastersChangeNoPixelAndThreadsChangeNothing) {
    // The glossy Cornell box with a sharp back wall (its highlight of the lamp near the top): with the
    // casters' verdicts and without them (every sample ray to Embree) the estimate is the same,
    // receiver by receiver — the proofs only leave out rays whose answers they know — up to rays
    // through an edge, where clipping and Embree may round differently (one sample, ≤ 1/N of a ratio).
    Scene s = loadScene(std::string(RRF_SOURCE_DIR) + "/projects/cornell-glossy/scene.json");
    for (Material& m : s.materials)
        if (m.name == "glossy-back") m.exponent = 300.f;
    const int size = 48, samples = 64;
    ModelSet none;
    const Predictor pred(s, none, PredictionSettings{});
    const GBuffer g = pred.gbuffer(s.lightPosition() + Vec3(0.1f, -0.2f, 0.1f), size, size);
    const Light movable = pred.tracer().movableLightAt(g.lightPosition);
    ExactDirect::Options off;
    off.proofs = false;
    const ExactDirect with(pred.tracer(), samples, 9), without(pred.tracer(), samples, 9, off);
    uint64_t bad = 0;
    ShadowCasters::Counts counts;
    const Image a = with.image(g, movable, bad, &counts);
    Image b, one;
    {
        b = without.image(g, movable, bad);
        tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
        one = with.image(g, movable, bad);
    }
    EXPECT_EQ(bad, 0u);
    EXPECT_GT(counts.unoccluded, 0u);
    EXPECT_GT(counts.occluded, 0u);
    EXPECT_GT(counts.segments, 0u);
    EXPECT_EQ(one.data, a.data) << "one thread or many: the same image";
    size_t differ = 0, pixels = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const Vec3 va = a.at(x, y), vb = b.at(x, y);
            if (!va.isZero() || !vb.isZero()) ++pixels;
            if (va == vb) continue;
            ++differ;
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(va[c], vb[c], 2.0 / samples * std::max(va[c], vb[c])) << x << "," << y;
        }
    EXPECT_GT(pixels, size_t(size * size / 2));
    EXPECT_LE(differ, pixels / 500) << "pixels whose casters and Embree disagree about a ray";
}

TEST(ExactDirect, ConvergesToThePathTracedDirectImage) {
    // Cornell-like box with a block casting shadows: exact direct light at 64 samples against the
    // renderer's direct image at 2048 spp (max depth 1). Pixels whose footprint spans an edge are left
    // out (the prediction is a pixel-centre value, the reference a pixel average). The per-pixel
    // squared error e must be explained by the reference's variance of the mean v plus the exact
    // estimator's own error in penumbra: mean(e) − mean(v) has standard error sd(e − v)/√n, and
    // the estimator's share is bounded by 0.01² relative (measured 0.004²).
    const int size = 32, spp = 2048;
    const Scene s = cornellLike(1.f, size);
    const Accel accel(s);
    RenderOptions ro = renderOptions(s, Estimator::NEE, spp, spp, 11);
    ro.maxDepth = 1;
    const RenderSnapshot ref = render(s, accel, ro);

    ModelSet none;
    PredictionSettings settings;
    settings.directSamples = 64;
    const Predictor pred(s, none, settings);
    const GBuffer g = pred.gbuffer(s.lightPosition(), size, size);
    const Prediction pr = pred.predict(g);
    const FootprintMask mask = footprintMask(g);
    std::vector<double> diff;
    double sumE = 0, sumV = 0;
    for (const std::vector<uint32_t>& kept : mask.keptByObject)
        for (uint32_t i : kept) {
            const int x = int(i % uint32_t(size)), y = int(i / uint32_t(size));
            const Vec3 r = ref.direct.at(x, y), e = pr.image(Term::Direct).at(x, y), v = ref.directVariance.at(x, y);
            double ei = 0, vi = 0;
            for (int c = 0; c < 3; ++c) {
                const double scale = std::fabs(double(r[c])) + 0.01;
                ei += std::pow((double(e[c]) - double(r[c])) / scale, 2.0) / 3.0;
                vi += double(v[c]) / (scale * scale) / 3.0;
            }
            sumE += ei;
            sumV += vi;
            diff.push_back(ei - vi);
        }
    ASSERT_GT(diff.size(), 400u);
    const double n = double(diff.size()), meanDiff = (sumE - sumV) / n;
    double ss = 0;
    for (double d : diff) ss += (d - meanDiff) * (d - meanDiff);
    const double standardError = std::sqrt(ss / (n - 1.0) / n);
    std::printf("  %zu kept pixels: relative RMSE %.4g, reference noise %.4g, excess %.3g (standard error %.3g)\n",
                diff.size(), std::sqrt(sumE / n), std::sqrt(sumV / n), meanDiff, standardError);
    EXPECT_GT(meanDiff, -4.0 * standardError) << "less error than the reference's own noise: impossible";
    EXPECT_LT(meanDiff, 1e-4 + 4.0 * standardError) << "exact direct light's own error above 0.01 relative";
}

TEST(ExactDirect, SampleGridCoversEveryCount) {
    for (int n : {1, 2, 3, 16, 17, 64, 65536}) {
        const SampleGrid g(n);
        EXPECT_GE(g.cols * g.rows, n) << n;
        EXPECT_LT(g.cols * (g.rows - 1), n) << n << ": no empty last row";
        EXPECT_LE(std::abs(g.cols - g.rows), 1) << n;
    }
}

}  // namespace test_exact_direct
