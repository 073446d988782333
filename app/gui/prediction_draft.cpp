#include "app/gui/prediction_draft.h"

#include <algorithm>

namespace rrf {

Camera draftCamera(const Camera& full, int divisor) {
    const int d = std::clamp(divisor, 1, kMaxDraftDivisor);
    Camera c = full;
    c.width = std::max(1, (full.width + d - 1) / d);
    c.height = std::max(1, (full.height + d - 1) / d);
    return c;
}

int nextDraftDivisor(int divisor, double seconds) {
    int d = std::clamp(divisor, 1, kMaxDraftDivisor);
    if (seconds > kDraftBudgetSeconds) ++d;
    else if (seconds < kDraftBudgetSeconds / 3) --d;
    return std::clamp(d, 1, kMaxDraftDivisor);
}

PredictionSettings draftPrediction(const PredictionSettings& full) {
    PredictionSettings p = full;
    p.directSamples = std::max(1, full.directSamples / kDraftSampleDivisor);
    return p;
}

Image replicatePixels(const Image& small, int width, int height) {
    Image out(width, height);
    if (small.empty()) return out;
    for (int y = 0; y < height; ++y) {
        // Centre of output row y, (y + 0.5) / height, falls into small row floor(that · small.height).
        const int sy = std::min(small.height - 1, int((2 * int64_t(y) + 1) * small.height / (2 * int64_t(height))));
        for (int x = 0; x < width; ++x) {
            const int sx = std::min(small.width - 1, int((2 * int64_t(x) + 1) * small.width / (2 * int64_t(width))));
            out.set(x, y, small.at(sx, sy));
        }
    }
    return out;
}

}  // namespace rrf
