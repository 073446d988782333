#pragma once
/// Internals shared by the FLIP sources (flip.cpp, flip_colour.cpp, flip_feature.cpp): a scalar
/// plane, the separable clamp-to-edge filter and the input checks. Not part of the API; see
/// core/eval/flip.h for the method and its conventions.

#include <cmath>
#include <cstddef>
#include <vector>

#include "core/eval/flip.h"
#include "core/util/image.h"

namespace rrf::flip_internal {

/// One float per pixel, row-major like Image.
struct Plane {
    int width = 0;
    int height = 0;
    std::vector<float> v;

    Plane() = default;
    Plane(int w, int h) : width(w), height(h), v(size_t(w) * size_t(h), 0.f) {}
    float& operator()(int x, int y) { return v[size_t(y) * size_t(width) + size_t(x)]; }
    float operator()(int x, int y) const { return v[size_t(y) * size_t(width) + size_t(x)]; }
};

/// A 1D kernel that is symmetric (k(−i) = k(i)) or antisymmetric (k(−i) = −k(i), so k(0) = 0)
/// about its centre, stored from the centre out: taps[i] = k(i) for i = 0 … radius. Every FLIP
/// filter is one or the other. The filter adds mirrored taps as pairs, so an antisymmetric kernel
/// answers a constant with exactly 0 (no feature in a flat region, not a rounding residue).
struct Kernel1D {
    std::vector<float> taps;
    bool odd = false;
    int radius() const { return int(taps.size()) - 1; }
};

/// response(x, y) = Σ_i k(i) · in(clamp(x + i), y): correlation along each row, clamp-to-edge.
Plane filterRows(const Plane& in, const Kernel1D& k);
/// response(x, y) = Σ_i k(i) · in(x, clamp(y + i)): correlation along each column, clamp-to-edge.
Plane filterColumns(const Plane& in, const Kernel1D& k);

/// Throws std::invalid_argument unless the two images have the same size and the settings'
/// pixels per degree is finite and > 0. `who` names the caller in the message.
void checkFlipInputs(const Image& reference, const Image& test, const FlipSettings& settings, const char* who);

/// True when pixel p (y · width + x) of `image` has a NaN or infinite channel.
inline bool nonFinitePixel(const Image& image, size_t p) {
    const float* c = &image.data[3 * p];
    return !(std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]));
}

/// An input channel as LDR-FLIP reads it: clamped to [0, 1], non-finite as 0 (black).
inline double ldrChannel(float v) {
    if (!std::isfinite(v)) return 0.0;
    return v < 0.f ? 0.0 : (v > 1.f ? 1.0 : double(v));
}

}  // namespace rrf::flip_internal
