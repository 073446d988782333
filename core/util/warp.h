#pragma once
/// Warping functions from [0,1)² to directions, with their densities (solid angle). All directions
/// are in the local frame of the surface (z = normal). Written for the hard cases of docs/design.md §7:
/// Phong exponents up to 1e6 must give finite, correctly distributed directions.

#include <cmath>

#include "core/util/vec3.h"

namespace rrf {

/// Cosine-weighted hemisphere: θ = arccos(√(1−u)), φ = 2πv; pdf = cosθ/π.
inline Vec3 sampleCosineHemisphere(float u, float v) {
    const float cosTheta = std::sqrt(1.f - u);
    const float sinTheta = std::sqrt(u);
    const float phi = 2.f * kPi * v;
    return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}
inline float cosineHemispherePdf(float cosTheta) { return cosTheta > 0 ? cosTheta * kInvPi : 0.f; }

/// cos^n(α) for cos α ∈ [0,1] without NaN: 0 for cos α ≤ 0, and pow's underflow to 0 is fine.
inline float powCos(float cosAlpha, float n) {
    if (cosAlpha <= 0.f) return 0.f;
    if (n == 0.f) return 1.f;
    return float(std::exp(double(n) * std::log(double(cosAlpha))));
}

/// Phong lobe around the local z axis: cos α = u^{1/(n+1)}, pdf = (n+1)/(2π) cos^n α.
/// sin α is computed as √(−expm1(2 ln u/(n+1))) so that it stays accurate when cos α rounds to 1
/// (n ≈ 1e6), where √(1 − cos²α) would collapse the whole lobe onto the axis.
inline Vec3 samplePhongLobe(float u, float v, float n) {
    const double lnu = std::log(double(u > 0.f ? u : 0x1.0p-25f));
    const double cosAlpha = std::exp(lnu / (double(n) + 1.0));
    const double sinAlpha = std::sqrt(std::max(0.0, -std::expm1(2.0 * lnu / (double(n) + 1.0))));
    const double phi = 2.0 * 3.14159265358979323846 * double(v);
    return {float(sinAlpha * std::cos(phi)), float(sinAlpha * std::sin(phi)), float(cosAlpha)};
}
inline float phongLobePdf(float cosAlpha, float n) {
    return cosAlpha > 0.f ? (n + 1.f) * kInv2Pi * powCos(cosAlpha, n) : 0.f;
}

/// Uniform direction on the unit sphere; pdf = 1/(4π).
inline Vec3 sampleUniformSphere(float u, float v) {
    const float z = 1.f - 2.f * u;
    const float r = std::sqrt(std::max(0.f, 1.f - z * z));
    const float phi = 2.f * kPi * v;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

}  // namespace rrf
