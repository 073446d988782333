#pragma once
/// What a scene holds, by name: its objects with their materials, and its lights. One description
/// for render.json ("scene_contents"), `rrf inspect scene.json` and anyone else who lists a scene, so
/// that an OBJ scene's groups, MTL materials and Ke emitters can be checked without a renderer.

#include <string>

#include <nlohmann/json.hpp>

#include "core/scene/scene.h"

namespace rrf {

/// {"objects": [{"name", "id", "kind", "primitives", "smooth_normals", "material": {"name",
/// "type", "kd", "ks", "exponent"}}], "lights": [{"name", "type", "radiance" | "intensity",
/// "area", "center", "one_sided", "movable"}], "light_region": {"min", "max"} | null}.
nlohmann::json sceneSummaryJson(const Scene& scene);

/// The same as text, one line per object and light, for a terminal.
std::string formatSceneSummary(const Scene& scene);

/// "quads", "triangles" or "sphere".
const char* objectKindName(Object::Kind kind);

/// "rect", "triangle" or "point".
const char* lightTypeName(Light::Type type);

}  // namespace rrf
