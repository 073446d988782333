#include "core/util/image.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rrf {

Image::Image(int w, int h, const Vec3& fill) : width(w), height(h) {
    if (w < 0 || h < 0)
        throw std::invalid_argument("Image: negative size " + std::to_string(w) + "x" + std::to_string(h));
    if (w > 0 && size_t(h) > std::numeric_limits<size_t>::max() / 3 / size_t(w))
        throw std::invalid_argument("Image: size " + std::to_string(w) + "x" + std::to_string(h) +
                                    " is too large");
    data.resize(3 * pixelCount());
    for (size_t i = 0; i < data.size(); i += 3) {
        data[i] = fill.x;
        data[i + 1] = fill.y;
        data[i + 2] = fill.z;
    }
}

Vec3 Image::mean() const {
    if (empty()) return Vec3(0.f);
    double s[3] = {0, 0, 0};
    for (size_t i = 0; i < data.size(); i += 3) {
        s[0] += data[i];
        s[1] += data[i + 1];
        s[2] += data[i + 2];
    }
    const double n = double(pixelCount());
    return {float(s[0] / n), float(s[1] / n), float(s[2] / n)};
}

size_t Image::nonFiniteCount() const {
    size_t bad = 0;
    for (size_t i = 0; i < data.size(); i += 3)
        if (!std::isfinite(data[i]) || !std::isfinite(data[i + 1]) || !std::isfinite(data[i + 2])) ++bad;
    return bad;
}

float srgbToLinear(float c) {
    // Evaluated in double so the 8-bit table built from it rounds the same on every platform.
    const double d = c;
    return float(d <= 0.04045 ? d / 12.92 : std::pow((d + 0.055) / 1.055, 2.4));
}

float linearToSrgb(float c) {
    const double d = c;
    return float(d <= 0.0031308 ? 12.92 * d : 1.055 * std::pow(d, 1.0 / 2.4) - 0.055);
}

namespace {

// matplotlib's viridis (van der Walt & Smith, CC0), every 15th of its 256 sRGB entries. Linear
// interpolation between these stays within 5/255 of the full table, which is invisible in an error
// map and keeps the table short enough to check by eye.
constexpr int kViridisKnots = 18;
constexpr float kViridis[kViridisKnots][3] = {
    {0.267004f, 0.004874f, 0.329415f}, {0.281924f, 0.089666f, 0.412415f},
    {0.280255f, 0.165693f, 0.476498f}, {0.263663f, 0.237631f, 0.518762f},
    {0.237441f, 0.305202f, 0.541921f}, {0.208623f, 0.367752f, 0.552675f},
    {0.182256f, 0.426184f, 0.557120f}, {0.159194f, 0.482237f, 0.558073f},
    {0.137770f, 0.537492f, 0.554906f}, {0.121148f, 0.592739f, 0.544641f},
    {0.128087f, 0.647749f, 0.523491f}, {0.180653f, 0.701402f, 0.488189f},
    {0.274149f, 0.751988f, 0.436601f}, {0.395174f, 0.797475f, 0.367757f},
    {0.535621f, 0.835785f, 0.281908f}, {0.688944f, 0.865448f, 0.182725f},
    {0.845561f, 0.887322f, 0.099702f}, {0.993248f, 0.906157f, 0.143936f},
};

}  // namespace

Vec3 viridis(float t) {
    if (!(t > 0.f)) t = 0.f;  // also catches NaN
    if (t > 1.f) t = 1.f;
    const float s = t * float(kViridisKnots - 1);
    const int k = std::min(int(s), kViridisKnots - 2);
    const float f = s - float(k);
    Vec3 c;
    for (int ch = 0; ch < 3; ++ch) {
        // Interpolate in sRGB, where the table was designed to be perceptually uniform.
        const float e = kViridis[k][ch] * (1.f - f) + kViridis[k + 1][ch] * f;
        c[ch] = srgbToLinear(e);
    }
    return c;
}

Vec3 coolWarm(float t) {
    // Moreland (2009), "Diverging Color Maps for Scientific Visualization": the cool-warm map's ends
    // and centre in sRGB, interpolated in linear RGB through the centre. Both halves have the same
    // lightness profile, so a bias of +x and −x stand out equally.
    static const float cool[3] = {59 / 255.f, 76 / 255.f, 192 / 255.f}, mid[3] = {221 / 255.f, 221 / 255.f, 221 / 255.f},
                       warm[3] = {180 / 255.f, 4 / 255.f, 38 / 255.f};
    t = std::clamp(std::isfinite(t) ? t : 0.f, -1.f, 1.f);
    const float* end = t < 0 ? cool : warm;
    const float a = std::fabs(t);
    Vec3 c;
    for (int ch = 0; ch < 3; ++ch) c[ch] = (1 - a) * srgbToLinear(mid[ch]) + a * srgbToLinear(end[ch]);
    return c;
}

Image signedFalseColor(const Image& scalar, float range) {
    if (!std::isfinite(range) || !(range > 0))
        throw std::invalid_argument("signedFalseColor: invalid range " + std::to_string(range) + " (need finite > 0)");
    Image out(scalar.width, scalar.height);
    for (int y = 0; y < scalar.height; ++y)
        for (int x = 0; x < scalar.width; ++x) {
            const float v = scalar.at(x, y).x;
            out.set(x, y, std::isfinite(v) ? coolWarm(v / range) : Vec3(1.f, 0.f, 1.f));
        }
    return out;
}

Image falseColor(const Image& scalar, float lo, float hi) {
    if (!std::isfinite(lo) || !std::isfinite(hi) || hi < lo)
        throw std::invalid_argument("falseColor: invalid range [" + std::to_string(lo) + ", " +
                                    std::to_string(hi) + "] (need finite lo <= hi)");
    Image out(scalar.width, scalar.height);
    const Vec3 magenta(1.f, 0.f, 1.f);
    const double range = double(hi) - double(lo);
    for (int y = 0; y < scalar.height; ++y)
        for (int x = 0; x < scalar.width; ++x) {
            const float v = scalar.at(x, y).x;
            if (!std::isfinite(v)) {
                out.set(x, y, magenta);
                continue;
            }
            float t;
            if (range > 0) t = float((double(v) - double(lo)) / range);
            else t = v > lo ? 1.f : 0.f;
            out.set(x, y, viridis(t));
        }
    return out;
}

}  // namespace rrf
