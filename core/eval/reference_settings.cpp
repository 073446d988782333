#include "core/eval/reference_settings.h"

#include <algorithm>
#include <cmath>

namespace rrf {

double NoiseTarget::wanted(double measuredError) const {
    // NaN compares false: without a measured error the target stands alone.
    return std::isfinite(measuredError) ? std::max(relativeRmse, errorFraction * measuredError) : relativeRmse;
}

}  // namespace rrf
