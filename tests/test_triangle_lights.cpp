// Triangle emitters (Light::Type::Triangle, from OBJ faces with Ke) against closed forms: Lambert's
// polygon formula for the irradiance of a uniform triangle, the square that two triangles make, and
// a white furnace closed by triangle emitters. NEE samples all triangle lights together, one
// triangle picked by area, so the tests use triangles of different sizes and radiances.

#include <gtest/gtest.h>

#include <cmath>

#include "core/predict/exact_direct.h"
#include "core/render/path_tracer.h"
#include "core/scene/accel.h"
#include "scene_builders.h"

namespace test_triangle_lights {

using namespace rrf;
using namespace rrf::test;

namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr float kRho = 0.6f;

int addTriangleLight(Scene& s, const Vec3& a, const Vec3& b, const Vec3& c, float radiance, bool oneSided = true,
                     int material = -1) {
    Light l;
    l.type = Light::Type::Triangle;
    l.name = "tri" + std::to_string(s.lights.size());
    l.corner = a;
    l.edge1 = b - a;
    l.edge2 = c - a;
    l.radiance = Vec3(radiance);
    l.oneSided = oneSided;
    l.material = material;
    s.lights.push_back(l);
    return int(s.lights.size()) - 1;
}

/// Lambert's formula E = (L/2) |Σ Θ_i n·(v_i × v_{i+1})/|v_i × v_{i+1}|| over the triangle a b c,
/// entirely above p's tangent plane; written out here from the vertices, independent of the code's
/// Light::vertices and projectedSolidAngle.
double triangleIrradiance(const Vec3& a, const Vec3& b, const Vec3& c, double radiance, const Vec3& pf, const Vec3& nf) {
    const D3 p = toD(pf), n = toD(nf);
    const D3 vs[3] = {toD(a), toD(b), toD(c)};
    double sum = 0;
    for (int i = 0; i < 3; ++i) {
        D3 u = sub(vs[i], p), w = sub(vs[(i + 1) % 3], p);
        const double lu = lenD(u), lw = lenD(w);
        u = {u.x / lu, u.y / lu, u.z / lu};
        w = {w.x / lw, w.y / lw, w.z / lw};
        const D3 uxw = crossD(u, w);
        const double s = lenD(uxw);
        if (s == 0) continue;
        sum += std::atan2(s, dotD(u, w)) * dotD(n, uxw) / s;
    }
    return 0.5 * radiance * std::fabs(sum);
}

/// NEE mean of the floor's direct radiance at p against `expected` within `tol` (relative), where
/// the sample count makes `tol` at least 5 standard errors (asserted).
void expectDirect(const Scene& scene, const Vec3& p, double expected, int samples, uint64_t seed, const char* what,
                  double tol = 0.01) {
    const FloorShading st = shadeFloor(scene, p, samples, seed);
    EXPECT_EQ(st.nonFinite, 0u);
    EXPECT_LE(5 * st.direct.sigma(), tol * expected) << what << ": too few samples for the check";
    EXPECT_NEAR(st.direct.mean, expected, tol * expected) << what << " (σ = " << st.direct.sigma() << ")";
}

}  // namespace

TEST(TriangleLights, TwoHalvesOfASquareGiveTheSquaresIrradiance) {
    // Reference: the unit square at height 1 whose irradiance formula test_irradiance checks against
    // the coaxial-rectangle form factor. Its two triangles (split along the diagonal through the point
    // below the centre) each give exactly half of it by symmetry.
    Scene square = floorScene(kRho, 5.f);
    addCeilingLight(square, 0, 0, 1.f, 1.f, 4.f);
    const double eSquare = polygonIrradiance(square.lights[0], Vec3(0.f), Vec3(0, 1, 0));
    const Vec3 a(-0.5f, 1, -0.5f), b(0.5f, 1, -0.5f), c(0.5f, 1, 0.5f), d(-0.5f, 1, 0.5f);
    // Winding a c d / a b c: normal (c − a) × (d − a) = (b − a) × (c − a) = −y, facing the floor.
    EXPECT_NEAR(triangleIrradiance(a, c, d, 4.0, Vec3(0.f), Vec3(0, 1, 0)), 0.5 * eSquare, 1e-9);
    EXPECT_NEAR(triangleIrradiance(a, b, c, 4.0, Vec3(0.f), Vec3(0, 1, 0)), 0.5 * eSquare, 1e-9);

    Scene s = floorScene(kRho, 5.f);
    addTriangleLight(s, a, c, d, 4.f);
    addTriangleLight(s, a, b, c, 4.f);
    ASSERT_LT(s.lights[0].normal().y, -0.99f);
    ASSERT_LT(s.lights[1].normal().y, -0.99f);
    expectDirect(s, Vec3(0.f), kRho / kPiD * eSquare, 200000, 1, "under two triangles making a square");
}

