#include "core/eval/error_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>


namespace rrf {

namespace {
void checkSizes(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height)
        throw std::invalid_argument("error metrics: prediction is " + std::to_string(a.width) + "x" +
                                    std::to_string(a.height) + " but the reference is " + std::to_string(b.width) +
                                    "x" + std::to_string(b.height));
}

/// d / (|ref| + 0.01): the relative error of one channel, shared by the maps and the statistics.
double relativeDifference(double d, double ref) { return d / (std::fabs(ref) + kRelativeEpsilon); }
/// 1 / (ref² + 0.01): tev's relative squared error's weight of d².
double relMseWeight(double ref) { return 1.0 / (ref * ref + kRelativeEpsilon); }
/// |d| / (|pred| + |ref| + 0.01): the symmetric absolute percentage error of one channel.
double smapeTerm(double pred, double ref) {
    return std::fabs(pred - ref) / (std::fabs(pred) + std::fabs(ref) + kRelativeEpsilon);
}

/// Sums over the pixels of a mask, in pixel order. `variance` (may be null) is the reference's per-pixel
/// variance of the mean; with it the sums of the noise floor and the corrected error are kept too.
struct Accumulator {
    const Image& prediction;
    const Image& reference;
    const Image* variance;
    double sq = 0, rel = 0, abs = 0, max = 0, ref = 0;
    double bias = 0, relSq = 0, smape = 0;  ///< Σ d / (|ref| + 0.01), Σ d² / (ref² + 0.01), Σ SMAPE terms
    double var = 0, relVar = 0, relSqVar = 0;  ///< Σ v, Σ v / (|ref| + 0.01)² and Σ v / (ref² + 0.01)
    uint64_t pixels = 0, bad = 0;

    void add(size_t i) {
        const float* a = &prediction.data[3 * i];
        const float* b = &reference.data[3 * i];
        const float* v = variance ? &variance->data[3 * i] : nullptr;
        bool finite = true;
        for (int c = 0; c < 3; ++c) finite = finite && std::isfinite(a[c]) && std::isfinite(b[c]);
        // A variance is a non-negative number; anything else (a damaged file) cannot be subtracted.
        if (v)
            for (int c = 0; c < 3; ++c) finite = finite && std::isfinite(v[c]) && v[c] >= 0.f;
        if (!finite) {
            ++bad;
            return;
        }
        for (int c = 0; c < 3; ++c) {
            const double d = double(a[c]) - double(b[c]);
            const double rd = relativeDifference(d, double(b[c]));
            sq += d * d;
            rel += rd * rd;
            bias += rd;
            relSq += d * d * relMseWeight(double(b[c]));
            smape += smapeTerm(double(a[c]), double(b[c]));
            abs += std::fabs(d);
            max = std::max(max, std::fabs(d));
            ref += double(b[c]);
            if (v) {
                // The relative weight 1 / (|ref| + 0.01)² is the one the relative RMSE gives d².
                const double w = relativeDifference(1.0, double(b[c]));
                var += double(v[c]);
                relVar += double(v[c]) * w * w;
                relSqVar += double(v[c]) * relMseWeight(double(b[c]));
            }
        }
        ++pixels;
    }
    ErrorStats stats() const {
        ErrorStats s;
        s.pixels = pixels;
        s.nonFinite = bad;
        s.noiseKnown = variance != nullptr;
        if (s.noiseKnown)
            s.rmseNoiseFloor = s.rmseCorrected = s.relativeRmseNoiseFloor = s.relativeRmseCorrected = s.relMseNoiseFloor =
                s.relMseCorrected = 0;
        if (pixels == 0) return s;
        const double n = 3.0 * double(pixels);
        s.rmse = std::sqrt(sq / n);
        s.relativeRmse = std::sqrt(rel / n);
        s.mae = abs / n;
        s.maxError = max;
        s.meanReference = ref / n;
        s.signedRelativeMean = bias / n;
        s.relMse = relSq / n;
        s.smape = smape / n;
        if (s.noiseKnown) {
            // mean(d² − v) = mean d² − mean v: the sums are subtracted once, then clamped at 0 (the
            // estimate of a squared error can fall below 0 where the prediction is within the noise).
            s.rmseNoiseFloor = std::sqrt(var / n);
            s.relativeRmseNoiseFloor = std::sqrt(relVar / n);
            s.rmseCorrected = std::sqrt(std::max(0.0, (sq - var) / n));
            s.relativeRmseCorrected = std::sqrt(std::max(0.0, (rel - relVar) / n));
            s.relMseNoiseFloor = relSqVar / n;
            s.relMseCorrected = std::max(0.0, (relSq - relSqVar) / n);
        }
        return s;
    }
};

/// Nullptr for "unknown" (an empty image); throws if a given variance does not match the reference.
const Image* knownVariance(const Image& variance, const Image& reference) {
    if (variance.empty()) return nullptr;
    if (variance.width != reference.width || variance.height != reference.height)
        throw std::invalid_argument("error metrics: the reference's variance is " + std::to_string(variance.width) + "x" +
                                    std::to_string(variance.height) + " but the reference is " +
                                    std::to_string(reference.width) + "x" + std::to_string(reference.height));
    return &variance;
}

ErrorStats maskedStats(const Image& prediction, const Image& reference, const Image* variance,
                       const std::vector<uint32_t>& mask) {
    checkSizes(prediction, reference);
    Accumulator acc{prediction, reference, variance};
    const size_t n = prediction.pixelCount();
    for (uint32_t i : mask) {
        if (i >= n) throw std::invalid_argument("error metrics: mask pixel " + std::to_string(i) + " outside the image");
        acc.add(i);
    }
    return acc.stats();
}

ErrorStats allPixelStats(const Image& prediction, const Image& reference, const Image* variance) {
    checkSizes(prediction, reference);
    Accumulator acc{prediction, reference, variance};
    for (size_t i = 0; i < prediction.pixelCount(); ++i) acc.add(i);
    return acc.stats();
}

}  // namespace

