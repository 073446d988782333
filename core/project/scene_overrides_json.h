#pragma once
/// The project's "scene_overrides" section (core/project/scene_overrides.h) in JSON.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/project/scene_overrides.h"
#include "core/util/json_reader.h"

namespace rrf {

/// {"light_position": [x, y, z], "materials": {name: {"kd", "ks", "exponent"}}}; empty parts are left out.
nlohmann::json toJson(const SceneOverrides& overrides);
/// Reads the section. The overrides are the workbench's own record of the user's edits, so a
/// damaged entry must not lock the user out of the project: an entry of the wrong shape is
/// skipped and described in `warnings` (file, JSON pointer, what was expected); the rest is kept.
SceneOverrides sceneOverridesFromJson(const JsonReader& section, std::vector<std::string>& warnings);

}  // namespace rrf
