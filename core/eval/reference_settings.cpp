#include "core/eval/reference_settings.h"

#include <algorithm>
#include <cmath>

#include "core/scene/scene.h"

namespace rrf {

double NoiseTarget::wanted(double measuredError) const {
    // NaN compares false: without a measured error the target stands alone.
    return std::isfinite(measuredError) ? std::max(relativeRmse, errorFraction * measuredError) : relativeRmse;
}

nlohmann::json ReferenceSettings::toJson() const {
    return {{"noise", target.relativeRmse}, {"error_fraction", target.errorFraction}, {"spp_cap", target.sppCap},
            {"spp_per_pass", target.sppPerPass}, {"width", width}, {"height", height}};
}

ReferenceSettings ReferenceSettings::fromJson(const JsonReader& r) {
    r.checkKeys({"noise", "error_fraction", "spp_cap", "spp_per_pass", "width", "height"});
    ReferenceSettings s;
    s.target.relativeRmse = r.numberOr("noise", s.target.relativeRmse, 0.0, 10.0, true);
    s.target.errorFraction = r.numberOr("error_fraction", s.target.errorFraction, 0.0, 1.0);
    s.target.sppCap = int(r.integerOr("spp_cap", s.target.sppCap, 2, 1 << 24));
    s.target.sppPerPass = int(r.integerOr("spp_per_pass", s.target.sppPerPass, 1, 1 << 16));
    s.width = int(r.integerOr("width", s.width, 0, kMaxImageSide));
    s.height = int(r.integerOr("height", s.height, 0, kMaxImageSide));
    return s;
}

}  // namespace rrf
