#pragma once
/// Float RGB images: the common currency of the renderer, the predictor and the error maps.
///
/// Layout: row-major, top row first, x grows to the right; three floats (R, G, B) per pixel, linear
/// radiance (never gamma-encoded). File I/O lives in core/util/image_io.h.

#include <cstddef>
#include <vector>

#include "core/util/vec3.h"

namespace rrf {

struct Image {
    int width = 0;
    int height = 0;
    /// 3 * width * height floats, pixel (x, y) at index 3 * (y * width + x).
    std::vector<float> data;

    Image() = default;
    /// A width × height image filled with `fill`. Throws std::invalid_argument for negative sizes
    /// or sizes whose float count overflows size_t.
    Image(int w, int h, const Vec3& fill = Vec3(0.f));

    size_t pixelCount() const { return size_t(width) * size_t(height); }
    bool empty() const { return width == 0 || height == 0; }

    /// Pixel (x, y); unchecked, as these sit in per-pixel loops (0 ≤ x < width, 0 ≤ y < height).
    Vec3 at(int x, int y) const {
        const float* p = &data[index(x, y)];
        return {p[0], p[1], p[2]};
    }
    void set(int x, int y, const Vec3& c) {
        float* p = &data[index(x, y)];
        p[0] = c.x;
        p[1] = c.y;
        p[2] = c.z;
    }

    /// Mean pixel value, accumulated in double. A non-finite pixel makes the mean non-finite on
    /// purpose: an average must not hide a NaN (check nonFiniteCount() first).
    Vec3 mean() const;

    /// Number of pixels with at least one NaN or infinite channel.
    size_t nonFiniteCount() const;

private:
    size_t index(int x, int y) const { return 3 * (size_t(y) * size_t(width) + size_t(x)); }
};

/// Rec. 709 / sRGB-primaries luminance of a linear RGB value.
inline float luminance(const Vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

/// Maps the first channel of `scalar` through the viridis colour map: values ≤ lo give the dark
/// purple end, values ≥ hi the yellow end, linear in between. The result is linear RGB (the
/// colour map is defined in sRGB and decoded here), so a PNG written with exposure 0 shows the
/// published viridis colours. Non-finite inputs become magenta (1, 0, 1), which viridis never
/// produces, so a NaN in an error map stays visible instead of blending into the scale.
/// If hi == lo, values > lo map to the top and everything else to the bottom.
/// Throws std::invalid_argument if lo or hi is not finite or hi < lo.
Image falseColor(const Image& scalar, float lo, float hi);

/// The viridis colour (linear RGB) for t in [0, 1] (clamped); the map behind falseColor().
Vec3 viridis(float t);

/// False colour for a signed scalar (first channel) on [−range, range]: Moreland's cool-warm
/// diverging map (blue below zero, near-white at zero, red above; values beyond ±range at the ends),
/// linear RGB, magenta for non-finite inputs as falseColor(). Throws std::invalid_argument unless
/// range is finite and > 0.
Image signedFalseColor(const Image& scalar, float range);
/// The cool-warm colour (linear RGB) for t in [−1, 1] (clamped); the map behind signedFalseColor().
Vec3 coolWarm(float t);

/// The exact sRGB transfer functions (IEC 61966-2-1 piecewise curves), for values in [0, 1].
float srgbToLinear(float c);
float linearToSrgb(float c);

}  // namespace rrf
