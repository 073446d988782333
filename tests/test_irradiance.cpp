// Direct lighting of a Lambert floor against closed forms: Lambert's formula for the irradiance of a
// uniform polygonal luminaire, and the inverse-square law for point lights. PathTracer::shade is
// called at hand-made hits on the floor, so only next-event estimation is exercised (the floor alone
// cannot light itself, so no bounce rays are traced).

#include <gtest/gtest.h>

#include <cmath>

#include "core/scene/accel.h"
#include "core/render/path_tracer.h"
#include "scene_builders.h"

namespace test_irradiance {

using namespace rrf;
using namespace rrf::test;

namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr float kRho = 0.6f;

/// Mean and standard error of the direct radiance shade() returns at floor point p towards wo.
RunningStat shadeStat(const Scene& scene, const Vec3& p, int samples, uint64_t seed, Vec3 wo = Vec3(0, 1, 0)) {
    const FloorShading st = shadeFloor(scene, p, samples, seed, wo);
    EXPECT_EQ(st.nonFinite, 0u);
    EXPECT_EQ(st.indirectNonZero, 0u) << "a lone floor cannot light itself";
    return st.direct;
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
    Scene s = floorScene(kRho, 5.f);
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
    Scene s = floorScene(kRho, 30.f);
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
        Scene s = floorScene(kRho, 2.f);
        addCeilingLight(s, 0, 0, 1e-3f, 1.f);
        expectIrradiance(s, Vec3(1.f, 0, 0.2f), 800000, 10, "0.5 beside a light 1e-3 above the floor");
    }
    // A light as small as its height (2e-3 side at 1e-3): right under it and exactly below its edge,
    // where d² → 1e-6. The uniform-area estimator's relative variance grows like A/h², so this is
    // the closest to the light's plane that 1% at 5σ allows in a few 1e5 samples.
    {
        Scene s = floorScene(kRho, 1.f);
        addCeilingLight(s, 0, 0, 1e-3f, 2e-3f);
        expectIrradiance(s, Vec3(0, 0, 0), 400000, 11, "under a light 1e-3 above the floor");
        expectIrradiance(s, Vec3(1e-3f, 0, 0), 400000, 12, "exactly below the edge of a light 1e-3 above the floor");
    }
}

TEST(Irradiance, LightFacingAwayOrTwoSided) {
    // A one-sided light facing up (away from the floor) gives exactly 0; made two-sided it lights
    // the floor as the downward-facing one does.
    Scene s = floorScene(kRho, 5.f);
    addRectLight(s, Vec3(-0.5f, 1.f, -0.5f), Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(4.f), true);  // normal +y
    const RunningStat away = shadeStat(s, Vec3(0.2f, 0, 0), 1000, 20);
    EXPECT_EQ(away.mean, 0.0);
    s.lights[0].oneSided = false;
    expectIrradiance(s, Vec3(0.2f, 0, 0), 200000, 21, "two-sided light seen from its back");
}

TEST(Irradiance, PointLightIsExact) {
    // ρ I cos θ / (π d²), deterministic: float rounding only (relative 1e-5).
    Scene s = floorScene(kRho, 50.f);
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
            const Radiance L = tracer.shade(surfaceHit(p), Vec3(0, 1, 0), rng, counters);
            EXPECT_NEAR(L.direct.x, expected, 1e-5 * expected) << "p = " << p;
            EXPECT_TRUE(L.indirect.isZero());
        }
    }
    // A point light below the floor's plane does not light its upper side.
    s.lights[0].position = Vec3(0.f, -1.f, 0.f);
    const PathTracer below(s, accel, Estimator::NEE, 8);
    Rng rng(31, 0);
    EXPECT_TRUE(below.shade(surfaceHit(Vec3(0.5f, 0, 0)), Vec3(0, 1, 0), rng, counters).direct.isZero());
}

}  // namespace test_irradiance
