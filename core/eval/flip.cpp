/// LDR-FLIP's final error and HDR-FLIP (exposure range, tone mapping, max over exposures), plus the
/// separable filter the colour and feature pipelines share.
#include "core/eval/flip.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/eval/flip_internal.h"

namespace rrf {

namespace flip_internal {

// Both filters add the centre tap first, then the mirrored pairs i = 1 … radius in order, so the
// sum runs in one fixed order whatever the image.
Plane filterRows(const Plane& in, const Kernel1D& k) {
    Plane out(in.width, in.height);
    const int r = k.radius(), w = in.width;
    const float sign = k.odd ? -1.f : 1.f;
    std::vector<float> padded(size_t(w) + 2 * size_t(r));
    for (int y = 0; y < in.height; ++y) {
        const float* row = &in.v[size_t(y) * size_t(w)];
        for (int i = 0; i < w + 2 * r; ++i) padded[size_t(i)] = row[std::clamp(i - r, 0, w - 1)];
        float* o = &out.v[size_t(y) * size_t(w)];
        for (int x = 0; x < w; ++x) {
            const float* c = &padded[size_t(x + r)];
            float acc = k.taps[0] * c[0];
            for (int i = 1; i <= r; ++i) acc += k.taps[size_t(i)] * (c[i] + sign * c[-i]);
            o[x] = acc;
        }
    }
    return out;
}

Plane filterColumns(const Plane& in, const Kernel1D& k) {
    Plane out(in.width, in.height);
    const int r = k.radius(), w = in.width, h = in.height;
    const float sign = k.odd ? -1.f : 1.f;
    for (int y = 0; y < h; ++y) {
        float* o = &out.v[size_t(y) * size_t(w)];
        const float* c = &in.v[size_t(y) * size_t(w)];
        for (int x = 0; x < w; ++x) o[x] = k.taps[0] * c[x];
        for (int i = 1; i <= r; ++i) {
            const float* up = &in.v[size_t(std::clamp(y + i, 0, h - 1)) * size_t(w)];
            const float* down = &in.v[size_t(std::clamp(y - i, 0, h - 1)) * size_t(w)];
            const float t = k.taps[size_t(i)];
            for (int x = 0; x < w; ++x) o[x] += t * (up[x] + sign * down[x]);
        }
    }
    return out;
}

void checkFlipInputs(const Image& reference, const Image& test, const FlipSettings& settings, const char* who) {
    if (reference.width != test.width || reference.height != test.height)
        throw std::invalid_argument(std::string(who) + ": image sizes differ (" + std::to_string(reference.width) + "x" +
                                    std::to_string(reference.height) + " vs " + std::to_string(test.width) + "x" +
                                    std::to_string(test.height) + ")");
    if (!std::isfinite(settings.pixelsPerDegree) || !(settings.pixelsPerDegree > 0))
        throw std::invalid_argument(std::string(who) + ": invalid pixels per degree " +
                                    std::to_string(settings.pixelsPerDegree) + " (need finite > 0)");
}

}  // namespace flip_internal

namespace {

// Narkowicz's ACES fit with its 0.6 input scale folded in: t(x) = (k0 x² + k1 x) / (k3 x² + k4 x + k5).
constexpr double kFlipTm[6] = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};
// The tone-mapped value the exposure range puts the brightest and the median pixel at.
constexpr double kFlipRangeTarget = 0.85;

double flipToneCurve(double x) {
    const double num = (kFlipTm[0] * x + kFlipTm[1]) * x + kFlipTm[2];
    const double den = (kFlipTm[3] * x + kFlipTm[4]) * x + kFlipTm[5];
    return std::clamp(num / den, 0.0, 1.0);
}

// The x ≥ 0 with t(x) = target: the positive root of (k0 − k3 t) x² + (k1 − k4 t) x + (k2 − k5 t) = 0.
double flipToneInverse(double target) {
    const double a = kFlipTm[0] - kFlipTm[3] * target;
    const double c0 = (kFlipTm[1] - kFlipTm[4] * target) / a, c1 = (kFlipTm[2] - kFlipTm[5] * target) / a;
    return -0.5 * c0 + std::sqrt(0.25 * c0 * c0 - c1);
}

// The 50th percentile with linear interpolation; reorders `v`.
double flipMedian(std::vector<double>& v) {
    const size_t mid = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(mid), v.end());
    const double upper = v[mid];
    if (v.size() % 2 == 1) return upper;
    const double lower = *std::max_element(v.begin(), v.begin() + std::ptrdiff_t(mid));
    return 0.5 * (lower + upper);
}

}  // namespace

