#pragma once
/// Wavefront OBJ + MTL reading for scene files (tinyobjloader). The file is read into parts — one
/// per group (`o`/`g`) and material, or one per material — whose faces stay polygons as written, so
/// that the scene builder (scene_json.cpp) can turn emitting quads into rect lights and everything
/// else into triangles. tinyobjloader reads bad numbers as 0 and reports no line numbers for bad
/// face indices or unknown materials, so a line scan of the OBJ and MTL text
/// (core/scene/obj_text_scan.h) checks them first and errors name the line.

#include <cstdint>
#include <string>
#include <vector>

#include "core/util/vec3.h"

namespace rrf {

/// How an OBJ file's faces become objects: one per group (`o`/`g`, split further where a group uses
/// several materials), or one per material (`usemtl`) whatever the groups.
enum class ObjSplit { Groups, Materials };

/// A material of the OBJ's MTL library, as written (not yet clamped to energy conservation).
struct ObjMaterial {
    std::string name;
    Vec3 kd{0.f}, ks{0.f}, ke{0.f};
    float ns = 0.f;  ///< Phong exponent
};

/// Faces of one group and material. Polygons as written: faceSizes[f] indices per face, into this
/// part's own positions (vertices are renumbered per part).
struct ObjPart {
    std::string name;
    int material = -1;  ///< index into ObjFile::materials; -1 = faces before any `usemtl`
    std::vector<Vec3> positions;
    /// Unit vertex normals parallel to positions when every corner of the part names a `vn`; else empty.
    std::vector<Vec3> normals;
    std::vector<uint32_t> faceSizes;
    std::vector<uint32_t> indices;
};

struct ObjFile {
    std::vector<ObjMaterial> materials;
    std::vector<ObjPart> parts;
    /// The OBJ parser's non-fatal remarks, and the count of faces with fewer than 3 vertices
    /// (skipped) with the first one's line.
    std::vector<std::string> warnings;
};

/// Loads `objPath` with its MTL libraries. Errors (missing or unreadable file, a `v`/`vn` number
/// that is not a finite float or missing, a face index out of range, no faces; with
/// `requireMaterials` also a missing MTL library, a bad Kd/Ks/Ke/Ns (core/scene/obj_text_scan.h) or a
/// `usemtl` of a material no library defines, unless `knownMaterials` has it) throw
/// InputError(sceneFile, where, ...) naming the OBJ file and, where there is one, its line, so the
/// message points at the scene entry that named the OBJ file as well as the OBJ text.
ObjFile loadObjFile(const std::string& objPath, const std::string& sceneFile, const std::string& where,
                    ObjSplit split, bool requireMaterials, const std::vector<std::string>& knownMaterials = {});

/// Splits a planar convex polygon (indices[first .. first+count)) into a fan of triangles, appended
/// to `out`: (v0, v1, v2), (v0, v2, v3), …
void fanTriangulate(const std::vector<uint32_t>& indices, size_t first, size_t count, std::vector<uint32_t>& out);

}  // namespace rrf
