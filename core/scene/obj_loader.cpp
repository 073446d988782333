#include "core/scene/obj_loader.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <tiny_obj_loader.h>

#include "core/util/error.h"
#include "core/util/memory_budget.h"

namespace rrf {

namespace {
/// Splits tinyobjloader's newline-separated message text.
void appendLines(const std::string& text, const std::string& prefix, std::vector<std::string>& out) {
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line))
        if (!line.empty()) out.push_back(prefix + line);
}
}  // namespace

ObjMesh loadObj(const std::string& objPath, const std::string& sceneFile, const std::string& where) {
    {
        // tinyobjloader's own message for a missing file is terse; check first to say which file.
        std::ifstream probe(objPath);
        if (!probe) throw InputError(sceneFile, where, "cannot open OBJ file '" + objPath + "'");
    }
    std::error_code ec;
    // A device or pipe (/dev/zero) would be read until memory runs out.
    if (!std::filesystem::is_regular_file(objPath, ec))
        throw InputError(sceneFile, where, "OBJ file '" + objPath + "' is not a regular file");
    // tinyobjloader keeps every vertex and index of the text, and the mesh is copied once more: about
    // as many bytes as the text has, twice (a "v x y z" line of ~30 bytes becomes 12-24 bytes).
    const uint64_t fileBytes = uint64_t(std::filesystem::file_size(objPath, ec));
    requireMemory(2 * fileBytes, "twice the OBJ file's " + formatBytes(fileBytes), sceneFile, where);
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    const size_t slash = objPath.find_last_of('/');
    config.mtl_search_path = slash == std::string::npos ? "./" : objPath.substr(0, slash + 1);

    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(objPath, config)) {
        std::string err = reader.Error();
        while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
        throw InputError(sceneFile, where, "cannot parse OBJ file '" + objPath + "': " + err);
    }

    ObjMesh mesh;
    appendLines(reader.Warning(), objPath + ": ", mesh.warnings);
    const std::vector<tinyobj::real_t>& v = reader.GetAttrib().vertices;
    const size_t vertexCount = v.size() / 3;
    mesh.positions.reserve(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i) {
        const Vec3 p{static_cast<float>(v[3 * i]), static_cast<float>(v[3 * i + 1]), static_cast<float>(v[3 * i + 2])};
        if (!p.isFinite())
            throw InputError(sceneFile, where,
                             "OBJ file '" + objPath + "': vertex " + std::to_string(i + 1) + " is not finite");
        mesh.positions.push_back(p);
    }
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        const auto& faceSizes = shape.mesh.num_face_vertices;
        const auto& idx = shape.mesh.indices;
        size_t offset = 0;
        for (size_t f = 0; f < faceSizes.size(); ++f) {
            const size_t n = faceSizes[f];
            // Triangulation is on, so anything but 3 is a face tinyobjloader could not split.
            if (n == 3) {
                for (size_t k = 0; k < 3; ++k) {
                    const int vi = idx[offset + k].vertex_index;
                    if (vi < 0 || size_t(vi) >= vertexCount)
                        throw InputError(sceneFile, where,
                                         "OBJ file '" + objPath + "': face " + std::to_string(f + 1) + " of '" +
                                             shape.name + "' refers to a missing vertex");
                    mesh.indices.push_back(uint32_t(vi));
                }
            } else {
                mesh.warnings.push_back(objPath + ": skipped a face with " + std::to_string(n) + " vertices");
            }
            offset += n;
        }
    }
    if (mesh.indices.empty())
        throw InputError(sceneFile, where, "OBJ file '" + objPath + "' contains no triangles or polygons");
    return mesh;
}

}  // namespace rrf
