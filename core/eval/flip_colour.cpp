/// LDR-FLIP's colour pipeline (HPG 2020, "colour pipeline"): opponent space, contrast-sensitivity
/// filtering, Hunt-adjusted CIELAB, HyAB distance and its compression to [0, 1].
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/eval/flip.h"
#include "core/eval/flip_internal.h"

namespace rrf {

namespace {

using flip_internal::Kernel1D;
using flip_internal::Plane;

struct FlipMat3 {
    double m[3][3];
};

constexpr FlipMat3 flipInverse(const FlipMat3& a) {
    const auto& m = a.m;
    const double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    const double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    const double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    const double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
    FlipMat3 r{};
    r.m[0][0] = c00 / det;
    r.m[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
    r.m[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
    r.m[1][0] = c01 / det;
    r.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
    r.m[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
    r.m[2][0] = c02 / det;
    r.m[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
    r.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
    return r;
}

// Linear sRGB (Rec. 709 primaries, D65) to CIE XYZ, IEC 61966-2-1. The Y row is the luminance
// weighting of rrf::luminance().
constexpr FlipMat3 kFlipRgbToXyz = {{{0.4124, 0.3576, 0.1805}, {0.2126, 0.7152, 0.0722}, {0.0193, 0.1192, 0.9505}}};
constexpr FlipMat3 kFlipXyzToRgb = flipInverse(kFlipRgbToXyz);
// The reference white is the XYZ of RGB (1, 1, 1), so white has a* = b* = 0 exactly.
constexpr double kFlipWhite[3] = {kFlipRgbToXyz.m[0][0] + kFlipRgbToXyz.m[0][1] + kFlipRgbToXyz.m[0][2],
                                  kFlipRgbToXyz.m[1][0] + kFlipRgbToXyz.m[1][1] + kFlipRgbToXyz.m[1][2],
                                  kFlipRgbToXyz.m[2][0] + kFlipRgbToXyz.m[2][1] + kFlipRgbToXyz.m[2][2]};

constexpr double kFlipPi = 3.14159265358979323846;
constexpr double kFlipQc = 0.7;   // exponent on the HyAB distance
constexpr double kFlipPc = 0.4;   // fraction of cmax below which errors are spread over [0, pt]
constexpr double kFlipPt = 0.95;  // share of [0, 1] given to errors below pc · cmax

struct FlipTriple {
    double v[3];
};

FlipTriple flipMul(const FlipMat3& a, const double x[3]) {
    FlipTriple r{};
    for (int i = 0; i < 3; ++i) r.v[i] = a.m[i][0] * x[0] + a.m[i][1] * x[1] + a.m[i][2] * x[2];
    return r;
}

double flipLabF(double t) {
    constexpr double d = 6.0 / 29.0;
    return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}

// Linear RGB in [0, 1] to Hunt-adjusted L*a*b* (HPG 2020, "perceptually uniform colour space"):
// CIELAB, then a* and b* scaled by 0.01 L*, as the chroma of dark colours is less visible.
FlipTriple flipHuntLab(const double rgb[3]) {
    const FlipTriple xyz = flipMul(kFlipRgbToXyz, rgb);
    const double fx = flipLabF(xyz.v[0] / kFlipWhite[0]);
    const double fy = flipLabF(xyz.v[1] / kFlipWhite[1]);
    const double fz = flipLabF(xyz.v[2] / kFlipWhite[2]);
    const double L = 116.0 * fy - 16.0;
    return {{L, 0.01 * L * 500.0 * (fx - fy), 0.01 * L * 200.0 * (fy - fz)}};
}

// HyAB (Abasi et al. 2020): city-block in lightness plus Euclidean in the chroma plane.
double flipHyab(const FlipTriple& a, const FlipTriple& b) {
    const double da = a.v[1] - b.v[1], db = a.v[2] - b.v[2];
    return std::fabs(a.v[0] - b.v[0]) + std::sqrt(da * da + db * db);
}

// cmax: the exponentiated HyAB distance of green and blue, the pair the paper finds farthest apart
// in Hunt-adjusted L*a*b* among the colours of the RGB cube; it sets the scale of ΔEc.
double flipColourMax() {
    static const double cmax = [] {
        const double green[3] = {0, 1, 0}, blue[3] = {0, 0, 1};
        return std::pow(flipHyab(flipHuntLab(green), flipHuntLab(blue)), kFlipQc);
    }();
    return cmax;
}

// The contrast sensitivity filter of one opponent channel (HPG 2020, "spatial filtering"): a sum
// of one or two Gaussians, S(x) = Σ a_k √(π / b_k) exp(−π² x² / b_k) with x in degrees, sampled at
// 1 / ppd, normalised to unit sum. Each Gaussian is separable, so the 2D filter is the weighted sum
// of separable passes; the weight of Gaussian k is its share of the 2D sum.
struct FlipCsfPart {
    double weight;
    Kernel1D kernel;
};

std::vector<FlipCsfPart> flipCsf(int channel, double ppd) {
    // (a1, b1, a2, b2) per channel: achromatic, red–green, blue–yellow. The first two are single
    // Gaussians (a2 = 0).
    static const double kParams[3][4] = {{1.0, 0.0047, 0.0, 0.0}, {1.0, 0.0053, 0.0, 0.0}, {34.1, 0.04, 13.5, 0.025}};
    // One radius for all channels, three standard deviations of the widest Gaussian (b = 0.04).
    const double widest = 0.04;
    const int radius = int(std::ceil(3.0 * std::sqrt(widest / (2.0 * kFlipPi * kFlipPi)) * ppd));
    std::vector<FlipCsfPart> parts;
    double total = 0.0;
    for (int k = 0; k < 2; ++k) {
        const double a = kParams[channel][2 * k], b = kParams[channel][2 * k + 1];
        if (a == 0.0) continue;
        std::vector<double> g(size_t(radius) + 1);
        double sum = 0.0;
        for (int i = 0; i <= radius; ++i) {
            const double x = double(i) / ppd;
            g[size_t(i)] = std::exp(-kFlipPi * kFlipPi * x * x / b);
            sum += (i == 0 ? 1.0 : 2.0) * g[size_t(i)];
        }
        FlipCsfPart part{a * std::sqrt(kFlipPi / b) * sum * sum, {}};
        for (double gi : g) part.kernel.taps.push_back(float(gi / sum));
        total += part.weight;
        parts.push_back(std::move(part));
    }
    for (auto& p : parts) p.weight /= total;
    return parts;
}

Plane flipCsfFilter(const Plane& in, const std::vector<FlipCsfPart>& parts) {
    if (parts.size() == 1)
        return flip_internal::filterColumns(flip_internal::filterRows(in, parts[0].kernel), parts[0].kernel);
    Plane out(in.width, in.height);
    for (const auto& p : parts) {
        const Plane f = flip_internal::filterColumns(flip_internal::filterRows(in, p.kernel), p.kernel);
        const float w = float(p.weight);
        for (size_t i = 0; i < out.v.size(); ++i) out.v[i] += w * f.v[i];
    }
    return out;
}

// YCxCz (Edwards & Zhang's linearised CIELAB): Y' = 116 Y/Yn − 16, Cx = 500 (X/Xn − Y/Yn),
// Cz = 200 (Y/Yn − Z/Zn); linear in XYZ, so filtering in it is filtering the radiance.
void flipToYcxcz(const Image& img, Plane out[3]) {
    for (int c = 0; c < 3; ++c) out[c] = Plane(img.width, img.height);
    const size_t n = img.pixelCount();
    for (size_t p = 0; p < n; ++p) {
        const double rgb[3] = {flip_internal::ldrChannel(img.data[3 * p]), flip_internal::ldrChannel(img.data[3 * p + 1]),
                               flip_internal::ldrChannel(img.data[3 * p + 2])};
        const FlipTriple xyz = flipMul(kFlipRgbToXyz, rgb);
        const double x = xyz.v[0] / kFlipWhite[0], y = xyz.v[1] / kFlipWhite[1], z = xyz.v[2] / kFlipWhite[2];
        out[0].v[p] = float(116.0 * y - 16.0);
        out[1].v[p] = float(500.0 * (x - y));
        out[2].v[p] = float(200.0 * (y - z));
    }
}

// A filtered YCxCz pixel back to linear RGB, clamped to [0, 1] (the filter can leave the gamut),
// then to Hunt-adjusted L*a*b*.
FlipTriple flipFilteredToHuntLab(float yp, float cx, float cz) {
    const double y = (double(yp) + 16.0) / 116.0;
    const double xyz[3] = {(y + double(cx) / 500.0) * kFlipWhite[0], y * kFlipWhite[1], (y - double(cz) / 200.0) * kFlipWhite[2]};
    FlipTriple rgb = flipMul(kFlipXyzToRgb, xyz);
    for (double& c : rgb.v) c = std::clamp(c, 0.0, 1.0);
    return flipHuntLab(rgb.v);
}

}  // namespace

Image flipColourDifference(const Image& reference, const Image& test, const FlipSettings& settings) {
    flip_internal::checkFlipInputs(reference, test, settings, "flipColourDifference");
    Image out(reference.width, reference.height);
    if (out.empty()) return out;
    const std::vector<FlipCsfPart> csf[3] = {flipCsf(0, settings.pixelsPerDegree), flipCsf(1, settings.pixelsPerDegree),
                                             flipCsf(2, settings.pixelsPerDegree)};
    Plane ref[3], tst[3];
    flipToYcxcz(reference, ref);
    flipToYcxcz(test, tst);
    for (int c = 0; c < 3; ++c) {
        ref[c] = flipCsfFilter(ref[c], csf[c]);
        tst[c] = flipCsfFilter(tst[c], csf[c]);
    }
    const double cmax = flipColourMax(), pccmax = kFlipPc * cmax;
    const size_t n = out.pixelCount();
    for (size_t p = 0; p < n; ++p) {
        float e;
        if (flip_internal::nonFinitePixel(reference, p) || flip_internal::nonFinitePixel(test, p)) {
            e = std::numeric_limits<float>::quiet_NaN();
        } else {
            const double d = std::pow(flipHyab(flipFilteredToHuntLab(ref[0].v[p], ref[1].v[p], ref[2].v[p]),
                                               flipFilteredToHuntLab(tst[0].v[p], tst[1].v[p], tst[2].v[p])),
                                      kFlipQc);
            // Compression (HPG 2020, "colour metric"): errors below pc · cmax, the range where
            // differences are told apart best, take [0, pt]; the rest share (pt, 1].
            const double c = d < pccmax ? (kFlipPt / pccmax) * d : kFlipPt + (d - pccmax) / (cmax - pccmax) * (1.0 - kFlipPt);
            e = float(std::clamp(c, 0.0, 1.0));
        }
        out.data[3 * p] = out.data[3 * p + 1] = out.data[3 * p + 2] = e;
    }
    return out;
}

}  // namespace rrf
