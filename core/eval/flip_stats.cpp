/// Pooled FLIP values and the magma error-map colours (RTG II 2021, "pooling" and the FLIP tool).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/eval/flip.h"

namespace rrf {

namespace {

// The weighted percentile of `sorted` (ascending, finite, ≥ 0) at p, as documented at FlipStats.
// The cumulative sums run in sorted order, and the total is their last value, so the search always
// ends inside the array.
double flipWeightedPercentile(const std::vector<float>& sorted, const std::vector<double>& cumulative, double p) {
    const double target = p * cumulative.back();
    const size_t k = size_t(std::lower_bound(cumulative.begin(), cumulative.end(), target) - cumulative.begin());
    const size_t next = std::min(k + 1, sorted.size() - 1);
    return 0.5 * (double(sorted[k]) + double(sorted[next]));
}

template <typename ForEachPixel>
FlipStats flipPool(const Image& flipMap, ForEachPixel forEach) {
    FlipStats s;
    std::vector<float> values;
    double sum = 0.0;
    forEach([&](size_t p) {
        const float v = flipMap.data[3 * p];
        if (!std::isfinite(v)) {
            ++s.nonFinite;
            return;
        }
        values.push_back(v);
        sum += v;  // pixel order, for the mean
    });
    s.pixels = values.size();
    if (values.empty()) return s;
    s.mean = sum / double(values.size());
    std::sort(values.begin(), values.end());
    std::vector<double> cumulative(values.size());
    double c = 0.0;
    for (size_t i = 0; i < values.size(); ++i) cumulative[i] = c += values[i];
    s.weightedMedian = flipWeightedPercentile(values, cumulative, 0.50);
    s.weightedFirstQuartile = flipWeightedPercentile(values, cumulative, 0.25);
    s.weightedThirdQuartile = flipWeightedPercentile(values, cumulative, 0.75);
    s.min = values.front();
    s.max = values.back();
    return s;
}

// matplotlib's magma (van der Walt & Smith, CC0), every 15th of its 256 sRGB entries, as
// kViridis in core/util/image.cpp: linear interpolation between them stays close to the full table.
constexpr int kFlipMagmaKnots = 18;
constexpr float kFlipMagma[kFlipMagmaKnots][3] = {
    {0.001462f, 0.000466f, 0.013866f}, {0.035520f, 0.028397f, 0.125209f},
    {0.102815f, 0.063010f, 0.257854f}, {0.191460f, 0.064818f, 0.396152f},
    {0.291366f, 0.064553f, 0.475462f}, {0.384299f, 0.097855f, 0.501002f},
    {0.475780f, 0.134577f, 0.507921f}, {0.569172f, 0.167454f, 0.504105f},
    {0.664915f, 0.198075f, 0.488836f}, {0.761077f, 0.231214f, 0.460162f},
    {0.852126f, 0.276106f, 0.418573f}, {0.925937f, 0.346844f, 0.374959f},
    {0.969680f, 0.446936f, 0.360311f}, {0.989363f, 0.557873f, 0.391671f},
    {0.996580f, 0.668256f, 0.456192f}, {0.996727f, 0.776795f, 0.541039f},
    {0.992440f, 0.884330f, 0.640099f}, {0.987053f, 0.991438f, 0.749504f},
};

}  // namespace

FlipStats flipStats(const Image& flipMap) {
    return flipPool(flipMap, [&](auto&& visit) {
        for (size_t p = 0; p < flipMap.pixelCount(); ++p) visit(p);
    });
}

FlipStats flipStats(const Image& flipMap, const std::vector<uint32_t>& pixels) {
    const size_t n = flipMap.pixelCount();
    for (uint32_t p : pixels)
        if (size_t(p) >= n)
            throw std::out_of_range("flipStats: pixel index " + std::to_string(p) + " outside a " +
                                    std::to_string(flipMap.width) + "x" + std::to_string(flipMap.height) + " map");
    return flipPool(flipMap, [&](auto&& visit) {
        for (uint32_t p : pixels) visit(size_t(p));
    });
}

Vec3 magma(float t) {
    if (!(t > 0.f)) t = 0.f;  // also catches NaN
    if (t > 1.f) t = 1.f;
    const float s = t * float(kFlipMagmaKnots - 1);
    const int k = std::min(int(s), kFlipMagmaKnots - 2);
    const float f = s - float(k);
    Vec3 c;
    // Interpolate in sRGB, where the table was designed to be perceptually uniform.
    for (int ch = 0; ch < 3; ++ch) c[ch] = srgbToLinear(kFlipMagma[k][ch] * (1.f - f) + kFlipMagma[k + 1][ch] * f);
    return c;
}

Image flipColour(const Image& flipMap) {
    Image out(flipMap.width, flipMap.height);
    for (int y = 0; y < flipMap.height; ++y)
        for (int x = 0; x < flipMap.width; ++x) {
            const float v = flipMap.at(x, y).x;
            out.set(x, y, std::isfinite(v) ? magma(v) : Vec3(1.f, 0.f, 1.f));
        }
    return out;
}

}  // namespace rrf