bool errorMapIsSigned(ErrorMapKind k) { return k == ErrorMapKind::Signed; }

const char* errorMapName(ErrorMapKind k) {
    switch (k) {
    case ErrorMapKind::Absolute: return "absolute";
    case ErrorMapKind::Relative: return "relative";
    case ErrorMapKind::Squared: return "squared";
    case ErrorMapKind::Signed: return "signed";
    case ErrorMapKind::RelativeSquared: return "relmse";
    case ErrorMapKind::Smape: return "smape";
    }
    return "?";
}

std::optional<ErrorMapKind> parseErrorMapKind(std::string_view name) {
    for (ErrorMapKind k : kErrorMapKinds)
        if (name == errorMapName(k)) return k;
    return std::nullopt;
}

const char* errorMapFormula(ErrorMapKind k) {
    switch (k) {
    case ErrorMapKind::Absolute: return "mean_c |d_c|";
    case ErrorMapKind::Relative: return "mean_c |d_c| / (|ref_c| + 0.01)";
    case ErrorMapKind::Squared: return "mean_c d_c^2";
    case ErrorMapKind::Signed: return "mean_c d_c / (|ref_c| + 0.01)";
    case ErrorMapKind::RelativeSquared: return "mean_c d_c^2 / (ref_c^2 + 0.01)";
    case ErrorMapKind::Smape: return "mean_c |d_c| / (|pred_c| + |ref_c| + 0.01)";
    }
    return "?";
}

ErrorStats errorStats(const Image& prediction, const Image& reference, const std::vector<uint32_t>& mask) {
    return maskedStats(prediction, reference, nullptr, mask);
}

ErrorStats errorStats(const Image& prediction, const Image& reference) { return allPixelStats(prediction, reference, nullptr); }

ErrorStats errorStatsWithNoise(const Image& prediction, const Image& reference, const Image& referenceVariance,
                               const std::vector<uint32_t>& mask) {
    return maskedStats(prediction, reference, knownVariance(referenceVariance, reference), mask);
}

