#pragma once
/// Scene file (JSON) reader. See docs/file-formats.md for the format.

#include <string>

#include <nlohmann/json.hpp>

#include "core/scene/scene.h"

namespace rrf {

/// Reads and validates a scene file. Throws InputError naming the file and the JSON path
/// (e.g. "scene.json: /shapes/2/material: unknown material 'wite'").
Scene loadScene(const std::string& path);

/// Builds a scene from an already parsed document. `file` is used in error messages; relative
/// paths (OBJ files) are resolved against `baseDir`.
Scene parseScene(const nlohmann::json& doc, const std::string& file, const std::string& baseDir);

}  // namespace rrf
