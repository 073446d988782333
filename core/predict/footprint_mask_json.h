#pragma once
/// The footprint mask's counts (predict/footprint_mask.h) as an evaluation's "footprint_mask" object.

#include <nlohmann/json.hpp>

#include "core/predict/footprint_mask.h"

namespace rrf {

/// {"next_to_light", "object_edge", "normal_edge", "depth_step", "total", "emitter_pixels",
///  "normal_degrees", "depth_fraction"}: the counts and the thresholds that produced them.
nlohmann::json toJson(const FootprintCounts& c);

}  // namespace rrf
