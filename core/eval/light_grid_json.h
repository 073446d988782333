#pragma once
/// The light-grid figures (core/eval/light_grid.h) in JSON, as `rrf evaluate --light-grid` writes them.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/eval/light_grid.h"

namespace rrf {

/// {"grid", "region", "axes", "scale", "lights": [{"index", "position", "global": {...},
/// "objects": {name: figure}}], "marks": {"source", "count", "why"}}; unknown figures are null.
nlohmann::json lightGridJson(const Scene& scene, const LightGridMap& map);


}  // namespace rrf
