// Radiometry on spheres and triangle meshes (the other tests use quads): a furnace, where a convex
// Lambert object inside a cube of uniform emitters has radiance ρ·Le everywhere; the exact
// point-light radiance on a sphere at analytically computed hit points; and the irradiance under a
// rectangle light on a triangle mesh against Lambert's polygon formula.

#include <gtest/gtest.h>

#include <cmath>

#include "core/render/path_tracer.h"
#include "core/scene/accel.h"
#include "scene_builders.h"

namespace test_shape_radiometry {

using namespace rrf;
using namespace rrf::test;

namespace {

constexpr double kPiD = 3.14159265358979323846;

int addSphere(Scene& s, const Vec3& c, float r, int material) {
    Object o;
    o.kind = Object::Kind::Sphere;
    o.name = "sphere";
    o.id = int(s.objects.size());
    o.material = material;
    o.center = c;
    o.radius = r;
    o.closed = true;
    s.objects.push_back(o);
    return o.id;
}

/// The regular octahedron |x| + |y| + |z| ≤ r around c as 8 outward-facing triangles.
int addOctahedron(Scene& s, const Vec3& c, float r, int material) {
    Object o;
    o.kind = Object::Kind::Triangles;
    o.name = "octahedron";
    o.id = int(s.objects.size());
    o.material = material;
    o.closed = true;
    o.positions = {c + Vec3(r, 0, 0), c + Vec3(-r, 0, 0), c + Vec3(0, r, 0),
                   c + Vec3(0, -r, 0), c + Vec3(0, 0, r), c + Vec3(0, 0, -r)};
    for (const int sx : {0, 1})
        for (const int sy : {2, 3})
            for (const int sz : {4, 5}) {
                // Counter-clockwise seen from outside: the sign of the permutation follows the octant.
                const bool flip = ((sx == 1) + (sy == 3) + (sz == 5)) % 2 == 1;
                o.indices.push_back(uint32_t(sx));
                o.indices.push_back(uint32_t(flip ? sz : sy));
                o.indices.push_back(uint32_t(flip ? sy : sz));
            }
    s.objects.push_back(std::move(o));
    return int(s.objects.size()) - 1;
}

/// Six black one-sided emitters of radiance `le` closing the cube [-1, 1]³, facing inwards.
void addEmitterCube(Scene& s, float le) {
    for (const QuadSpec& q : inwardCubeFaces(1.f)) addRectLight(s, q.corner, q.e1, q.e2, Vec3(le));
}

/// Mean first-channel radiance (direct, indirect) of rays from `eye` towards points jittered
/// around `target` by up to `spread`, all of which must hit object `object`.
void expectFurnace(const Scene& s, Estimator e, const Vec3& eye, const Vec3& target, float spread, double expected,
                   const char* what) {
    const Accel accel(s);
    const PathTracer tracer(s, accel, e);
    TraceCounters counters;
    RunningStat direct;
    for (int i = 0; i < 100000; ++i) {
        Rng rng(70, uint64_t(i));
        const Vec3 aim = target + Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f) * spread;
        Ray ray;
        ray.origin = eye;
        ray.dir = normalize(aim - eye);
        Hit hit;
        ASSERT_TRUE(accel.intersect(ray, hit) && hit.object == 0) << what << ": ray " << i << " misses the object";
        const Radiance L = tracer.trace(ray, rng, counters);
        ASSERT_TRUE(L.indirect.isZero()) << what << ": the walls are black, so nothing arrives by two bounces";
        direct.add(L.direct.x);
    }
    // NEE's six one-sample light estimates are noisy; the naive estimator is exact here (every
    // cosine-sampled bounce sees Le, weight ρ), so only float rounding separates it from ρ·Le.
    EXPECT_LT(5 * direct.sigma(), 0.025 * expected) << what << ": too few samples";
    EXPECT_NEAR(direct.mean, expected, 5 * direct.sigma() + 1e-6 * expected) << what;
}

}  // namespace

TEST(ShapeRadiometry, ConvexSphereAndMeshInAFurnaceReflectAlbedoTimesLe) {
    // A convex surface sees only the emitting cube in its whole hemisphere: L = ρ Le, exactly.
    for (const Estimator e : {Estimator::NEE, Estimator::Naive}) {
        const char* name = e == Estimator::NEE ? "NEE" : "naive";
        Scene sphere;
        addSphere(sphere, Vec3(0.1f, -0.1f, 0.f), 0.45f, addLambert(sphere, Vec3(0.6f)));
        addEmitterCube(sphere, 0.5f);
        expectFurnace(sphere, e, Vec3(0.7f, 0.6f, 0.8f), Vec3(0.1f, -0.1f, 0.f), 0.4f, 0.6 * 0.5,
                      (std::string("sphere, ") + name).c_str());
        Scene mesh;
        addOctahedron(mesh, Vec3(0.f, 0.1f, -0.1f), 0.6f, addLambert(mesh, Vec3(0.7f)));
        addEmitterCube(mesh, 0.5f);
        expectFurnace(mesh, e, Vec3(0.8f, 0.7f, 0.75f), Vec3(0.f, 0.1f, -0.1f), 0.3f, 0.7 * 0.5,
                      (std::string("octahedron, ") + name).c_str());
    }
}

