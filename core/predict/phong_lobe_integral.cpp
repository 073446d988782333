#include "core/predict/phong_lobe_integral.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Core>

namespace rrf {

namespace {

// Gauss–Legendre nodes and weights on [−1, 1], 8 points (the positive half; the rule is symmetric).
constexpr float kNode[4] = {0.1834346424956498f, 0.5255324099163290f, 0.7966664774136267f, 0.9602898564975363f};
constexpr float kWeight[4] = {0.3626837833783620f, 0.3137066458778873f, 0.2223810344533745f, 0.1012285362903763f};
float node(int i) { return i < 4 ? -kNode[3 - i] : kNode[i - 4]; }
float weight(int i) { return i < 4 ? kWeight[3 - i] : kWeight[i - 4]; }
/// The nodes as one packet.
Eigen::Array<float, kLobeNodes, 1> nodes() {
    Eigen::Array<float, kLobeNodes, 1> x;
    for (int i = 0; i < kLobeNodes; ++i) x[i] = node(i);
    return x;
}

constexpr float kTwoPi = 6.283185307179586f;

/// e^x − 1 without GLSL's missing expm1: the series where exp would cancel.
float expMinusOne(float x) { return x < 1e-3f ? x * (1.f + 0.5f * x) : std::exp(x) - 1.f; }

/// The light's plane seen from p, in the light's (u, v) coordinates: x(u, v) = corner + u·e1 + v·e2.
/// Every quantity the integrand needs is affine in (u, v) and set up once per receiver.
struct Setup {
    Vec3 q0, e1, e2;      ///< x − p = q0 + u e1 + v e2
    float a0, a1, a2;     ///< r·(x − p) = a0 + u a1 + v a2
    Vec3 p0, p1, p2;      ///< component of x − p across r = p0 + u p1 + v p2
    Vec3 n, lightNormal;  ///< receiver normal, unit light normal
    float e;
    bool oneSided;

    using Nodes = Eigen::Array<float, kLobeNodes, 1>;

