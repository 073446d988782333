#include "core/scene/effects_json.h"

namespace rrf {

nlohmann::json toJson(const Effects& e) {
    return {{"diffuse", e.diffuse},       {"glossy", e.glossy},
            {"rect_lights", e.rectLights}, {"triangle_lights", e.triangleLights}, {"point_lights", e.pointLights},
            {"reflective_emitters", e.reflectiveEmitters},
            {"indirect", e.indirect},     {"caustics", e.caustics},     {"max_albedo", e.maxAlbedo},
            {"max_phong_exponent", e.maxPhongExponent}, {"description", e.describe()}};
}

}  // namespace rrf