TEST(TriangleLights, UnequalTrianglesMatchLambertFormula) {
    // Three triangles of different areas, radiances and tilts: the area-picked single sample must
    // still converge to the sum of their irradiances. Two-sided, so that every point sees each
    // triangle's emitting side whatever its tilt (Lambert's formula does not know sides).
    Scene s = floorScene(kRho, 30.f);
    const Vec3 t[3][3] = {{{-0.4f, 1.f, -0.3f}, {-0.4f, 1.f, 0.5f}, {0.6f, 1.f, -0.3f}},   // facing down
                          {{1.5f, 0.6f, 0.f}, {1.5f, 1.0f, 0.1f}, {1.6f, 0.8f, 0.9f}},     // steep, small
                          {{-2.f, 0.5f, -1.f}, {-2.f, 0.9f, 1.f}, {-1.f, 0.7f, -0.8f}}};   // large, far
    // No triangle shadows another from the test points (Lambert's formula knows no occlusion): the
    // first lies in the plane y = 1 and the others below it, on opposite sides.
    const float le[3] = {4.f, 10.f, 2.f};
    for (int i = 0; i < 3; ++i) addTriangleLight(s, t[i][0], t[i][1], t[i][2], le[i], false);
    for (const Vec3& p : {Vec3(0.f), Vec3(0.8f, 0.f, 0.3f), Vec3(-3.f, 0.f, 2.f)}) {
        double e = 0;
        for (const Light& l : s.lights) {
            Vec3 v[4];
            ASSERT_EQ(l.vertices(v), 3);
            e += triangleIrradiance(v[0], v[1], v[2], double(l.radiance.x), p, Vec3(0, 1, 0));
        }
        expectDirect(s, p, kRho / kPiD * e, 400000, 7, "three unequal triangles", 0.015);
    }
}

TEST(TriangleLights, BackOfAOneSidedTriangleIsDarkTwoSidedIsLit) {
    Scene s = floorScene(kRho, 5.f);
    const Vec3 a(-0.5f, 1, -0.5f), b(0.5f, 1, -0.5f), c(0.f, 1, 0.5f);
    const bool down = cross(b - a, c - a).y < 0.f;
    addTriangleLight(s, a, down ? c : b, down ? b : c, 4.f);  // wound to face up: the floor sees its back
    const FloorShading back = shadeFloor(s, Vec3(0.1f, 0, 0), 1000, 3);
    EXPECT_EQ(back.direct.mean, 0.0);
    s.lights[0].oneSided = false;
    expectDirect(s, Vec3(0.1f, 0, 0), kRho / kPiD * triangleIrradiance(a, b, c, 4.0, Vec3(0.1f, 0, 0), Vec3(0, 1, 0)),
                 200000, 4, "two-sided triangle seen from its back");
}

