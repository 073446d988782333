#include "core/scene/obj_loader.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <tiny_obj_loader.h>

#include "core/scene/obj_text_scan.h"
#include "core/scene/radiometric_range.h"
#include "core/util/error.h"
#include "core/util/memory_budget.h"

namespace rrf {

namespace {
/// Splits tinyobjloader's newline-separated message text. Its "Degenerated face found\n." per
/// face of fewer than 3 corners (so ".Degenerated face found" from the second on) is left out: the
/// text scan counts those faces and names the first one's line.
void appendLines(const std::string& text, const std::string& prefix, std::vector<std::string>& out) {
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        const std::string bare = !line.empty() && line[0] == '.' ? line.substr(1) : line;
        if (!bare.empty() && bare != "Degenerated face found") out.push_back(prefix + line);
    }
}

std::string fileLine(const std::string& path, size_t line) { return "OBJ file '" + path + "' line " + std::to_string(line); }

Vec3 vec3At(const std::vector<tinyobj::real_t>& v, size_t i) {
    return {float(v[3 * i]), float(v[3 * i + 1]), float(v[3 * i + 2])};
}
}  // namespace

void fanTriangulate(const std::vector<uint32_t>& indices, size_t first, size_t count, std::vector<uint32_t>& out) {
    for (size_t k = 1; k + 1 < count; ++k)
        out.insert(out.end(), {indices[first], indices[first + k], indices[first + k + 1]});
}

