#pragma once
/// The scene summary (scene/scene_summary.h) as JSON: render.json's "scene_contents" and
/// `rrf inspect scene.json --json`.

#include <nlohmann/json.hpp>

#include "core/scene/scene.h"
#include "core/scene/scene_summary.h"

namespace rrf {

/// {"objects": [{"name", "id", "kind", "primitives", "smooth_normals", "material": {"name",
/// "type", "kd", "ks", "exponent"}}], "lights": [{"name", "type", "radiance" | "intensity",
/// "area", "center", "one_sided", "movable"}], "light_region": {"min", "max"} | null}.
nlohmann::json sceneSummaryJson(const Scene& scene);

}  // namespace rrf
