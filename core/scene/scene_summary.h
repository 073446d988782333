#pragma once
/// What a scene holds, by name: its objects with their materials, and its lights. One description
/// for render.json ("scene_contents"), `rrf inspect scene.json` and anyone else who lists a scene, so
/// that an OBJ scene's groups, MTL materials and Ke emitters can be checked without a renderer. The
/// JSON form is scene/scene_summary_json.h's.

#include <string>

#include "core/scene/scene.h"

namespace rrf {

/// The same as text, one line per object and light, for a terminal.
std::string formatSceneSummary(const Scene& scene);

/// "quads", "triangles" or "sphere".
const char* objectKindName(Object::Kind kind);

/// "rect", "triangle" or "point".
const char* lightTypeName(Light::Type type);

}  // namespace rrf
