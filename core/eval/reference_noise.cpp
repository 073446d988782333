#include "core/eval/reference_noise.h"

#include "core/eval/error_metrics.h"

namespace rrf {

ReferenceNoise::ReferenceNoise() {
    for (int t = 0; t < kTermCount; ++t) rmse[t] = relativeRmse[t] = ErrorStats::kUnknownNoise;
}

namespace {
// The floors are the error statistics of the reference against itself with its variance given: the
// difference is 0, so only the noise terms of error_metrics' formulas remain (one definition).
ErrorStats selfStats(const Image& image, const Image& variance, const std::vector<uint32_t>& mask) {
    return errorStatsWithNoise(image, image, variance, mask);
}
}  // namespace

double relativeNoiseFloor(const Image& image, const Image& variance, const std::vector<uint32_t>& mask) {
    if (variance.empty()) return ErrorStats::kUnknownNoise;
    const ErrorStats s = selfStats(image, variance, mask);
    return s.pixels ? s.relativeRmseNoiseFloor : ErrorStats::kUnknownNoise;
}

ReferenceNoise referenceNoise(const Reference& reference, const FootprintMask& mask) {
    ReferenceNoise n;
    for (Term t : kTerms) {
        const Image& v = reference.variance(t);
        if (v.empty() || reference.image(t).empty()) continue;
        const ErrorStats s = selfStats(reference.image(t), v, mask.kept);
        if (!s.pixels) continue;
        n.rmse[int(t)] = s.rmseNoiseFloor;
        n.relativeRmse[int(t)] = s.relativeRmseNoiseFloor;
    }
    return n;
}

}  // namespace rrf
