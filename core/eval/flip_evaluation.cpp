#include "core/eval/flip_evaluation.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/eval/evaluation.h"
#include "core/util/rng.h"

namespace rrf {

namespace {
/// The noise draw's seed: fixed, so the noise floor of one reference is one number across runs.
constexpr uint64_t kFlipNoiseSeed = 0x464C4950u;  // "FLIP"
}  // namespace

float flipNoiseNormal(uint64_t seed, uint64_t pixel, int c) {
    Rng rng(seed, pixel, uint64_t(c));
    // Box-Muller; 1 - u is in (0, 1], so the logarithm is finite.
    const double u1 = 1.0 - rng.uniformDouble(), u2 = rng.uniformDouble();
    return float(std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * 3.14159265358979323846 * u2));
}

Image withDrawnNoise(const Image& image, const Image& variance, uint64_t seed) {
    if (image.width != variance.width || image.height != variance.height)
        throw std::invalid_argument("withDrawnNoise: the variance image's size differs from the image's");
    Image out = image;
    const size_t n = image.pixelCount();
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            const float v = variance.data[3 * i + c];
            if (std::isfinite(v) && v > 0.f) out.data[3 * i + c] += std::sqrt(v) * flipNoiseNormal(seed, i, c);
        }
    return out;
}

FlipEvaluation flipEvaluation(const Evaluation& e, const Reference& reference, const FlipSettings& settings) {
    FlipEvaluation f;
    const int g = int(Term::Global);
    if (!e.prediction.available[g]) return f;
    const auto t0 = std::chrono::steady_clock::now();
    const Image& ref = reference.images[g];
    const Image& pred = e.prediction.images[g];
    f.available = true;
    f.settings = settings;
    f.range = flipExposureRange(ref);
    f.hdrMap = hdrFlip(ref, pred, f.range, settings);
    f.ldrMap = ldrFlip(ref, pred, settings);
    f.hdr = flipStats(f.hdrMap, e.footprint.kept);
    f.ldr = flipStats(f.ldrMap, e.footprint.kept);
    for (const auto& px : e.footprint.keptByObject) f.hdrPerObject.push_back(flipStats(f.hdrMap, px));
    const Image& variance = reference.variances[g];
    if (!variance.empty()) {
        const Image noisy = withDrawnNoise(ref, variance, kFlipNoiseSeed);
        f.hdrNoiseFloor = flipStats(hdrFlip(ref, noisy, f.range, settings), e.footprint.kept).mean;
    }
    f.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return f;
}

}  // namespace rrf
