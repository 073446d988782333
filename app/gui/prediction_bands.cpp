// Band heights of full-quality GLSL frames (prediction_bands.h).
#include "app/gui/prediction_bands.h"

#include <algorithm>
#include <cmath>

namespace rrf {

int firstBandRows(int height, double secondsPerRow) {
    if (height <= 0) return 1;
    if (!(secondsPerRow > 0.0) || !std::isfinite(secondsPerRow)) return std::max(1, height / kFirstBandDivisor);
    // 80 % of the budget: a band costs about its rows' share, with some noise on a shared machine.
    const double rows = 0.8 * kBandBudgetSeconds / secondsPerRow;
    return int(std::clamp(rows, 1.0, double(height)));
}

int nextBandRows(int rows, double seconds, int height) {
    if (height <= 0) return 1;
    rows = std::clamp(rows, 1, height);
    if (!(seconds > 0.0) || !std::isfinite(seconds)) return std::min(height, 2 * rows);
    // Towards 80 % of the budget, at most doubling per band: one band that happened to be fast (a
    // row of background) must not make the next one take the whole frame.
    const double scaled = double(rows) * 0.8 * kBandBudgetSeconds / seconds;
    return int(std::clamp(scaled, 1.0, std::min(double(height), 2.0 * rows)));
}

}  // namespace rrf
