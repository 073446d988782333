// Direct lighting of a Lambert floor against closed forms: Lambert's formula for the irradiance of a
// uniform polygonal luminaire, and the inverse-square law for point lights. PathTracer::shade is
// called at hand-made hits on the floor, so only next-event estimation is exercised (the floor alone
// cannot light itself, so no bounce rays are traced).

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "core/accel.h"
#include "core/path_tracer.h"
#include "scene_builders.h"

using namespace rrf;
using namespace rrf::test;

namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr float kRho = 0.6f;

struct D3 {
    double x, y, z;
};
D3 sub(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 crossD(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double dotD(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double lenD(D3 a) { return std::sqrt(dotD(a, a)); }
D3 toD(const Vec3& v) { return {v.x, v.y, v.z}; }

/// Irradiance at p (normal n) from a uniform Lambertian parallelogram of radiance L lying entirely
/// above p's tangent plane (Lambert 1760):
///   E = (L/2) Σ_i Θ_i n·(v_i × v_{i+1}) / |v_i × v_{i+1}|,
/// v_i the unit vectors from p to the vertices, Θ_i the angle between consecutive ones. The sign of
/// the sum depends on the winding as seen from p, hence the absolute value. Double precision.
double polygonIrradiance(const Light& l, const Vec3& pf, const Vec3& nf) {
    const D3 p = toD(pf), n = toD(nf);
    const D3 c = toD(l.corner), e1 = toD(l.edge1), e2 = toD(l.edge2);
    const std::array<D3, 4> vs = {c, D3{c.x + e1.x, c.y + e1.y, c.z + e1.z},
                                  D3{c.x + e1.x + e2.x, c.y + e1.y + e2.y, c.z + e1.z + e2.z},
                                  D3{c.x + e2.x, c.y + e2.y, c.z + e2.z}};
    double sum = 0;
    for (size_t i = 0; i < 4; ++i) {
        D3 a = sub(vs[i], p), b = sub(vs[(i + 1) % 4], p);
        const double la = lenD(a), lb = lenD(b);
        a = {a.x / la, a.y / la, a.z / la};
        b = {b.x / lb, b.y / lb, b.z / lb};
        const D3 axb = crossD(a, b);
        const double s = lenD(axb);
        if (s == 0) continue;
        const double theta = std::atan2(s, dotD(a, b));
        sum += theta * dotD(n, axb) / s;
    }
    return 0.5 * double(l.radiance.x) * std::fabs(sum);
}

/// A Lambert floor y = 0 of half-size `half` (albedo kRho, normal +y) under one light.
Scene floorScene(float half) {
    Scene s;
    const int m = addLambert(s, Vec3(kRho));
    addQuads(s, {{{-half, 0, -half}, {0, 0, 2 * half}, {2 * half, 0, 0}}}, m, "floor");
    return s;
}

/// A one-sided square light of side `side` centred above (cx, cz) at height h, facing down.
void addCeilingLight(Scene& s, float cx, float cz, float h, float side, float radiance = 4.f, bool oneSided = true) {
    addRectLight(s, Vec3(cx - 0.5f * side, h, cz - 0.5f * side), Vec3(side, 0, 0), Vec3(0, 0, side), Vec3(radiance),
                 oneSided);
}

Hit floorHit(const Vec3& p) {
    Hit h;
    h.t = 1.f;
    h.p = p;
    h.ng = Vec3(0, 1, 0);
    h.object = 0;
    return h;
}

/// Mean and standard error of the direct radiance shade() returns at floor point p towards wo.
RunningStat shadeStat(const Scene& scene, const Vec3& p, int samples, uint64_t seed, Vec3 wo = Vec3(0, 1, 0)) {
    const Accel accel(scene);
    const PathTracer tracer(scene, accel, Estimator::NEE, 8);
    TraceCounters counters;
    RunningStat st;
    for (int i = 0; i < samples; ++i) {
        Rng rng(seed, uint64_t(i));
        const Radiance L = tracer.shade(floorHit(p), wo, rng, counters);
        EXPECT_TRUE(L.direct.isFinite() && L.indirect.isFinite());
        EXPECT_TRUE(L.indirect.isZero());  // a lone floor cannot light itself
        st.add(L.direct.x);
    }
    return st;
}

/// Checks the NEE estimate at p against ρE/π within 1%, where the sample count makes 1% at least
/// 5 standard errors (asserted, so the check keeps its power if the estimator's variance grows).
void expectIrradiance(const Scene& scene, const Vec3& p, int samples, uint64_t seed, const char* what,
                      Vec3 wo = Vec3(0, 1, 0)) {
    const double expected = kRho / kPiD * polygonIrradiance(scene.lights[0], p, Vec3(0, 1, 0));
    const RunningStat st = shadeStat(scene, p, samples, seed, wo);
    EXPECT_LE(5 * st.sigma(), 0.01 * expected) << what << ": too few samples for a 1% check";
    EXPECT_NEAR(st.mean, expected, 0.01 * expected) << what << " at " << p << " (σ = " << st.sigma() << ")";
}

}  // namespace

TEST(Irradiance, PolygonFormulaMatchesKnownValues) {
    // Check of the reference itself against the form factor from a point to a coaxial rectangle
    // corner (Cohen & Wallace, "Radiosity and Realistic Image Synthesis", appendix): for an x×y
    // rectangle (in units of the height) F = 1/(2π) [x/√(1+x²) atan(y/√(1+x²)) + y/√(1+y²) atan(x/√(1+y²))].
    // A unit square centred over p is four such quarters with x = y = 1/(2h); E = π L · 4F.
    Scene s = floorScene(5.f);
    for (const float h : {0.25f, 1.f, 4.f}) {
        s.lights.clear();
        addCeilingLight(s, 0, 0, h, 1.f, 1.f);
        const double x = 0.5 / double(h);
        const double r = x / std::sqrt(1 + x * x);
        const double F = 1.0 / (2 * kPiD) * (2 * r * std::atan(r));
        EXPECT_NEAR(polygonIrradiance(s.lights[0], Vec3(0.f), Vec3(0, 1, 0)), kPiD * 4 * F, 1e-9) << "h = " << h;
    }
}

TEST(Irradiance, RectLightMatchesLambertFormula) {
    // 1×1 light at height 1 over a floor that reaches far enough for grazing angles.
    Scene s = floorScene(30.f);
    addCeilingLight(s, 0, 0, 1.f, 1.f);
    expectIrradiance(s, Vec3(0, 0, 0), 200000, 1, "under the light");
    expectIrradiance(s, Vec3(0.5f, 0, 0), 200000, 2, "below the light's edge");
    expectIrradiance(s, Vec3(0.5f, 0, 0.5f), 200000, 3, "below the light's corner");
    expectIrradiance(s, Vec3(3.f, 0, 0.7f), 200000, 4, "off to the side");
    expectIrradiance(s, Vec3(20.f, 0, -5.f), 200000, 5, "grazing (light 2.8° above the horizon)");
    // Lambert: the view direction does not matter, not even at grazing view angles.
    expectIrradiance(s, Vec3(0.2f, 0, 0.1f), 200000, 6, "grazing view", normalize(Vec3(1.f, 1e-4f, 0.3f)));
}

TEST(Irradiance, LightLowOverTheFloor) {
    // Light 1e-3 above the floor: cos θ and cos θ' ≈ 1e-3 for a point beside it.
    {
        Scene s = floorScene(2.f);
        addCeilingLight(s, 0, 0, 1e-3f, 1.f);
        expectIrradiance(s, Vec3(1.f, 0, 0.2f), 800000, 10, "0.5 beside a light 1e-3 above the floor");
    }
    // A light as small as its height (2e-3 side at 1e-3): right under it and exactly below its edge,
    // where d² → 1e-6. The uniform-area estimator's relative variance grows like A/h², so this is
    // the closest to the light's plane that 1% at 5σ allows in a few 1e5 samples.
    {
        Scene s = floorScene(1.f);
        addCeilingLight(s, 0, 0, 1e-3f, 2e-3f);
        expectIrradiance(s, Vec3(0, 0, 0), 400000, 11, "under a light 1e-3 above the floor");
        expectIrradiance(s, Vec3(1e-3f, 0, 0), 400000, 12, "exactly below the edge of a light 1e-3 above the floor");
    }
}

TEST(Irradiance, LightFacingAwayOrTwoSided) {
    // A one-sided light facing up (away from the floor) gives exactly 0; made two-sided it lights
    // the floor as the downward-facing one does.
    Scene s = floorScene(5.f);
    addRectLight(s, Vec3(-0.5f, 1.f, -0.5f), Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(4.f), true);  // normal +y
    const RunningStat away = shadeStat(s, Vec3(0.2f, 0, 0), 1000, 20);
    EXPECT_EQ(away.mean, 0.0);
    s.lights[0].oneSided = false;
    expectIrradiance(s, Vec3(0.2f, 0, 0), 200000, 21, "two-sided light seen from its back");
}

TEST(Irradiance, PointLightIsExact) {
    // ρ I cos θ / (π d²), deterministic: float rounding only (relative 1e-5).
    Scene s = floorScene(50.f);
    const Vec3 lp(0.3f, 2.f, -0.4f);
    addPointLight(s, lp, Vec3(5.f));
    const Accel accel(s);
    const PathTracer tracer(s, accel, Estimator::NEE, 8);
    TraceCounters counters;
    for (const Vec3 p : {Vec3(0, 0, 0), Vec3(0.3f, 0, -0.4f), Vec3(4, 0, 2), Vec3(-40, 0, 30)}) {
        const Vec3 d = lp - p;
        const double d2 = double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z;
        const double expected = kRho * 5.0 * (double(d.y) / std::sqrt(d2)) / (kPiD * d2);
        for (int i = 0; i < 3; ++i) {
            Rng rng(30, uint64_t(i));
            const Radiance L = tracer.shade(floorHit(p), Vec3(0, 1, 0), rng, counters);
            EXPECT_NEAR(L.direct.x, expected, 1e-5 * expected) << "p = " << p;
            EXPECT_TRUE(L.indirect.isZero());
        }
    }
    // A point light below the floor's plane does not light its upper side.
    s.lights[0].position = Vec3(0.f, -1.f, 0.f);
    const PathTracer below(s, accel, Estimator::NEE, 8);
    Rng rng(31, 0);
    EXPECT_TRUE(below.shade(floorHit(Vec3(0.5f, 0, 0)), Vec3(0, 1, 0), rng, counters).direct.isZero());
}