ErrorStats errorStatsWithNoise(const Image& prediction, const Image& reference, const Image& referenceVariance) {
    return allPixelStats(prediction, reference, knownVariance(referenceVariance, reference));
}

std::string noiseFigureText(double value) {
    if (std::isnan(value)) return "unknown";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", value);
    return buf;
}

float pixelError(const Vec3& prediction, const Vec3& reference, ErrorMapKind kind) {
    double v = 0;
    for (int c = 0; c < 3; ++c) {
        const double d = double(prediction[c]) - double(reference[c]);
        switch (kind) {
        case ErrorMapKind::Absolute: v += std::fabs(d); break;
        case ErrorMapKind::Relative: v += std::fabs(relativeDifference(d, double(reference[c]))); break;
        case ErrorMapKind::Squared: v += d * d; break;
        case ErrorMapKind::Signed: v += relativeDifference(d, double(reference[c])); break;
        case ErrorMapKind::RelativeSquared: v += d * d * relMseWeight(double(reference[c])); break;
        case ErrorMapKind::Smape: v += smapeTerm(double(prediction[c]), double(reference[c])); break;
        }
    }
    // A NaN or Inf input propagates into v: the map keeps it visible (NaN) instead of a number.
    return std::isfinite(v) ? float(v / 3.0) : std::numeric_limits<float>::quiet_NaN();
}

Image errorMap(const Image& prediction, const Image& reference, ErrorMapKind kind) {
    checkSizes(prediction, reference);
    Image out(prediction.width, prediction.height);
    for (size_t i = 0; i < prediction.pixelCount(); ++i) {
        const float* a = &prediction.data[3 * i];
        const float* b = &reference.data[3 * i];
        const float f = pixelError(Vec3(a[0], a[1], a[2]), Vec3(b[0], b[1], b[2]), kind);
        out.data[3 * i] = out.data[3 * i + 1] = out.data[3 * i + 2] = f;
    }
    return out;
}

std::vector<std::vector<uint32_t>> objectMasks(const std::vector<int32_t>& objectIds, size_t objectCount) {
    std::vector<std::vector<uint32_t>> masks(objectCount);
    for (size_t i = 0; i < objectIds.size(); ++i) {
        const int32_t id = objectIds[i];
        if (id >= 0 && size_t(id) < objectCount) masks[size_t(id)].push_back(uint32_t(i));
    }
    return masks;
}

float percentile(const Image& scalar, double q) {
    std::vector<float> v;
    v.reserve(scalar.pixelCount());
    for (size_t i = 0; i < scalar.pixelCount(); ++i)
        if (std::isfinite(scalar.data[3 * i])) v.push_back(scalar.data[3 * i]);
    if (v.empty()) return 0.f;
    q = std::clamp(q, 0.0, 1.0);
    const size_t k = std::min(v.size() - 1, size_t(std::ceil(q * double(v.size()))) - (q > 0 ? 1 : 0));
    std::nth_element(v.begin(), v.begin() + long(k), v.end());
    return v[k];
}

float errorMapScale(const Image& map, ErrorMapKind k) {
    if (!errorMapIsSigned(k)) return percentile(map, 0.99);
    Image magnitude = map;
    for (float& v : magnitude.data) v = std::fabs(v);
    return percentile(magnitude, 0.99);
}

Image errorMapColour(const Image& map, ErrorMapKind k, float scale) {
    const float s = std::isfinite(scale) ? std::max(scale, 1e-12f) : 1e-12f;
    return errorMapIsSigned(k) ? signedFalseColor(map, s) : falseColor(map, 0.f, s);
}

Image finiteMap(const Image& map, uint64_t& replaced) {
    Image out = map;
    replaced = 0;
    for (size_t i = 0; i < out.pixelCount(); ++i) {
        float* p = &out.data[3 * i];
        if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])) continue;
        p[0] = p[1] = p[2] = 0.f;
        ++replaced;
    }
    return out;
}

}  // namespace rrf