TEST(TriangleLights, WhiteFurnaceOfTriangleEmitters) {
    // The furnace of test_path_tracer with every face split into two triangle emitters (Le = 0.5,
    // Lambert albedo 0.5): every camera ray sees Le / (1 − a) = 1, direct 0.75 and indirect 0.25.
    // Light 0, a triangle, is the movable one, so the analytic intersection of a moving triangle
    // light is exercised too.
    Material wall;
    wall.kd = Vec3(0.5f);
    Scene s = furnaceScene(0.5f, wall);
    std::vector<Light> rects = s.lights;
    s.lights.clear();
    for (const Light& r : rects) {
        const Vec3 a = r.corner, b = r.corner + r.edge1, c = r.corner + r.edge1 + r.edge2, d = r.corner + r.edge2;
        addTriangleLight(s, a, b, c, 0.5f, true, 0);
        addTriangleLight(s, a, c, d, 0.5f, true, 0);
    }
    s.movableLight = 0;
    const Accel accel(s);
    for (const Estimator e : {Estimator::NEE, Estimator::Naive}) {
        // NEE's one area-picked sample over 12 triangles has a heavy tail near the cube's edges
        // (A/d² of a neighbouring face's triangle), so its check is 2.5% at 5σ; the naive
        // estimator's direct term is exact here (every BRDF ray hits an emitter) and gets 1%.
        const bool nee = e == Estimator::NEE;
        const double tol = nee ? 0.025 : 0.01;
        const ImageMeanStats st = traceImageMean(s, accel, e, nee ? 400000 : 40000, 11);
        EXPECT_EQ(st.nonFinite, 0u);
        EXPECT_LE(5 * st.direct.sigma(), tol * 0.75);
        EXPECT_NEAR(st.direct.mean, 0.75, tol * 0.75) << "σ = " << st.direct.sigma();
        EXPECT_NEAR(st.indirect.mean, 0.25, 5 * st.indirect.sigma() + 1e-3) << "σ = " << st.indirect.sigma();
        // Global: both estimators' indirect paths carry Russian-roulette noise; 2.5% at 5σ.
        EXPECT_LE(5 * st.global.sigma(), 0.025);
        EXPECT_NEAR(st.global.mean, 1.0, 0.025) << "σ = " << st.global.sigma();
    }
}

TEST(TriangleLights, ExactDirectUsesTheTrianglesClosedForm) {
    // Unoccluded: exact direct light is kd/π · E with E from Lambert's formula, no variance.
    Scene s = floorScene(kRho, 5.f);
    const Vec3 a(-0.5f, 1, -0.5f), b(0.7f, 1.2f, -0.4f), c(0.f, 0.9f, 0.6f);
    const bool down = cross(b - a, c - a).y < 0.f;
    addTriangleLight(s, a, down ? b : c, down ? c : b, 3.f);
    const Accel accel(s);
    const PathTracer tracer(s, accel, Estimator::NEE, 8);
    const ExactDirect exact(tracer, 16, 5);
    TraceCounters counters;
    for (const Vec3& p : {Vec3(0.f), Vec3(1.2f, 0, -0.7f), Vec3(-2.f, 0, 3.f)}) {
        const double e = triangleIrradiance(a, b, c, 3.0, p, Vec3(0, 1, 0));
        EXPECT_NEAR(projectedSolidAngle(s.lights[0], p, Vec3(0, 1, 0)) * 3.0, e, 1e-6 * e);
        const Vec3 L = exact.radiance(p, Vec3(0, 1, 0), Vec3(0, 1, 0), 0, s.lights[0], 17, counters);
        EXPECT_NEAR(L.x, kRho / kPiD * e, 1e-5 * e) << "at " << p;
    }
}

TEST(TriangleLights, PointAtIsUniformOnTheTriangle) {
    // The fold u+v > 1 → (1−u, 1−v) maps the unit square 2:1 onto the triangle: a uniform grid of
    // (u, v) lands with the triangle's centroid as its mean and never outside the triangle.
    Light l;
    l.type = Light::Type::Triangle;
    l.corner = Vec3(1, 2, 3);
    l.edge1 = Vec3(2, 0, 0);
    l.edge2 = Vec3(0.5f, 1, 0);
    Vec3 sum(0.f);
    const int n = 200;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const Vec3 x = l.pointAt((float(i) + 0.5f) / n, (float(j) + 0.5f) / n);
            // Barycentric coordinates in the (edge1, edge2) basis: both ≥ 0, sum ≤ 1.
            const Vec3 q = x - l.corner;
            const float bv = q.y / l.edge2.y, bu = (q.x - bv * l.edge2.x) / l.edge1.x;
            EXPECT_GE(bu, -1e-6f);
            EXPECT_GE(bv, -1e-6f);
            EXPECT_LE(bu + bv, 1.f + 1e-6f);
            sum += x;
        }
    const Vec3 mean = sum / float(n * n), centroid = l.corner + (l.edge1 + l.edge2) / 3.f;
    EXPECT_NEAR(mean.x, centroid.x, 1e-3);
    EXPECT_NEAR(mean.y, centroid.y, 1e-3);
    EXPECT_NEAR(l.center().x, centroid.x, 1e-6);
    EXPECT_NEAR(l.area(), 0.5f * 2.f * 1.f, 1e-6);
}

}  // namespace test_triangle_lights