Image ldrFlip(const Image& reference, const Image& test, const FlipSettings& settings) {
    const Image colour = flipColourDifference(reference, test, settings);
    const Image feature = flipFeatureDifference(reference, test, settings);
    Image out(reference.width, reference.height);
    for (size_t i = 0; i < out.data.size(); i += 3) {
        const float c = colour.data[i], f = feature.data[i];
        // HPG 2020, "final error": features raise the colour error towards 1 (ΔEc ≤ 1, so a smaller
        // exponent gives a larger value). NaN stays NaN (std::pow(NaN, 0) would give 1).
        const float e = std::isnan(c) || std::isnan(f) ? std::numeric_limits<float>::quiet_NaN()
                                                       : float(std::pow(double(c), 1.0 - double(f)));
        out.data[i] = out.data[i + 1] = out.data[i + 2] = e;
    }
    return out;
}

double flipExposure(const FlipExposureRange& range, int i) {
    return range.start + double(i) * (range.stop - range.start) / double(std::max(range.count - 1, 1));
}

FlipExposureRange flipExposureRange(const Image& reference) {
    std::vector<double> lum;
    lum.reserve(reference.pixelCount());
    double ymax = 0.0;
    for (size_t p = 0; p < reference.pixelCount(); ++p) {
        if (flip_internal::nonFinitePixel(reference, p)) continue;
        const float* c = &reference.data[3 * p];
        const double y = 0.2126 * std::max(double(c[0]), 0.0) + 0.7152 * std::max(double(c[1]), 0.0) +
                         0.0722 * std::max(double(c[2]), 0.0);
        lum.push_back(y);
        ymax = std::max(ymax, y);
    }
    FlipExposureRange range;
    if (!(ymax > 0.0)) return range;  // nothing lit: start = stop = 0
    double ymedian = flipMedian(lum);
    if (!(ymedian > 0.0)) {
        lum.erase(std::remove_if(lum.begin(), lum.end(), [](double y) { return !(y > 0.0); }), lum.end());
        ymedian = flipMedian(lum);
    }
    const double x85 = flipToneInverse(kFlipRangeTarget);
    range.start = std::log2(x85 / ymax);
    range.stop = std::log2(x85 / ymedian);
    range.count = std::max(2, int(std::ceil(range.stop - range.start)));
    return range;
}

Image flipToneMap(const Image& hdr, double exposure) {
    Image out(hdr.width, hdr.height);
    const double scale = std::exp2(exposure);
    for (size_t i = 0; i < hdr.data.size(); ++i) {
        const float v = hdr.data[i];
        out.data[i] = std::isfinite(v) ? float(flipToneCurve(scale * std::max(double(v), 0.0)))
                                       : std::numeric_limits<float>::quiet_NaN();
    }
    return out;
}

Image hdrFlip(const Image& reference, const Image& test, const FlipExposureRange& range, const FlipSettings& settings,
              std::vector<int>* maxExposureIndex) {
    flip_internal::checkFlipInputs(reference, test, settings, "hdrFlip");
    if (range.count < 1 || !std::isfinite(range.start) || !std::isfinite(range.stop))
        throw std::invalid_argument("hdrFlip: invalid exposure range (start " + std::to_string(range.start) + ", stop " +
                                    std::to_string(range.stop) + ", count " + std::to_string(range.count) + ")");
    const size_t n = reference.pixelCount();
    Image out(reference.width, reference.height, Vec3(-1.f));
    std::vector<int> best(n, -1);
    for (int i = 0; i < range.count; ++i) {
        const double exposure = flipExposure(range, i);
        const Image e = ldrFlip(flipToneMap(reference, exposure), flipToneMap(test, exposure), settings);
        for (size_t p = 0; p < n; ++p) {
            const float v = e.data[3 * p];
            float& o = out.data[3 * p];
            if (std::isnan(o)) continue;
            if (std::isnan(v)) {
                o = v;
                best[p] = -1;
            } else if (v > o) {
                o = v;
                best[p] = i;
            }
        }
    }
    for (size_t p = 0; p < n; ++p) out.data[3 * p + 1] = out.data[3 * p + 2] = out.data[3 * p];
    if (maxExposureIndex) *maxExposureIndex = std::move(best);
    return out;
}

}  // namespace rrf