    /// The integrand at (u, v_j) for the kLobeNodes values v_j of one panel, as Eigen packets (the
    /// lobe's exp and log included); the shader takes the same steps node by node.
    Nodes integrand(float u, const Nodes& v) const {
        const Nodes rd = (a0 + u * a1) + v * a2;  // r·d; ≤ 0 behind the mirror direction: cos α ≤ 0
        const Nodes dx = (q0.x + e1.x * u) + e2.x * v, dy = (q0.y + e1.y * u) + e2.y * v,
                    dz = (q0.z + e1.z * u) + e2.z * v;
        const Nodes dist2 = dx * dx + dy * dy + dz * dz;
        const Nodes inv = dist2.sqrt().inverse();
        const Nodes cosTheta = (n.x * dx + n.y * dy + n.z * dz) * inv;
        Nodes cosLight = -(lightNormal.x * dx + lightNormal.y * dy + lightNormal.z * dz) * inv;
        if (!oneSided) cosLight = cosLight.abs();
        const Nodes ax = (p0.x + p1.x * u) + p2.x * v, ay = (p0.y + p1.y * u) + p2.y * v,
                    az = (p0.z + p1.z * u) + p2.z * v;
        const Nodes sin2 = ((ax * ax + ay * ay + az * az) / dist2).min(1.f - 1e-7f);
        // log(1 − sin²α): the series where log would lose a small sin²α.
        const Nodes series = -sin2 * (1.f + sin2 * (0.5f + sin2 * (1.f / 3.f)));
        const Nodes direct = (1.f - sin2).log();  // apart: Eigen's select() takes coefficients one by one
        const Nodes logCos2 = (sin2 < 1e-3f).select(series, direct);
        const Nodes lobe = e == 0.f ? Nodes::Ones().eval() : (0.5f * e * logCos2).exp().eval();
        const Nodes value = lobe * cosTheta * cosLight / dist2;
        return (rd > 0.f && cosTheta > 0.f && cosLight > 0.f).select(value, 0.f);
    }
};

/// Inserts `x` into the sorted break list `b` (count `m`) when it lies strictly inside (b[0], b[m−1]).
void addBreak(float* b, int& m, float x) {
    if (!(x > b[0] && x < b[m - 1])) return;
    int k = m;
    while (k > 0 && b[k - 1] > x) {
        b[k] = b[k - 1];
        --k;
    }
    b[k] = x;
    ++m;
}

}  // namespace

float lobeFootprintTan2(float e) {
    if (!(e > 0.f)) return std::numeric_limits<float>::infinity();
    const float lnEps = std::log(1e-6f * kTwoPi / (e + 2.f));
    const float x = -2.f * lnEps / e;
    return x > 80.f ? std::numeric_limits<float>::infinity() : expMinusOne(x);
}

float phongLobeIntegral(const Light& l, const Vec3& p, const Vec3& n, const Vec3& r, float e) {
    const Vec3 nl = cross(l.edge1, l.edge2);
    const float area2 = length(nl);  // |e1 × e2|: the Jacobian of (u, v) → x for rects and triangles
    if (!(area2 > 0.f)) return 0.f;
    Setup s;
    s.q0 = l.corner - p;
    s.e1 = l.edge1;
    s.e2 = l.edge2;
    s.n = n;
    s.lightNormal = nl / area2;
    s.e = e;
    s.oneSided = l.oneSided;
    if (l.oneSided && dot(s.q0, nl) >= 0.f) return 0.f;  // p behind the emitting side
    s.a0 = dot(r, s.q0);
    s.a1 = dot(r, s.e1);
    s.a2 = dot(r, s.e2);
    s.p0 = s.q0 - r * s.a0;
    s.p1 = s.e1 - r * s.a1;
    s.p2 = s.e2 - r * s.a2;
    const bool triangle = l.type == Light::Type::Triangle;

    // 1. Footprint: Q(u, v) = τ² (r·d)² − |d across r|² ≥ 0, a quadratic A u² + 2B uv + C v² + 2D u + 2E v + F.
    float u0 = 0.f, u1 = 1.f, v0 = 0.f, v1 = 1.f;
    const float tau2 = lobeFootprintTan2(e);
    if (std::isfinite(tau2)) {
        const float A = tau2 * s.a1 * s.a1 - dot(s.p1, s.p1);
        const float B = tau2 * s.a1 * s.a2 - dot(s.p1, s.p2);
        const float C = tau2 * s.a2 * s.a2 - dot(s.p2, s.p2);
        const float D = tau2 * s.a0 * s.a1 - dot(s.p0, s.p1);
        const float E = tau2 * s.a0 * s.a2 - dot(s.p0, s.p2);
        const float F = tau2 * s.a0 * s.a0 - dot(s.p0, s.p0);
        const float det = A * C - B * B;
        if (A < 0.f && C < 0.f && det > 0.f) {  // an ellipse
            const float uc = (B * E - C * D) / det, vc = (B * D - A * E) / det;
            const float qc = D * uc + E * vc + F;  // Q at the centre: the ellipse is δᵀ(−M)δ ≤ qc
            if (s.a0 + s.a1 * uc + s.a2 * vc <= 0.f || !(qc > 0.f)) return 0.f;
            const float hu = std::sqrt(qc * -C / det), hv = std::sqrt(qc * -A / det);
            // 2. The whole lobe on the light and above the horizon (sin α_max = τ/√(1+τ²) < n·r).
            const float nr = dot(n, r);
            const bool inside = uc - hu > 0.f && vc - hv > 0.f &&
                                (triangle ? (uc + hu) + (vc + hv) < 1.f : uc + hu < 1.f && vc + hv < 1.f);
            if (inside && nr > 0.f && nr * nr > tau2 / (1.f + tau2)) return kTwoPi * nr / (e + 2.f);
            u0 = std::max(u0, uc - hu);
            u1 = std::min(u1, uc + hu);
            v0 = std::max(v0, vc - hv);
            v1 = std::min(v1, vc + hv);
            if (!(u0 < u1) || !(v0 < v1)) return 0.f;
        }
    }

    // 3. Panels split at the mirror ray's hit (ur, vr), and for a triangle at the inner limit's kink.
    float ur = -1.f, vr = -1.f;
    const float denom = dot(r, nl);
    if (denom != 0.f) {
        const float t = dot(s.q0, nl) / denom;
        if (t > 0.f) {
            const Vec3 q = r * t - s.q0;
            const float nn = dot(nl, nl);
            ur = dot(cross(q, s.e2), nl) / nn;
            vr = dot(cross(s.e1, q), nl) / nn;
        }
    }
    float ub[4] = {u0, u1};
    int mu = 2;
    addBreak(ub, mu, ur);
    if (triangle) addBreak(ub, mu, 1.f - v1);
    float sum = 0.f;
    for (int pu = 0; pu + 1 < mu; ++pu) {
        const float hu = 0.5f * (ub[pu + 1] - ub[pu]), cu = 0.5f * (ub[pu + 1] + ub[pu]);
        for (int i = 0; i < kLobeNodes; ++i) {
            const float u = cu + hu * node(i);
            const float top = triangle ? std::min(v1, 1.f - u) : v1;
            if (!(top > v0)) continue;
            float vb[3] = {v0, top};
            int mv = 2;
            addBreak(vb, mv, vr);
            float inner = 0.f;
            for (int pv = 0; pv + 1 < mv; ++pv) {
                const float hv = 0.5f * (vb[pv + 1] - vb[pv]), cv = 0.5f * (vb[pv + 1] + vb[pv]);
                const Setup::Nodes f = s.integrand(u, cv + hv * nodes());
                float panel = 0.f;  // in node order, as the shader sums
                for (int j = 0; j < kLobeNodes; ++j) panel += weight(j) * f[j];
                inner += hv * panel;
            }
            sum += hu * weight(i) * inner;
        }
    }
    return sum * area2;
}

}  // namespace rrf