ObjFile loadObjFile(const std::string& objPath, const std::string& sceneFile, const std::string& where,
                    ObjSplit split, bool requireMaterials, const std::vector<std::string>& knownMaterials) {
    {
        // tinyobjloader's own message for a missing file is terse; check first to say which file.
        std::ifstream probe(objPath);
        if (!probe) throw InputError(sceneFile, where, "cannot open OBJ file '" + objPath + "'");
    }
    std::error_code ec;
    // A device or pipe (/dev/zero) would be read until memory runs out.
    if (!std::filesystem::is_regular_file(objPath, ec))
        throw InputError(sceneFile, where, "OBJ file '" + objPath + "' is not a regular file");
    // tinyobjloader keeps every vertex and index of the text, and the parts copy them once more: about
    // as many bytes as the text has, twice (a "v x y z" line of ~30 bytes becomes 12-24 bytes).
    const uint64_t fileBytes = uint64_t(std::filesystem::file_size(objPath, ec));
    requireMemory(2 * fileBytes, "twice the OBJ file's " + formatBytes(fileBytes), sceneFile, where);

    const ObjScanContext ctx{sceneFile, where};
    const ObjTextScan scan = scanObjText(objPath, ctx);
    const std::string dir = std::filesystem::path(objPath).parent_path().string();
    // tinyobjloader looks for a library as <search path><name>, the search path ending in '/'.
    const std::string searchPath = dir.empty() ? "./" : dir + "/";
    if (requireMaterials)
        for (const ObjTextScan::Library& lib : scan.mtllibs) {
            // tinyobjloader loads the first name of the line it can open; those are the texts it reads.
            bool found = false;
            std::string tried;
            for (const std::string& name : lib.names) {
                const std::string p = searchPath + name;
                tried += (tried.empty() ? "'" : ", '") + p + "'";
                if (!std::filesystem::is_regular_file(p, ec)) continue;
                scanMtlText(p, ctx);
                found = true;
                break;
            }
            if (!found) {
                std::string names;
                for (const std::string& name : lib.names) names += (names.empty() ? "'" : " '") + name + "'";
                throw InputError(sceneFile, where,
                                 fileLine(objPath, lib.line) + ": material library " + (names.empty() ? "''" : names) +
                                     " not found (looked for " + (tried.empty() ? "a file name" : tried) +
                                     "); give the shape a \"material\" to ignore the OBJ's materials");
            }
        }

    tinyobj::ObjReaderConfig config;
    config.triangulate = false;  // emitting quads become rect lights; the scene builder triangulates the rest
    config.vertex_color = false;
    config.mtl_search_path = searchPath;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(objPath, config)) {
        std::string err = reader.Error();
        while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
        throw InputError(sceneFile, where, "cannot parse OBJ file '" + objPath + "': " + err);
    }

    ObjFile file;
    appendLines(reader.Warning(), objPath + ": ", file.warnings);
    if (scan.degenerateFaces > 0)
        file.warnings.push_back("OBJ file '" + objPath + "': skipped " + std::to_string(scan.degenerateFaces) + " face" +
                                (scan.degenerateFaces == 1 ? "" : "s") + " with fewer than 3 vertices (the first on line " +
                                std::to_string(scan.firstDegenerateLine) + ")");
    for (const tinyobj::material_t& m : reader.GetMaterials()) {
        ObjMaterial om;
        om.name = m.name;
        om.kd = Vec3(m.diffuse[0], m.diffuse[1], m.diffuse[2]);
        om.ks = Vec3(m.specular[0], m.specular[1], m.specular[2]);
        om.ke = Vec3(m.emission[0], m.emission[1], m.emission[2]);
        om.ns = float(m.shininess);
        // The MTL scan has refused bad numbers with their line; this catches whatever tinyobjloader
        // read differently from the scan (a library the scan did not see), without a line.
        std::string why = emissionProblem(om.ke, "Ke");
        for (const Vec3& c : {om.kd, om.ks})
            if (why.empty() && !(c.isFinite() && c.minComponent() >= 0.f)) why = "Kd or Ks is negative or not finite";
        if (why.empty()) why = exponentProblem(om.ns, "Ns");
        if (requireMaterials && !why.empty())
            throw InputError(sceneFile, where, "OBJ file '" + objPath + "': material '" + m.name + "': " + why);
        file.materials.push_back(om);
    }
    if (requireMaterials)
        for (const ObjTextScan::Named& use : scan.usemtls) {
            const auto defined = [&](const std::string& n) {
                return std::any_of(file.materials.begin(), file.materials.end(), [&](const ObjMaterial& m) { return m.name == n; }) ||
                       std::find(knownMaterials.begin(), knownMaterials.end(), n) != knownMaterials.end();
            };
            if (!defined(use.name))
                throw InputError(sceneFile, where,
                                 fileLine(objPath, use.line) + ": usemtl '" + use.name +
                                     "' names a material that no material library (mtllib) defines");
        }

    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    const size_t vertexCount = attrib.vertices.size() / 3, normalCount = attrib.normals.size() / 3;
    for (size_t i = 0; i < vertexCount; ++i)
        if (!vec3At(attrib.vertices, i).isFinite())
            throw InputError(sceneFile, where, "OBJ file '" + objPath + "': vertex " + std::to_string(i + 1) + " is not finite");

    // Part key: (group name, material) when splitting by groups, the material alone otherwise.
    std::map<std::pair<std::string, int>, size_t> partIndex;
    std::vector<std::map<std::pair<int, int>, uint32_t>> renumber;  // per part: (v, vn) -> local vertex
    std::vector<bool> allNormals;
    const std::string stem = std::filesystem::path(objPath).stem().string();
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        const std::string group = shape.name.empty() ? stem : shape.name;
        const auto& sizes = shape.mesh.num_face_vertices;
        size_t offset = 0;
        for (size_t f = 0; f < sizes.size(); ++f) {
            const size_t n = sizes[f];
            const int mat = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
            const auto key = split == ObjSplit::Groups ? std::make_pair(group, mat) : std::make_pair(std::string(), mat);
            auto [it, fresh] = partIndex.emplace(key, file.parts.size());
            if (fresh) {
                file.parts.emplace_back();
                file.parts.back().material = mat;
                renumber.emplace_back();
                allNormals.push_back(true);
            }
            ObjPart& part = file.parts[it->second];
            if (n < 3) {  // tinyobjloader drops these itself; the scan's warning counts them
                offset += n;
                continue;
            }
            for (size_t k = 0; k < n; ++k) {
                const tinyobj::index_t& c = shape.mesh.indices[offset + k];
                // The line scan has checked every index; tinyobjloader resolved relative ones.
                if (c.vertex_index < 0 || size_t(c.vertex_index) >= vertexCount || c.normal_index >= int(normalCount))
                    throw InputError(sceneFile, where, "OBJ file '" + objPath + "': face " + std::to_string(f + 1) + " of '" +
                                                           group + "' refers to a missing vertex");
                if (c.normal_index < 0) allNormals[it->second] = false;
                auto [v, added] = renumber[it->second].emplace(std::make_pair(c.vertex_index, c.normal_index),
                                                               uint32_t(part.positions.size()));
                if (added) {
                    part.positions.push_back(vec3At(attrib.vertices, size_t(c.vertex_index)));
                    part.normals.push_back(c.normal_index >= 0 ? vec3At(attrib.normals, size_t(c.normal_index)) : Vec3(0.f));
                }
                part.indices.push_back(v->second);
            }
            part.faceSizes.push_back(uint32_t(n));
            offset += n;
        }
    }
    size_t faces = 0;
    for (size_t i = 0; i < file.parts.size(); ++i) {
        ObjPart& part = file.parts[i];
        faces += part.faceSizes.size();
        const std::string matName = part.material >= 0 ? file.materials[size_t(part.material)].name : "default";
        if (split == ObjSplit::Materials) {
            part.name = matName;
        } else {
            const std::string group = std::find_if(partIndex.begin(), partIndex.end(), [&](const auto& kv) {
                                          return kv.second == i;
                                      })->first.first;
            const bool several = std::count_if(partIndex.begin(), partIndex.end(), [&](const auto& kv) {
                                     return kv.first.first == group;
                                 }) > 1;
            part.name = several ? group + "." + matName : group;
        }
        // Normals count only if every corner has one and all have a direction.
        bool ok = allNormals[i];
        for (Vec3& n : part.normals) {
            const float len = length(n);
            if (!(len > 0.f) || !std::isfinite(len)) ok = false;
            else n = n / len;
        }
        if (!ok) part.normals.clear();
    }
    file.parts.erase(std::remove_if(file.parts.begin(), file.parts.end(), [](const ObjPart& p) { return p.faceSizes.empty(); }),
                     file.parts.end());
    if (faces == 0) throw InputError(sceneFile, where, "OBJ file '" + objPath + "' contains no triangles or polygons");
    return file;
}

}  // namespace rrf
