// The unshadowed Phong lobe over an area light (core/predict/phong_lobe_integral.h) against an
// independent high-order quadrature in double: composite 4-point Gauss–Legendre on 250 uniform panels
// per axis over the light (or, for sharp lobes, over a window of ±14 lobe widths around the mirror
// ray's hit that the test sizes itself), with no footprint, no closed form and no panel splitting.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/predict/light_polygon.h"
#include "core/predict/phong_lobe_integral.h"
#include "scene_builders.h"

namespace test_phong_lobe_integral {

using namespace rrf;
using namespace rrf::test;

namespace {

constexpr double kPiD = 3.14159265358979323846;

/// ∫ cos^e α (n·ω)⁺ dω over the part [ua, ub] × [va, vb] of the light's (u, v) square (the triangle's
/// half u + v ≤ 1 for a triangle light), in double.
double reference(const Light& l, const Vec3& pf, const Vec3& nf, const Vec3& rf, double e, double ua = 0, double ub = 1,
                 double va = 0, double vb = 1) {
    // r normalised in double: a float unit vector is off by 1e-7, which cos^e α raises to the e-th power.
    const D3 rr = toD(rf), p = toD(pf), n = toD(nf), c = toD(l.corner), e1 = toD(l.edge1), e2 = toD(l.edge2);
    const double rl = lenD(rr);
    const D3 r{rr.x / rl, rr.y / rl, rr.z / rl};
    const D3 nl = crossD(e1, e2);
    const double area2 = lenD(nl);
    const double x4[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
    const double w4[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
    const int panels = 250;
    auto f = [&](double u, double v) {
        const D3 x{c.x + u * e1.x + v * e2.x, c.y + u * e1.y + v * e2.y, c.z + u * e1.z + v * e2.z};
        const D3 d = sub(x, p);
        const double dist = lenD(d);
        const D3 w{d.x / dist, d.y / dist, d.z / dist};
        const double cosTheta = dotD(w, n), ca = dotD(w, r);
        double cosL = -dotD(w, nl) / area2;
        if (!l.oneSided) cosL = std::fabs(cosL);
        if (cosTheta <= 0 || cosL <= 0 || ca <= 0) return 0.0;
        return std::pow(ca, e) * cosTheta * cosL / (dist * dist);
    };
    // A triangle is the image of the square under (s, t) → (s, t(1 − s)), Jacobian 1 − s, so that no
    // panel straddles its hypotenuse.
    const bool triangle = l.type == Light::Type::Triangle;
    double sum = 0;
    const double hu = (ub - ua) / panels, hv = (vb - va) / panels;
    for (int i = 0; i < panels; ++i)
        for (int a = 0; a < 4; ++a) {
            const double u = ua + hu * (i + 0.5 + 0.5 * x4[a]);
            for (int j = 0; j < panels; ++j)
                for (int b = 0; b < 4; ++b) {
                    const double v = va + hv * (j + 0.5 + 0.5 * x4[b]);
                    sum += w4[a] * w4[b] * 0.25 * (triangle ? (1 - u) * f(u, v * (1 - u)) : f(u, v));
                }
        }
    return sum * hu * hv * area2;
}

/// The bound the header states: 1e-4 of the value from the quadrature, plus the light the footprint
/// leaves out, below ε = 1e-6 · 2π/(e+2) times the light's projected solid angle.
double tolerance(double expected, double e, const Light& l, const Vec3& p, const Vec3& n) {
    return 1e-4 * expected + 1e-6 * 2 * kPiD / (e + 2) * projectedSolidAngle(l, p, n);
}

/// 1×1 light at height 1 centred above (cx, cz), facing down.
Light ceiling(float cx = 0.f, float cz = 0.f, bool oneSided = true) {
    Scene s;
    addCeilingLight(s, cx, cz, 1.f, 1.f, 1.f, oneSided);
    return s.lights[0];
}

/// Mirror direction from p towards the light point (u, v).
Vec3 towards(const Light& l, const Vec3& p, float u, float v) { return normalize(l.corner + l.edge1 * u + l.edge2 * v - p); }

/// The (u, v) window of ±14 lobe widths (1/√e radians) around the mirror ray's hit, clipped to [0,1].
void window(const Light& l, const Vec3& p, const Vec3& r, double e, double& ua, double& ub, double& va, double& vb) {
    const double t = (l.corner.y - p.y) / r.y;  // the test lights are horizontal
    const Vec3 hit = p + r * float(t);
    const double half = 14.0 / std::sqrt(e) * t / std::fabs(r.y) / std::fabs(r.y);  // generous for slant
    const double u = (hit.x - l.corner.x) / l.edge1.x, v = (hit.z - l.corner.z) / l.edge2.z;
    ua = std::max(0.0, u - half / l.edge1.x);
    ub = std::min(1.0, u + half / l.edge1.x);
    va = std::max(0.0, v - half / l.edge2.z);
    vb = std::min(1.0, v + half / l.edge2.z);
}

}  // namespace

TEST(PhongLobeIntegral, WideLobesMatchQuadratureOverTheLight) {
    const Light l = ceiling();
    const Vec3 n(0, 1, 0);
    for (float e : {0.f, 1.f, 10.f, 40.f})
        for (const Vec3& p : {Vec3(0, 0, 0), Vec3(0.9f, 0.2f, -0.4f), Vec3(-2.f, 0.f, 1.f)}) {
            const Vec3 r = normalize(Vec3(0.3f, 1.f, -0.2f));
            const double expected = reference(l, p, n, r, e);
            ASSERT_GT(expected, 0.0);
            EXPECT_NEAR(phongLobeIntegral(l, p, n, r, e), expected, tolerance(expected, e, l, p, n))
                << "e " << e << " at " << p.x;
        }
}

TEST(PhongLobeIntegral, WholeLobeOnTheLightIsTheClosedForm) {
    // The mirror ray hits the light's middle and the lobe is narrow: G = 2π (n·r)/(e+2), which the
    // independent quadrature must give too (the light holds all but a negligible tail).
    const Light l = ceiling();
    const Vec3 p(0.1f, 0.f, -0.05f), n(0, 1, 0);
    const Vec3 r = towards(l, p, 0.45f, 0.55f);
    for (float e : {300.f, 1000.f, 1e4f}) {
        double ua, ub, va, vb;
        window(l, p, r, e, ua, ub, va, vb);
        const double expected = reference(l, p, n, r, e, ua, ub, va, vb);
        const double closed = 2 * kPiD * double(dot(n, r)) / (e + 2.0);
        EXPECT_NEAR(expected, closed, 1e-4 * closed) << "the test's quadrature, e " << e;
        EXPECT_NEAR(phongLobeIntegral(l, p, n, r, e), closed, 1e-5 * closed) << "e " << e;
    }
    const float big = phongLobeIntegral(l, p, n, r, 1e6f);
    EXPECT_TRUE(std::isfinite(big));
    EXPECT_NEAR(big, 2 * kPiD * double(dot(n, r)) / (1e6 + 2.0), 1e-5 * 2 * kPiD / 1e6) << "e = 1e6";
}

TEST(PhongLobeIntegral, LobesCutByTheLightsEdgeMatchQuadrature) {
    const Light l = ceiling();
    const Vec3 n(0, 1, 0);
    struct Case {
        Vec3 p;
        float u, v, e;
        const char* what;
    };
    const Case cases[] = {
        {{0.2f, 0.f, 0.1f}, 0.98f, 0.5f, 1000.f, "peak just inside an edge"},
        {{0.2f, 0.f, 0.1f}, 1.02f, 0.5f, 1000.f, "peak just outside an edge"},
        {{-0.3f, 0.f, 0.3f}, 0.99f, 0.995f, 300.f, "peak at a corner"},
        {{0.f, 0.f, 0.f}, 0.5f, 0.999f, 100.f, "wider lobe, peak on an edge"},
        {{0.7f, 0.f, -0.6f}, 0.03f, 0.6f, 3000.f, "slanted view, sharp lobe"},
    };
    for (const Case& c : cases) {
        const Vec3 r = towards(l, c.p, c.u, c.v);
        double ua, ub, va, vb;
        window(l, c.p, r, c.e, ua, ub, va, vb);
        const double expected = reference(l, c.p, n, r, c.e, ua, ub, va, vb);
        const double scale = 2 * kPiD / (c.e + 2.0);  // the whole lobe's G
        ASSERT_GT(expected, 1e-3 * scale) << c.what;
        EXPECT_NEAR(phongLobeIntegral(l, c.p, n, r, c.e), expected, tolerance(expected, c.e, l, c.p, n)) << c.what;
    }
}

TEST(PhongLobeIntegral, LobesMissingTheLightGiveNothing) {
    const Light l = ceiling();
    const Vec3 p(0.f, 0.f, 0.f), n(0, 1, 0);
    const Vec3 away = towards(l, p, 3.f, 0.5f);  // aimed 2.5 light widths beside it
    EXPECT_EQ(phongLobeIntegral(l, p, n, away, 1000.f), 0.f);
    EXPECT_LT(reference(l, p, n, away, 1000.0), 1e-30) << "the test's own quadrature agrees it is nothing";
    EXPECT_EQ(phongLobeIntegral(l, p, n, Vec3(0, -1, 0), 50.f), 0.f) << "lobe pointing away from the light";
    EXPECT_EQ(phongLobeIntegral(l, Vec3(0, 2, 0), Vec3(0, -1, 0), Vec3(0, -1, 0), 10.f), 0.f)
        << "behind a one-sided light";
}

TEST(PhongLobeIntegral, HorizonAndTwoSidedAndTriangleLights) {
    // The receiver's horizon cuts through the light and the lobe (a wall next to a ceiling light).
    const Light l = ceiling();
    const Vec3 wall(0.3f, 0.6f, 0.f), wn = normalize(Vec3(-1.f, 0.1f, 0.f));
    for (float e : {10.f, 200.f}) {
        const Vec3 r = towards(l, wall, 0.15f, 0.5f);
        const double expected = reference(l, wall, wn, r, e);
        EXPECT_NEAR(phongLobeIntegral(l, wall, wn, r, e), expected, 1e-3 * expected) << "horizon, e " << e;
    }
    // A two-sided light seen from above.
    const Light both = ceiling(0.f, 0.f, false);
    const Vec3 above(0.2f, 1.6f, 0.1f), down(0, -1, 0);
    const Vec3 r = towards(both, above, 0.4f, 0.6f);
    const double expected = reference(both, above, down, r, 60.0);
    EXPECT_NEAR(phongLobeIntegral(both, above, down, r, 60.f), expected, tolerance(expected, 60, both, above, down))
        << "two-sided, from behind";
    // A triangle light, the lobe cut by its hypotenuse.
    Light tri = ceiling();
    tri.type = Light::Type::Triangle;
    const Vec3 p(0.f, 0.f, 0.f), n(0, 1, 0);
    for (float e : {20.f, 400.f}) {
        const Vec3 rt = towards(tri, p, 0.45f, 0.5f);  // just beyond the hypotenuse u + v = 1
        const double ref = reference(tri, p, n, rt, e);
        EXPECT_NEAR(phongLobeIntegral(tri, p, n, rt, e), ref, tolerance(ref, e, tri, p, n)) << "triangle, e " << e;
    }
}

}  // namespace test_phong_lobe_integral
