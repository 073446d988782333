#pragma once
/// Wavefront OBJ reading for scene files: positions and faces only (materials come from the scene
/// file), polygons triangulated, all groups merged into one mesh.

#include <cstdint>
#include <string>
#include <vector>

#include "core/util/vec3.h"

namespace rrf {

struct ObjMesh {
    std::vector<Vec3> positions;
    std::vector<uint32_t> indices;  ///< 3 per triangle
    std::vector<std::string> warnings;  ///< the OBJ parser's non-fatal remarks
};

/// Loads `objPath`. Errors (missing or unreadable file, bad face indices, non-finite coordinates,
/// no faces) throw InputError(sceneFile, where, ...) so that the message points at the scene entry
/// that named the OBJ file as well as the OBJ file itself.
ObjMesh loadObj(const std::string& objPath, const std::string& sceneFile, const std::string& where);

}  // namespace rrf
