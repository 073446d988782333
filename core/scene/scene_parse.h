#pragma once
/// Scene parsing for documents that sit inside a larger file. A project file may embed its scene
/// under "/scene"; parsing through a JsonReader keeps the JSON pointers in error messages
/// relative to the file the user edits (e.g. `project.json: /scene/shapes/2/material`).

#include <string>

#include "core/util/json_reader.h"
#include "core/scene/scene.h"

namespace rrf {

/// Builds a scene from the scene object at `root`. Relative OBJ paths are resolved against
/// `baseDir` (empty = the working directory). Throws InputError on any invalid input.
Scene parseSceneAt(const JsonReader& root, const std::string& baseDir);

/// Directory part of a file path ("" for a bare file name), used as the base of relative paths.
std::string directoryOf(const std::string& path);

/// `ref` resolved against `baseDir` unless it is absolute.
std::string resolvePath(const std::string& baseDir, const std::string& ref);

}  // namespace rrf
