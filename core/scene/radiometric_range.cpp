#include "core/scene/radiometric_range.h"

#include <cmath>

#include "core/util/text_format.h"

namespace rrf {

namespace {
const char* const kChannelName[3] = {"red", "green", "blue"};
}  // namespace

std::string emissionProblem(const Vec3& c, const std::string& what) {
    for (int i = 0; i < 3; ++i) {
        const double v = c[i];
        if (std::isfinite(v) && v >= 0 && v <= double(kMaxRadiance)) continue;
        return what + " must lie in [0, " + formatNumber(kMaxRadiance) + "] (above it the tracer's products and their " +
               "squares leave float range), but its " + kChannelName[i] + " component is " + formatNumber(v);
    }
    return "";
}

std::string exponentProblem(double n, const std::string& what) {
    if (std::isfinite(n) && n >= 0 && n <= double(kMaxPhongExponent)) return "";
    return what + " (Phong exponent) must lie in [0, " + formatNumber(kMaxPhongExponent) + "], got " + formatNumber(n);
}

std::string lightSizeProblem(const Vec3& e1, const Vec3& e2) {
    const double cx = double(e1.y) * e2.z - double(e1.z) * e2.y, cy = double(e1.z) * e2.x - double(e1.x) * e2.z,
                 cz = double(e1.x) * e2.y - double(e1.y) * e2.x;
    const double cross = std::sqrt(cx * cx + cy * cy + cz * cz);
    if (cross >= double(kMinLightCross)) return "";
    return "the light is too small: |edge1 x edge2| = " + formatNumber(cross) + " is below " + formatNumber(kMinLightCross) +
           ", where its normal can no longer be computed in float";
}

}  // namespace rrf
