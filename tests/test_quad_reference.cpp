#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include <embree3/rtcore.h>

#include "tests/quad_reference.h"
#include "core/util/rng.h"
#include "core/util/vec3.h"

using namespace rrf;

namespace {

using Quad = std::array<Vec3, 4>;  // v00 v10 v11 v01 == Embree's v0 v1 v2 v3

/// One Embree device and a one-quad scene built with the raw API, as the renderer's own
/// acceleration structure would (robust mode), so the comparison is against Embree itself.
class EmbreeQuad {
public:
    EmbreeQuad(RTCDevice device, const Quad& q) {
        scene_ = rtcNewScene(device);
        rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
        RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_QUAD);
        auto* vb = static_cast<float*>(
            rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 4));
        auto* ib = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(unsigned), 1));
        for (int i = 0; i < 4; ++i) {
            vb[3 * i] = q[i].x;
            vb[3 * i + 1] = q[i].y;
            vb[3 * i + 2] = q[i].z;
            ib[i] = unsigned(i);
        }
        rtcCommitGeometry(geom);
        rtcAttachGeometry(scene_, geom);
        rtcReleaseGeometry(geom);
        rtcCommitScene(scene_);
    }
    ~EmbreeQuad() { rtcReleaseScene(scene_); }
    EmbreeQuad(const EmbreeQuad&) = delete;
    EmbreeQuad& operator=(const EmbreeQuad&) = delete;

    bool intersect(const Vec3& o, const Vec3& d, float& t) const {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRayHit rh{};
        rh.ray.org_x = o.x;
        rh.ray.org_y = o.y;
        rh.ray.org_z = o.z;
        rh.ray.dir_x = d.x;
        rh.ray.dir_y = d.y;
        rh.ray.dir_z = d.z;
        rh.ray.tnear = 0.f;
        rh.ray.tfar = std::numeric_limits<float>::infinity();
        rh.ray.mask = 0xFFFFFFFFu;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene_, &ctx, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
        t = rh.ray.tfar;
        return true;
    }

private:
    RTCScene scene_ = nullptr;
};

struct Device {
    RTCDevice handle = rtcNewDevice(nullptr);
    ~Device() { rtcReleaseDevice(handle); }
};

