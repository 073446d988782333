#include "tests/quad_reference.h"

#include <algorithm>
#include <cmath>

namespace rrf {

namespace {

/// Double-precision 3-vector, local to the reference so its accuracy does not depend on Vec3.
struct D3 {
    double x, y, z;
};

D3 toD(const Vec3& a) { return {a.x, a.y, a.z}; }
D3 sub(const D3& a, const D3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dotD(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 crossD(const D3& a, const D3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double lengthD(const D3& a) { return std::sqrt(dotD(a, a)); }

/// Relative threshold of the "ray parallel to the triangle" test: the paper's 1e-6, made
/// scale-free (see the header). Float vertices of a "planar" quad are only coplanar to ~1e-7 of
/// its size, so rays closer to parallel than this have no well-defined hit anyway.
constexpr double kParallelEps = 1e-6;
/// Tolerance of the paper's parallelogram/trapezoid classification of alpha11 and beta11
/// (dimensionless, so an absolute epsilon is right here).
constexpr double kShapeEps = 1e-9;

/// How far (u, v) may stray outside [0, 1] through rounding before a hit is declared spurious.
constexpr double kUvSlack = 1e-5;

/// Distance of x from the interval [0, 1] (infinite for NaN); picks the meaningful root of the
/// quadratic and catches spurious hits.
double outside01(double x) {
    if (x >= 0) return x > 1 ? x - 1 : 0;
    return x < 0 ? -x : HUGE_VAL;
}

}  // namespace

bool intersectQuadLagaeDutre(const Vec3& origin, const Vec3& dir, const Vec3& v00f, const Vec3& v10f,
                             const Vec3& v11f, const Vec3& v01f, float& tOut, float& uOut, float& vOut) {
    const D3 O = toD(origin), D = toD(dir);
    const D3 v00 = toD(v00f), v10 = toD(v10f), v11 = toD(v11f), v01 = toD(v01f);

    // Reject rays parallel to the quad, and rays that hit its plane on the far side of the lines
    // v00 v01 (alpha < 0) or v00 v10 (beta < 0).
    const D3 e01 = sub(v10, v00);
    const D3 e03 = sub(v01, v00);
    const D3 p = crossD(D, e03);
    const double det = dotD(e01, p);
    if (!(std::fabs(det) > kParallelEps * lengthD(D) * lengthD(e01) * lengthD(e03))) return false;
    const double invDet = 1.0 / det;
    const D3 T = sub(O, v00);
    const double alpha = dotD(T, p) * invDet;
    if (alpha < 0) return false;
    const D3 q = crossD(T, e01);
    const double beta = dotD(D, q) * invDet;
    if (beta < 0) return false;

    // Reject rays that hit the plane on the far side of the lines v11 v10 or v11 v01.
    if (alpha + beta > 1) {
        const D3 e23 = sub(v01, v11);
        const D3 e21 = sub(v10, v11);
        const D3 p2 = crossD(D, e21);
        const double det2 = dotD(e23, p2);
        if (!(std::fabs(det2) > kParallelEps * lengthD(D) * lengthD(e23) * lengthD(e21))) return false;
        const double invDet2 = 1.0 / det2;
        const D3 T2 = sub(O, v11);
        const double alpha2 = dotD(T2, p2) * invDet2;
        if (alpha2 < 0) return false;
        const D3 q2 = crossD(T2, e23);
        const double beta2 = dotD(D, q2) * invDet2;
        if (beta2 < 0) return false;
    }

    // Ray parameter of the hit.
    const double t = dotD(e03, q) * invDet;
    if (!(t > 0)) return false;

    // Barycentric coordinates of v11 with respect to v00, v10, v01: v11 = v00 + alpha11·e01 +
    // beta11·e03, solved in the coordinate plane where the normal is largest (best conditioned).
    const D3 e02 = sub(v11, v00);
    const D3 n = crossD(e01, e03);
    double alpha11, beta11;
    const double ax = std::fabs(n.x), ay = std::fabs(n.y), az = std::fabs(n.z);
    if (ax >= ay && ax >= az) {
        alpha11 = (e02.y * e03.z - e02.z * e03.y) / n.x;
        beta11 = (e01.y * e02.z - e01.z * e02.y) / n.x;
    } else if (ay >= ax && ay >= az) {
        alpha11 = (e02.z * e03.x - e02.x * e03.z) / n.y;
        beta11 = (e01.z * e02.x - e01.x * e02.z) / n.y;
    } else {
        alpha11 = (e02.x * e03.y - e02.y * e03.x) / n.z;
        beta11 = (e01.x * e02.y - e01.y * e02.x) / n.z;
    }

    // Bilinear coordinates of the hit.
    double u, v;
    if (std::fabs(alpha11 - 1) < kShapeEps) {
        u = alpha;
        if (std::fabs(beta11 - 1) < kShapeEps) v = beta;              // parallelogram
        else v = beta / (u * (beta11 - 1) + 1);                       // trapezoid, v01 v11 ∥ v00 v10
    } else if (std::fabs(beta11 - 1) < kShapeEps) {
        v = beta;                                                     // trapezoid, v10 v11 ∥ v00 v01
        u = alpha / (v * (alpha11 - 1) + 1);
    } else {
        const double A = 1 - beta11;
        const double B = alpha * (beta11 - 1) - beta * (alpha11 - 1) - 1;
        const double C = alpha;
        const double delta = B * B - 4 * A * C;
        const double qq = -0.5 * (B + (B < 0 ? -1.0 : 1.0) * std::sqrt(delta > 0 ? delta : 0.0));
        const double r1 = qq / A, r2 = C / qq;
        u = outside01(r1) <= outside01(r2) || !std::isfinite(r2) ? r1 : r2;
        v = beta / (u * (beta11 - 1) + 1);
    }
    // The two wedge tests above see the ray hit the planes of two different triangles. With float
    // vertices those planes differ slightly, and a nearly parallel ray can pass both tests at two
    // far-apart points outside the quad; its (u, v) then lies far outside [0, 1]. (Also rejects the
    // non-finite (u, v) at the collapsed corner of a degenerate quad.)
    if (!(outside01(u) <= kUvSlack) || !(outside01(v) <= kUvSlack)) return false;

    tOut = float(t);
    uOut = float(std::min(1.0, std::max(0.0, u)));
    vOut = float(std::min(1.0, std::max(0.0, v)));
    return true;
}

Vec3 bilinearQuadPoint(const Vec3& v00, const Vec3& v10, const Vec3& v11, const Vec3& v01, float u, float v) {
    return (1 - u) * (1 - v) * v00 + u * (1 - v) * v10 + u * v * v11 + (1 - u) * v * v01;
}

}  // namespace rrf
