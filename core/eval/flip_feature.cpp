/// LDR-FLIP's feature pipeline (HPG 2020, "feature pipeline"): edges and points of the luminance,
/// found with Gaussian derivative filters, compared between reference and test.
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/eval/flip.h"
#include "core/eval/flip_internal.h"

namespace rrf {

namespace {

using flip_internal::Kernel1D;
using flip_internal::Plane;

constexpr double kFlipFeatureWidth = 0.082;  // peak-to-trough width of the edge detector, degrees
constexpr double kFlipQf = 0.5;              // exponent on the feature difference

// The three 1D factors of the detectors. With g(x) = exp(−x² / 2σ²), σ = ½ · 0.082° · ppd pixels
// and radius ⌈3σ⌉, the 2D edge filter is −x g(x) g(y) and the point filter (x²/σ² − 1) g(x) g(y)
// (and their transposes), normalised so that the positive weights sum to 1 and the negative ones
// to −1. The sign of both depends on x alone, so the normalisation splits into the factors: the x
// factor is normalised that way, the y factor g / Σg.
struct FlipFeatureKernels {
    Kernel1D gauss, edge, point;
};

FlipFeatureKernels flipFeatureKernels(double ppd) {
    const double sigma = 0.5 * kFlipFeatureWidth * ppd;
    const int radius = int(std::ceil(3.0 * sigma));
    std::vector<double> g(size_t(radius) + 1), h(size_t(radius) + 1);
    double gSum = 0.0, edgePositive = 0.0, pointPositive = 0.0, pointNegative = 0.0;
    for (int i = 0; i <= radius; ++i) {
        const double x = double(i), w = i == 0 ? 1.0 : 2.0;  // taps i > 0 stand for ±i
        g[size_t(i)] = std::exp(-x * x / (2.0 * sigma * sigma));
        h[size_t(i)] = (x * x / (sigma * sigma) - 1.0) * g[size_t(i)];
        gSum += w * g[size_t(i)];
        edgePositive += x * g[size_t(i)];  // −x g(x) is positive at −i: i g(i)
        if (h[size_t(i)] > 0) pointPositive += w * h[size_t(i)];
        else pointNegative -= w * h[size_t(i)];
    }
    FlipFeatureKernels k;
    k.edge.odd = true;
    for (int i = 0; i <= radius; ++i) {
        const double gi = g[size_t(i)], hi = h[size_t(i)];
        k.gauss.taps.push_back(float(gi / gSum));
        k.edge.taps.push_back(edgePositive > 0 ? float(-double(i) * gi / edgePositive) : 0.f);
        const double split = hi > 0 ? pointPositive : pointNegative;
        k.point.taps.push_back(split > 0 ? float(hi / split) : 0.f);
    }
    return k;
}

// Edge and point strengths of one image: the lengths of the (x, y) filter response vectors.
struct FlipFeatures {
    Plane edge, point;
};

FlipFeatures flipFeatures(const Image& img, const FlipFeatureKernels& k) {
    // The achromatic channel normalised to [0, 1], (Y' + 16) / 116 = Y / Yn: the luminance of the
    // clamped input (Yn = 1 for the Rec. 709 weights).
    Plane y(img.width, img.height);
    const size_t n = img.pixelCount();
    for (size_t p = 0; p < n; ++p)
        y.v[p] = float(0.2126 * flip_internal::ldrChannel(img.data[3 * p]) + 0.7152 * flip_internal::ldrChannel(img.data[3 * p + 1]) +
                       0.0722 * flip_internal::ldrChannel(img.data[3 * p + 2]));
    const Plane rowsGauss = flip_internal::filterRows(y, k.gauss);
    const Plane ex = flip_internal::filterColumns(flip_internal::filterRows(y, k.edge), k.gauss);
    const Plane ey = flip_internal::filterColumns(rowsGauss, k.edge);
    const Plane px = flip_internal::filterColumns(flip_internal::filterRows(y, k.point), k.gauss);
    const Plane py = flip_internal::filterColumns(rowsGauss, k.point);
    FlipFeatures f{Plane(img.width, img.height), Plane(img.width, img.height)};
    for (size_t p = 0; p < n; ++p) {
        f.edge.v[p] = std::hypot(ex.v[p], ey.v[p]);
        f.point.v[p] = std::hypot(px.v[p], py.v[p]);
    }
    return f;
}

}  // namespace

Image flipFeatureDifference(const Image& reference, const Image& test, const FlipSettings& settings) {
    flip_internal::checkFlipInputs(reference, test, settings, "flipFeatureDifference");
    Image out(reference.width, reference.height);
    if (out.empty()) return out;
    const FlipFeatureKernels k = flipFeatureKernels(settings.pixelsPerDegree);
    const FlipFeatures r = flipFeatures(reference, k), t = flipFeatures(test, k);
    const size_t n = out.pixelCount();
    for (size_t p = 0; p < n; ++p) {
        float e;
        if (flip_internal::nonFinitePixel(reference, p) || flip_internal::nonFinitePixel(test, p)) {
            e = std::numeric_limits<float>::quiet_NaN();
        } else {
            // A response is at most 1 per direction (weights of each sign sum to ±1 and the input
            // is in [0, 1]), so a strength is at most √2 and the scaled difference at most 1; the
            // clamp only absorbs rounding.
            const double d = std::max(std::fabs(double(r.edge.v[p]) - double(t.edge.v[p])),
                                      std::fabs(double(r.point.v[p]) - double(t.point.v[p])));
            e = float(std::pow(std::min(1.0, d / std::sqrt(2.0)), kFlipQf));
        }
        out.data[3 * p] = out.data[3 * p + 1] = out.data[3 * p + 2] = e;
    }
    return out;
}

}  // namespace rrf