Vec3 randomUnit(Rng& rng) {
    const float z = 2.f * rng.uniform() - 1.f;
    const float phi = 2.f * kPi * rng.uniform();
    const float r = std::sqrt(std::max(0.f, 1.f - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

enum class Shape { Parallelogram, TrapezoidU, TrapezoidV, Convex };

/// A random planar convex quad: built in 2D, then placed with a random orientation, position
/// and scale (10^-2 … 10^3). 2D vertices in boundary order; the winding is random.
Quad randomQuad(Rng& rng, Shape shape, float& size) {
    std::array<float, 8> p{};  // x0 y0 … x3 y3
    auto set = [&](int i, float x, float y) { p[2 * i] = x; p[2 * i + 1] = y; };
    if (shape == Shape::Parallelogram) {
        const float a = 0.2f + rng.uniform(), b = 0.2f + rng.uniform();
        const float phi = 0.3f + 2.5f * rng.uniform();  // angle between the sides
        set(0, 0, 0);
        set(1, a, 0);
        set(2, a + b * std::cos(phi), b * std::sin(phi));
        set(3, b * std::cos(phi), b * std::sin(phi));
    } else if (shape == Shape::TrapezoidU || shape == Shape::TrapezoidV) {
        // Bottom and top parallel; top shorter and shifted, but still convex.
        const float w = 0.5f + rng.uniform(), h = 0.2f + rng.uniform();
        const float top = w * (0.2f + 0.7f * rng.uniform());
        const float shift = (w - top) * rng.uniform();
        set(0, 0, 0);
        set(1, w, 0);
        set(2, shift + top, h);
        set(3, shift, h);
        if (shape == Shape::TrapezoidV) {  // rotate the labels: the parallel sides become v00v01, v10v11
            const std::array<float, 8> c = p;
            for (int i = 0; i < 4; ++i) set(i, c[2 * ((i + 1) % 4)], c[2 * ((i + 1) % 4) + 1]);
        }
    } else {
        // Four points on an ellipse in angular order form a convex quad; keep every gap between
        // 0.35 and pi - 0.35 rad so no corner is degenerate.
        std::array<float, 4> gap{};
        for (;;) {
            float sum = 0;
            for (float& g : gap) sum += (g = 0.2f + rng.uniform());
            bool ok = true;
            for (float& g : gap) ok = ok && (g = g / sum * 2.f * kPi) > 0.35f && g < kPi - 0.35f;
            if (ok) break;
        }
        const float ax = 0.5f + rng.uniform(), ay = 0.5f + rng.uniform();
        float ang = 2.f * kPi * rng.uniform();
        for (int i = 0; i < 4; ++i) {
            set(i, ax * std::cos(ang), ay * std::sin(ang));
            ang += gap[size_t(i)];
        }
    }
    const Frame frame(randomUnit(rng));
    const float scale = std::pow(10.f, -2.f + 5.f * rng.uniform());
    const Vec3 center = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * (4.f * scale) - Vec3(2.f * scale);
    Quad q;
    for (int i = 0; i < 4; ++i) q[size_t(i)] = center + frame.toWorld(Vec3(p[2 * i], p[2 * i + 1], 0.f) * scale);
    if (rng.uniform() < 0.5f) std::swap(q[1], q[3]);  // opposite winding, same boundary
    size = 0;
    for (int i = 0; i < 4; ++i) size = std::max(size, length(q[size_t(i)] - q[size_t((i + 1) % 4)]));
    return q;
}

/// Distance from x to the quad's boundary (double precision, on the float vertices).
double boundaryDistance(const Quad& q, const Vec3& x) {
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 4; ++i) {
        const Vec3 a = q[size_t(i)], b = q[size_t((i + 1) % 4)];
        const double ab[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
        const double ax[3] = {double(x.x) - a.x, double(x.y) - a.y, double(x.z) - a.z};
        const double len2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
        double s = (ab[0] * ax[0] + ab[1] * ax[1] + ab[2] * ax[2]) / len2;
        s = std::min(1.0, std::max(0.0, s));
        const double d[3] = {ax[0] - s * ab[0], ax[1] - s * ab[1], ax[2] - s * ab[2]};
        best = std::min(best, std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
    }
    return best;
}

/// Point where the ray meets the quad's plane (double precision); false if parallel or behind.
bool planeHit(const Quad& q, const Vec3& o, const Vec3& d, Vec3& x) {
    const Vec3 n = cross(q[1] - q[0], q[3] - q[0]);
    const double nd = double(n.x) * d.x + double(n.y) * d.y + double(n.z) * d.z;
    if (nd == 0) return false;
    const double num = double(n.x) * (double(q[0].x) - o.x) + double(n.y) * (double(q[0].y) - o.y) +
                       double(n.z) * (double(q[0].z) - o.z);
    const double t = num / nd;
    x = Vec3(float(o.x + t * d.x), float(o.y + t * d.y), float(o.z + t * d.z));
    return t > 0;
}

}  // namespace

TEST(QuadReference, RecoversBilinearCoordinatesOfEveryShape) {
    // Shoot at known (u, v) points: the reference must give them back, on every code path
    // (parallelogram, both trapezoid branches, the quadratic).
    Rng rng(2024, 1);
    for (int shape = 0; shape < 4; ++shape)
        for (int k = 0; k < 200; ++k) {
            float size;
            const Quad q = randomQuad(rng, Shape(shape), size);
            const float u0 = 0.02f + 0.96f * rng.uniform(), v0 = 0.02f + 0.96f * rng.uniform();
            const Vec3 target = bilinearQuadPoint(q[0], q[1], q[2], q[3], u0, v0);
            const Vec3 n = normalize(cross(q[1] - q[0], q[3] - q[0]));
            const Vec3 origin = target + (n + 0.5f * randomUnit(rng)) * (2.f * size);
            float t, u, v;
            ASSERT_TRUE(intersectQuadLagaeDutre(origin, target - origin, q[0], q[1], q[2], q[3], t, u, v))
                << "shape " << shape << " k " << k;
            EXPECT_NEAR(u, u0, 1e-4f) << "shape " << shape << " k " << k;
            EXPECT_NEAR(v, v0, 1e-4f) << "shape " << shape << " k " << k;
            EXPECT_NEAR(t, 1.f, 1e-5f);
        }
}

TEST(QuadReference, UnitSquareByHand) {
    const Vec3 v00(0, 0, 0), v10(1, 0, 0), v11(1, 1, 0), v01(0, 1, 0);
    float t = -1, u = -1, v = -1;
    ASSERT_TRUE(intersectQuadLagaeDutre({0.25f, 0.75f, 2.f}, {0, 0, -0.5f}, v00, v10, v11, v01, t, u, v));
    EXPECT_FLOAT_EQ(t, 4.f);  // in units of |dir|
    EXPECT_FLOAT_EQ(u, 0.25f);
    EXPECT_FLOAT_EQ(v, 0.75f);
    ASSERT_TRUE(intersectQuadLagaeDutre({0.9f, 0.8f, -1.f}, {0, 0, 1}, v00, v10, v11, v01, t, u, v));  // back side
    EXPECT_FLOAT_EQ(u, 0.9f);
    EXPECT_FALSE(intersectQuadLagaeDutre({1.1f, 0.5f, 1.f}, {0, 0, -1}, v00, v10, v11, v01, t, u, v));
    EXPECT_FALSE(intersectQuadLagaeDutre({0.5f, 0.5f, 1.f}, {0, 0, 1}, v00, v10, v11, v01, t, u, v));  // behind
    EXPECT_FLOAT_EQ(u, 0.9f);  // a miss leaves the outputs alone
}

TEST(QuadReference, AgreesWithEmbreeOnRandomQuads) {
    Device device;
    ASSERT_NE(device.handle, nullptr);
    Rng rng(7, 0);
    constexpr int kQuads = 240, kRaysPerQuad = 500;  // 120k rays
    long hits = 0, misses = 0, nearEdge = 0, grazing = 0, mismatches = 0, tErrors = 0, uvErrors = 0;
    double worstT = 0, worstUv = 0;
    for (int qi = 0; qi < kQuads; ++qi) {
        float size;
        const Quad q = randomQuad(rng, Shape(qi % 4), size);
        const EmbreeQuad embree(device.handle, q);
        Vec3 center(0.f);
        for (const Vec3& p : q) center += p * 0.25f;
        const Vec3 e1 = q[1] - q[0], e3 = q[3] - q[0];
        const Vec3 normal = normalize(cross(e1, e3));
        for (int r = 0; r < kRaysPerQuad; ++r) {
            // Aim at the quad's neighbourhood so hits and misses are both common; every tenth ray
            // takes a fully random direction.
            const Vec3 origin = center + randomUnit(rng) * (size * (1.5f + 3.f * rng.uniform()));
            const Vec3 target = q[0] + e1 * (1.6f * rng.uniform() - 0.3f) + e3 * (1.6f * rng.uniform() - 0.3f);
            Vec3 dir = r % 10 == 0 ? randomUnit(rng) : target - origin;
            dir = dir * (size * (0.5f + 1.5f * rng.uniform()) / length(dir));  // |dir| need not be 1

            float tE = 0, tR = 0, u = 0, v = 0;
            const bool hitE = embree.intersect(origin, dir, tE);
            const bool hitR = intersectQuadLagaeDutre(origin, dir, q[0], q[1], q[2], q[3], tR, u, v);
            // Embree works in single precision, and float vertices are coplanar only to ~1e-7 of
            // the quad's size, so where a ray meets the quad is uncertain by about
            // eps·(distance + size)/cos(angle to the normal). Grazing rays (cos < 1e-2) are
            // excused from the comparison (below cos = 1e-6 the reference even calls them
            // parallel); only finite results are required of them.
            const double cosTheta = std::fabs(dot(normal, dir)) / length(dir);
            if (cosTheta < 1e-2) {
                ++grazing;
                EXPECT_TRUE(!hitE || std::isfinite(tE));
                EXPECT_TRUE(!hitR || (std::isfinite(tR) && std::isfinite(u) && std::isfinite(v)));
                continue;
            }
            // Rays within 1e-5·size of an edge may go either way; at oblique incidence the band
            // widens to the float uncertainty above.
            Vec3 x;
            if (planeHit(q, origin, dir, x)) {
                const double reach = length(x - origin) + size;
                const double band = std::max(1e-5 * size, 4 * FLT_EPSILON * reach / cosTheta);
                if (boundaryDistance(q, x) <= band) {
                    ++nearEdge;
                    continue;
                }
            }
            if (hitE != hitR) {
                if (++mismatches <= 5)
                    ADD_FAILURE() << "quad " << qi << " ray " << r << ": embree " << hitE << " reference " << hitR
                                  << " origin " << origin << " dir " << dir << " boundary distance "
                                  << boundaryDistance(q, x) / size << " x size";
                continue;
            }
            if (!hitR) {
                ++misses;
                continue;
            }
            ++hits;
            const double dt = std::fabs(double(tE) - tR) / tR;
            worstT = std::max(worstT, dt);
            if (dt > 1e-4 && ++tErrors <= 5)
                ADD_FAILURE() << "quad " << qi << " ray " << r << ": t embree " << tE << " reference " << tR;
            // The reference's (u, v) must reproduce its own hit point.
            const Vec3 xr = origin + dir * tR;
            const double duv = length(bilinearQuadPoint(q[0], q[1], q[2], q[3], u, v) - xr) / size;
            worstUv = std::max(worstUv, duv);
            if ((duv > 1e-4 || u < -1e-4f || u > 1 + 1e-4f || v < -1e-4f || v > 1 + 1e-4f) && ++uvErrors <= 5)
                ADD_FAILURE() << "quad " << qi << " ray " << r << ": (u, v) = (" << u << ", " << v
                              << ") reproduces the hit to " << duv << " x size";
        }
    }
    EXPECT_EQ(mismatches, 0);
    EXPECT_EQ(tErrors, 0);
    EXPECT_EQ(uvErrors, 0);
    // The comparison means something only if both outcomes are common and few rays were excused.
    EXPECT_GT(hits, kQuads * kRaysPerQuad / 5);
    EXPECT_GT(misses, kQuads * kRaysPerQuad / 5);
    EXPECT_LT(nearEdge, kQuads * kRaysPerQuad / 1000);
    EXPECT_LT(grazing, kQuads * kRaysPerQuad / 40);  // ~1% of random directions are within cos 1e-2
    RecordProperty("hits", int(hits));
    RecordProperty("misses", int(misses));
    RecordProperty("near_edge", int(nearEdge));
    RecordProperty("grazing", int(grazing));
    std::printf("[ quad ] %ld hits, %ld misses compared; %ld near an edge, %ld grazing excused; "
                "worst relative t difference %.3g, worst (u,v) reproduction %.3g x size\n",
                hits, misses, nearEdge, grazing, worstT, worstUv);
}

TEST(QuadReference, RaysThroughVerticesStayFinite) {
    Device device;
    Rng rng(11, 0);
    for (int qi = 0; qi < 40; ++qi) {
        float size;
        const Quad q = randomQuad(rng, Shape(qi % 4), size);
        const EmbreeQuad embree(device.handle, q);
        const float corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (int i = 0; i < 4; ++i) {
            const Vec3 origin = q[size_t(i)] + randomUnit(rng) * (2.f * size);
            const Vec3 dir = q[size_t(i)] - origin;
            float t = NAN, u = NAN, v = NAN, tE = NAN;
            if (intersectQuadLagaeDutre(origin, dir, q[0], q[1], q[2], q[3], t, u, v)) {
                EXPECT_TRUE(std::isfinite(t) && std::isfinite(u) && std::isfinite(v));
                EXPECT_NEAR(t, 1.f, 1e-4f);
                EXPECT_NEAR(u, corner[i][0], 1e-3f) << "quad " << qi << " vertex " << i;
                EXPECT_NEAR(v, corner[i][1], 1e-3f) << "quad " << qi << " vertex " << i;
            }
            if (embree.intersect(origin, dir, tE)) {
                EXPECT_NEAR(tE, 1.f, 1e-4f);
            }
        }
    }
}

TEST(QuadReference, RaysJustInsideVerticesAndEdgesHit) {
    // The exact-vertex and in-plane edge rays above may hit or miss; rays aimed 1% of the way from a
    // vertex or an edge midpoint towards the centroid (inside: every quad here is convex) must hit,
    // in both intersectors, with (u, v) at that vertex or edge midpoint.
    Device device;
    Rng rng(14, 0);
    const float corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const float midpoint[4][2] = {{0.5f, 0}, {1, 0.5f}, {0.5f, 1}, {0, 0.5f}};  // edge i: vertex i → i+1
    int checked = 0;
    for (int qi = 0; qi < 40; ++qi) {
        float size;
        const Quad q = randomQuad(rng, Shape(qi % 4), size);
        const EmbreeQuad embree(device.handle, q);
        const Vec3 centroid = (q[0] + q[1] + q[2] + q[3]) * 0.25f;
        const Vec3 n = normalize(cross(q[1] - q[0], q[3] - q[0]));
        for (int i = 0; i < 8; ++i) {
            const bool vertex = i < 4;
            const int k = i % 4;
            const Vec3 at = vertex ? q[size_t(k)] : (q[size_t(k)] + q[size_t((k + 1) % 4)]) * 0.5f;
            const float* uv = vertex ? corner[k] : midpoint[k];
            const Vec3 target = at + (centroid - at) * 0.01f;
            Vec3 offset = randomUnit(rng);
            if (std::fabs(dot(offset, n)) < 0.2f) offset = offset + n;  // not grazing
            const Vec3 origin = target + normalize(offset) * (2.f * size);
            const Vec3 dir = target - origin;
            float t = NAN, u = NAN, v = NAN, tE = NAN;
            ASSERT_TRUE(intersectQuadLagaeDutre(origin, dir, q[0], q[1], q[2], q[3], t, u, v))
                << "quad " << qi << (vertex ? " vertex " : " edge ") << k;
            EXPECT_NEAR(t, 1.f, 1e-4f);
            EXPECT_NEAR(u, uv[0], 0.03f) << "quad " << qi << (vertex ? " vertex " : " edge ") << k;
            EXPECT_NEAR(v, uv[1], 0.03f) << "quad " << qi << (vertex ? " vertex " : " edge ") << k;
            ASSERT_TRUE(embree.intersect(origin, dir, tE)) << "quad " << qi << (vertex ? " vertex " : " edge ") << k;
            EXPECT_NEAR(tE, 1.f, 1e-4f);
            ++checked;
        }
    }
    EXPECT_EQ(checked, 320);
}

TEST(QuadReference, RaysAlongEdgesStayFinite) {
    Device device;
    Rng rng(12, 0);
    for (int qi = 0; qi < 40; ++qi) {
        float size;
        const Quad q = randomQuad(rng, Shape(qi % 4), size);
        const EmbreeQuad embree(device.handle, q);
        for (int i = 0; i < 4; ++i) {
            const Vec3 a = q[size_t(i)], b = q[size_t((i + 1) % 4)];
            for (const Vec3& origin : {a - (b - a) * 0.5f, a, (a + b) * 0.5f}) {
                float t = 0, u = 0, v = 0, tE = 0;
                if (intersectQuadLagaeDutre(origin, b - a, q[0], q[1], q[2], q[3], t, u, v)) {
                    EXPECT_TRUE(std::isfinite(t) && std::isfinite(u) && std::isfinite(v));
                }
                if (embree.intersect(origin, b - a, tE)) {
                    EXPECT_TRUE(std::isfinite(tE));
                }
            }
        }
    }
    // Exactly representable in-plane edge rays are parallel to the quad: a miss, not a NaN.
    float t, u, v;
    EXPECT_FALSE(intersectQuadLagaeDutre({-1, 0, 0}, {1, 0, 0}, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, t, u, v));
    EXPECT_FALSE(intersectQuadLagaeDutre({1, -1, 0}, {0, 1, 0}, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, t, u, v));
}

TEST(QuadReference, ParallelRaysMiss) {
    Device device;
    Rng rng(13, 0);
    for (int qi = 0; qi < 40; ++qi) {
        float size;
        const Quad q = randomQuad(rng, Shape(qi % 4), size);
        const EmbreeQuad embree(device.handle, q);
        const Vec3 n = normalize(cross(q[1] - q[0], q[3] - q[0]));
        const Frame f(n);
        for (int k = 0; k < 20; ++k) {
            const float phi = 2.f * kPi * rng.uniform();
            const Vec3 dir = f.s * std::cos(phi) + f.t * std::sin(phi);  // in the plane's direction
            const Vec3 origin = q[0] - dir * (2.f * size) + n * (size * (0.01f + rng.uniform()));
            float t, u, v, tE;
            EXPECT_FALSE(intersectQuadLagaeDutre(origin, dir, q[0], q[1], q[2], q[3], t, u, v)) << "quad " << qi;
            EXPECT_FALSE(embree.intersect(origin, dir, tE));
        }
    }
}

TEST(QuadReference, DegenerateQuadsStayFinite) {
    float t, u, v;
    // Zero area (all vertices on a line): nothing to hit.
    EXPECT_FALSE(intersectQuadLagaeDutre({0.5f, 0, 1}, {0, 0, -1}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, t, u, v));
    EXPECT_FALSE(intersectQuadLagaeDutre({0, 0, 1}, {0, 0, -1}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, t, u, v));
    // A triangle given as a quad (v11 == v10): interior hits are finite, including at the
    // collapsed corner.
    const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    Rng rng(14, 0);
    for (int k = 0; k < 1000; ++k) {
        const float x = rng.uniform(), y = rng.uniform() * (1 - x);
        if (intersectQuadLagaeDutre({x, y, 1}, {0, 0, -1}, a, b, b, c, t, u, v)) {
            EXPECT_TRUE(std::isfinite(t) && std::isfinite(u) && std::isfinite(v));
            const Vec3 p = bilinearQuadPoint(a, b, b, c, u, v);
            EXPECT_NEAR(p.x, x, 1e-4f);
            EXPECT_NEAR(p.y, y, 1e-4f);
        }
    }
    if (intersectQuadLagaeDutre({1, 0, 1}, {0, 0, -1}, a, b, b, c, t, u, v)) {
        EXPECT_TRUE(std::isfinite(u) && std::isfinite(v));
    }
}
