#include "core/predict/light_polygon.h"

#include <cmath>

namespace rrf {

namespace {

struct D3 {
    double x, y, z;
};
D3 d3(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }
D3 operator-(const D3& a, const D3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator+(const D3& a, const D3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator*(const D3& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dotD(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 crossD(const D3& a, const D3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
Vec3 f3(const D3& v) { return Vec3(float(v.x), float(v.y), float(v.z)); }

}  // namespace

double projectedSolidAngle(const Light& l, const Vec3& pf, const Vec3& nf, Vec3* centroid, ClippedLight* clipped) {
    if (centroid) *centroid = pf;
    if (clipped) clipped->count = 0;
    const D3 p = d3(pf), n = d3(nf);
    const D3 c = d3(l.corner), e1 = d3(l.edge1), e2 = d3(l.edge2);
    if (l.oneSided && dotD(p - c, crossD(e1, e2)) <= 0.0) return 0.0;  // behind the emitting side
    Vec3 corners[4];
    const int nv = l.vertices(corners);
    D3 quad[4];
    for (int k = 0; k < nv; ++k) quad[k] = d3(corners[k]) - p;
    // Clip to the receiver's hemisphere: the part below the horizon sends no light to the surface.
    D3 poly[5];
    int m = 0;
    for (int k = 0; k < nv; ++k) {
        const D3 &a = quad[k], &b = quad[(k + 1) % nv];
        const double ha = dotD(a, n), hb = dotD(b, n);
        if (ha >= 0.0) poly[m++] = a;
        if ((ha >= 0.0) != (hb >= 0.0)) poly[m++] = a + (b - a) * (ha / (ha - hb));
    }
    if (m < 3) return 0.0;
    D3 mean{0, 0, 0};
    double sum = 0.0;
    for (int k = 0; k < m; ++k) {
        const D3 a = poly[k], b = poly[(k + 1) % m];
        mean = mean + a;
        const double la = std::sqrt(dotD(a, a)), lb = std::sqrt(dotD(b, b));
        if (!(la > 0.0) || !(lb > 0.0)) return 0.0;  // p on a vertex of the light
        const D3 axb = crossD(a, b);
        const double s = std::sqrt(dotD(axb, axb));
        if (s == 0.0) continue;  // edge collinear with p: subtends no angle
        // atan2 rather than acos: accurate for the tiny angles of distant or grazing edges.
        sum += std::atan2(s, dotD(a, b)) * dotD(n, axb) / s;
    }
    if (centroid) *centroid = f3(p + mean * (1.0 / m));
    if (clipped) {
        for (int k = 0; k < m; ++k) clipped->vertex[k] = f3(p + poly[k]);
        clipped->count = m;
    }
    return 0.5 * std::fabs(sum);
}

}  // namespace rrf
