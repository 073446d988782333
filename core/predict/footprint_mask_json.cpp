#include "core/predict/footprint_mask_json.h"

namespace rrf {

nlohmann::json toJson(const FootprintCounts& c) {
    return {{"next_to_light", c.nextToLight}, {"object_edge", c.objectEdge},         {"normal_edge", c.normalEdge},
            {"depth_step", c.depthStep},      {"total", c.total()},                   {"emitter_pixels", c.emitterPixels},
            {"normal_degrees", kFootprintNormalDegrees}, {"depth_fraction", kFootprintDepthFraction}};
}

}  // namespace rrf
