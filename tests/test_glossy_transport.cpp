// Glossy (Phong) light transport against independent computations: the direct light on a Phong
// plane under a rectangle light against a 2-D quadrature over the light, and NEE against the naive
// estimator on a glossy Cornell box at several exponents. The Lambert tests cannot see a renderer
// that drops or misplaces the specular lobe; these can.

#include <gtest/gtest.h>

#include <cmath>

#include "core/render/path_tracer.h"
#include "core/scene/accel.h"
#include "core/scene/camera_rays.h"
#include "scene_builders.h"

namespace test_glossy_transport {

using namespace rrf;
using namespace rrf::test;

namespace {

constexpr double kPiD = 3.14159265358979323846;

/// L_direct(p, ωo) = ∫_light Le f(ωo, ωi) cosθ cosθ' / d² dA for a floor point p (normal +y) under a
/// downward-facing light, by Gauss–Legendre quadrature over the light's (s, t) in double, with the
/// modified Phong BRDF written out here: f = kd/π + ks (n+2)/(2π) max(0, r·ωi)^n, r = ωo mirrored
/// about the normal.
double quadratureDirect(const Light& l, const D3& p, const D3& wo, double kd, double ks, double n) {
    const D3 r{-wo.x, wo.y, -wo.z};
    const D3 nl = crossD(toD(l.edge1), toD(l.edge2));
    const double area = lenD(nl);
    const D3 nlUnit{nl.x / area, nl.y / area, nl.z / area};
    const GaussLegendre gl(16);
    const D3 c = toD(l.corner), e1 = toD(l.edge1), e2 = toD(l.edge2);
    auto integrand = [&](double s, double t) {
        const D3 x{c.x + s * e1.x + t * e2.x, c.y + s * e1.y + t * e2.y, c.z + s * e1.z + t * e2.z};
        D3 d = sub(x, p);
        const double dist2 = dotD(d, d), dist = std::sqrt(dist2);
        d = {d.x / dist, d.y / dist, d.z / dist};
        const double cosTheta = d.y, cosLight = -dotD(d, nlUnit);
        if (cosTheta <= 0 || cosLight <= 0) return 0.0;
        const double f = kd / kPiD + ks * (n + 2) / (2 * kPiD) * std::pow(std::max(0.0, dotD(r, d)), n);
        return double(l.radiance.x) * f * cosTheta * cosLight / dist2 * area;
    };
    return gl.integrate([&](double s) { return gl.integrate([&](double t) { return integrand(s, t); }, 0, 1, 16); },
                        0, 1, 16);
}

/// NEE and the naive estimator on the same 150 000 camera rays of `scene` (32×32 pixels, ray i from
/// Rng(seed, i), NEE's path randomness from Rng(seed + 1, i), the naive one's from Rng(seed + 2, i)):
/// paired samples, so the standard error of the mean difference is exact.
struct PairedEstimates {
    RunningStat dDirect, dGlobal;  ///< NEE − naive, red channel
    RunningStat direct, global;    ///< NEE alone
    bool allFinite = true;
};

PairedEstimates pairedNeeAndNaive(const Scene& scene, uint64_t seed) {
    const Accel accel(scene);
    const PathTracer nee(scene, accel, Estimator::NEE), naive(scene, accel, Estimator::Naive);
    const CameraRays cam(scene.camera, 32, 32);
    TraceCounters counters;
    PairedEstimates e;
    for (int i = 0; i < 150000; ++i) {
        Rng pick(seed, uint64_t(i));
        const int px = int(pick.uniformInt(32)), py = int(pick.uniformInt(32));
        const Ray ray = cam.generate(px, py, pick.uniform(), pick.uniform());
        Rng ra(seed + 1, uint64_t(i)), rb(seed + 2, uint64_t(i));
        const Radiance a = nee.trace(ray, ra, counters), b = naive.trace(ray, rb, counters);
        if (!(a.direct.isFinite() && a.indirect.isFinite() && b.direct.isFinite() && b.indirect.isFinite())) {
            e.allFinite = false;
            return e;
        }
        e.dDirect.add(double(a.direct.x) - double(b.direct.x));
        e.dGlobal.add(double(a.direct.x + a.indirect.x) - double(b.direct.x + b.indirect.x));
        e.direct.add(a.direct.x);
        e.global.add(double(a.direct.x) + double(a.indirect.x));
    }
    return e;
}

}  // namespace

TEST(GlossyTransport, DirectLightOnAPhongPlaneMatchesQuadratureOverTheLight) {
    // The viewer looks at the origin from the −x side; the 1 × 1 light at height 2 is centred on the
    // mirror direction, so the lobe's position, width and normalisation all show in the value (a lobe
    // around ωo itself would see almost nothing of the light).
    const D3 woD{-1.5 / 2.5, 2.0 / 2.5, 0.0};
    const Vec3 wo(float(woD.x), float(woD.y), float(woD.z));
    struct Case {
        float kd, ks, n;
    };
    for (const Case c : {Case{0.2f, 0.6f, 1.f}, Case{0.1f, 0.7f, 10.f}, Case{0.05f, 0.8f, 100.f}, Case{0.f, 0.8f, 30.f}}) {
        Scene s;
        const int m = addPhong(s, Vec3(c.kd), Vec3(c.ks), c.n);
        addQuads(s, {{{-10, 0, -10}, {0, 0, 20}, {20, 0, 0}}}, m, "floor");
        addCeilingLight(s, 1.5f, 0.f, 2.f, 1.f, 4.f);
        const double expected = quadratureDirect(s.lights[0], {0, 0, 0}, woD, c.kd, c.ks, c.n);
        const double diffuseOnly = quadratureDirect(s.lights[0], {0, 0, 0}, woD, c.kd, 0, c.n);
        ASSERT_GT(expected, 1.5 * diffuseOnly) << "the specular lobe must dominate the value";
        const FloorShading st = shadeFloor(s, Vec3(0.f), 200000, 31, wo);
        EXPECT_EQ(st.nonFinite, 0u);
        EXPECT_EQ(st.indirectNonZero, 0u) << "one plane: no indirect light";
        EXPECT_LT(5 * st.direct.sigma(), 0.03 * expected) << "n = " << c.n << ": too few samples for a 3% check";
        EXPECT_NEAR(st.direct.mean, expected, 5 * st.direct.sigma()) << "kd " << c.kd << " ks " << c.ks << " n " << c.n;
    }
}

TEST(GlossyTransport, NeeMatchesNaiveOnAGlossySceneAtSeveralExponents) {
    // The Cornell box with glossy white walls (kd 0.3, ks 0.4) and a light 2× the default size.
    // Paired samples (one camera ray, independent path randomness) make the standard error of the
    // mean difference exact. NEE evaluates the lobe; the naive estimator samples it: a lobe evaluated
    // in the wrong place or with the wrong constant shows as a difference.
    for (const float n : {1.f, 10.f, 100.f}) {
        Scene scene = cornellLike(1.f, 32, 2.f);
        Material& white = scene.materials[0];
        white.type = Material::Type::Phong;
        white.kd = Vec3(0.3f);
        white.ks = Vec3(0.4f);
        white.exponent = n;
        const PairedEstimates e = pairedNeeAndNaive(scene, 40);
        ASSERT_TRUE(e.allFinite) << "n = " << n;
        const RunningStat &dDirect = e.dDirect, &dGlobal = e.dGlobal, &direct = e.direct, &global = e.global;
        EXPECT_NEAR(dDirect.mean, 0.0, 5 * dDirect.sigma()) << "n = " << n;
        EXPECT_NEAR(dGlobal.mean, 0.0, 5 * dGlobal.sigma()) << "n = " << n;
        EXPECT_LT(5 * dDirect.sigma(), 0.05 * direct.mean) << "n = " << n << ": must see a 5% bias of direct";
        EXPECT_LT(5 * dGlobal.sigma(), 0.08 * global.mean) << "n = " << n;
    }
}

TEST(GlossyTransport, NeeMatchesNaiveWithTriangleLightsAtHighExponents) {
    // As above with the rect light cut into its two triangles, so light samples take the triangle
    // lights' path (one point for all triangles, picked by area) and, in this glossy scene, are
    // combined with the BRDF rays that hit a triangle (multiple importance sampling): a wrong light
    // pdf in either half of the weights biases NEE against the naive estimator, which only hits.
    for (const float n : {100.f, 1000.f}) {
        Scene scene = cornellLike(1.f, 32, 2.f);
        Material& white = scene.materials[0];
        white.type = Material::Type::Phong;
        white.kd = Vec3(0.3f);
        white.ks = Vec3(0.4f);
        white.exponent = n;
        const Light rect = scene.lights.at(0);
        Light a = rect, b = rect;
        a.type = b.type = Light::Type::Triangle;
        b.corner = rect.corner + rect.edge1 + rect.edge2;
        b.edge1 = rect.edge1 * -1.f;
        b.edge2 = rect.edge2 * -1.f;
        b.name = rect.name + "-b";
        scene.lights = {a, b};
        scene.movableLight = -1;
        const PairedEstimates e = pairedNeeAndNaive(scene, 50);
        ASSERT_TRUE(e.allFinite) << "n = " << n;
        const RunningStat &dDirect = e.dDirect, &dGlobal = e.dGlobal, &direct = e.direct, &global = e.global;
        EXPECT_NEAR(dDirect.mean, 0.0, 5 * dDirect.sigma()) << "n = " << n;
        EXPECT_NEAR(dGlobal.mean, 0.0, 5 * dGlobal.sigma()) << "n = " << n;
        EXPECT_LT(5 * dDirect.sigma(), 0.05 * direct.mean) << "n = " << n << ": must see a 5% bias of direct";
        EXPECT_LT(5 * dGlobal.sigma(), 0.08 * global.mean) << "n = " << n;
    }
}
}  // namespace test_glossy_transport