TEST(ShapeRadiometry, PointLightOnASphereIsExactAtAnalyticHitPoints) {
    // L = ρ/π · I cosθ / d² at the hit point, computed in double from the ray–sphere intersection;
    // points facing away from the light are black. NEE of a point light has no randomness.
    Scene s;
    const D3 c{0.2, 0.1, -0.3};
    const double r = 0.8, rho = 0.55, I = 3.0;
    addSphere(s, Vec3(float(c.x), float(c.y), float(c.z)), float(r), addLambert(s, Vec3(float(rho))));
    const D3 light{1.5, 2.5, 0.5};
    addPointLight(s, Vec3(float(light.x), float(light.y), float(light.z)), Vec3(float(I)));
    const Accel accel(s);
    const PathTracer tracer(s, accel, Estimator::NEE);
    TraceCounters counters;
    const D3 eye{0.4, 0.6, 4.0};
    int lit = 0, dark = 0;
    for (int i = 0; i < 400; ++i) {
        Rng rng(71, uint64_t(i));
        // Aim at a random point of the sphere's bounding square seen from the eye; keep the hits.
        const D3 aim{c.x + (2 * rng.uniform() - 1) * r, c.y + (2 * rng.uniform() - 1) * r, c.z};
        D3 d = sub(aim, eye);
        const double len = lenD(d);
        d = {d.x / len, d.y / len, d.z / len};
        const D3 oc = sub(eye, c);
        const double b = dotD(oc, d), disc = b * b - (dotD(oc, oc) - r * r);
        if (disc < 1e-3) continue;  // a miss or a grazing hit, where float and double may disagree
        const double t = -b - std::sqrt(disc);
        const D3 p{eye.x + t * d.x, eye.y + t * d.y, eye.z + t * d.z};
        const D3 n{(p.x - c.x) / r, (p.y - c.y) / r, (p.z - c.z) / r};
        const D3 toLight = sub(light, p);
        const double dist = lenD(toLight), cosTheta = dotD(n, toLight) / dist;
        const double expected = cosTheta > 0 ? rho / kPiD * I * cosTheta / (dist * dist) : 0.0;
        Ray ray;
        ray.origin = Vec3(float(eye.x), float(eye.y), float(eye.z));
        ray.dir = Vec3(float(d.x), float(d.y), float(d.z));
        const Radiance L = tracer.trace(ray, rng, counters);
        if (cosTheta > 0.05) {
            ++lit;
            EXPECT_NEAR(L.direct.x, expected, 2e-3 * expected) << "ray " << i;
        } else if (cosTheta < -0.05) {
            ++dark;
            EXPECT_EQ(L.direct.x, 0.f) << "ray " << i << " sees the unlit side";
        }
    }
    EXPECT_GT(lit, 50);
    EXPECT_GT(dark, 20);
}

TEST(ShapeRadiometry, RectLightOnATriangleMeshMatchesLambertsPolygonFormula) {
    // A floor of two triangles under a square light: ρ E / π at points found by tracing rays.
    Scene s;
    const int m = addLambert(s, Vec3(0.5f));
    Object o;
    o.kind = Object::Kind::Triangles;
    o.name = "floor";
    o.material = m;
    o.positions = {Vec3(-3, 0, -3), Vec3(3, 0, -3), Vec3(3, 0, 3), Vec3(-3, 0, 3)};
    o.indices = {0, 2, 1, 0, 3, 2};  // normals +y
    s.objects.push_back(o);
    addCeilingLight(s, 0.3f, -0.2f, 1.5f, 1.f);
    const Accel accel(s);
    const PathTracer tracer(s, accel, Estimator::NEE);
    TraceCounters counters;
    for (const Vec3 p : {Vec3(0.3f, 0.f, -0.2f), Vec3(-1.1f, 0.f, 0.7f), Vec3(1.9f, 0.f, 1.4f)}) {
        const double expected = 0.5 / kPiD * polygonIrradiance(s.lights[0], p, Vec3(0, 1, 0));
        Ray ray;
        ray.origin = p + Vec3(-0.9f, 1.2f, 0.8f);  // from above, beside the light
        ray.dir = normalize(p - ray.origin);
        RunningStat st;
        for (int i = 0; i < 40000; ++i) {
            Rng rng(72, uint64_t(i));
            st.add(tracer.trace(ray, rng, counters).direct.x);
        }
        EXPECT_LT(5 * st.sigma(), 0.01 * expected) << p;
        EXPECT_NEAR(st.mean, expected, 5 * st.sigma() + 2e-3 * expected) << p;
    }
}

}  // namespace test_shape_radiometry
