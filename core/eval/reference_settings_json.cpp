// The project's "reference" section in JSON (see reference_settings_json.h).
#include "core/eval/reference_settings_json.h"

#include "core/scene/scene.h"

namespace rrf {

nlohmann::json toJson(const ReferenceSettings& s) {
    return {{"noise", s.target.relativeRmse}, {"error_fraction", s.target.errorFraction}, {"spp_cap", s.target.sppCap},
            {"spp_per_pass", s.target.sppPerPass}, {"width", s.width}, {"height", s.height}};
}

ReferenceSettings referenceSettingsFromJson(const JsonReader& r) {
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
