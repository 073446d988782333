// OBJ shapes that bring their own materials and lights (the "obj" shape without "material"):
// objects per group or material, MTL materials, Ke emitters as rect or triangle lights.
#include <algorithm>
#include <optional>
#include <set>

#include "core/scene/coordinate_range.h"
#include "core/scene/obj_loader.h"
#include "core/scene/radiometric_range.h"
#include "core/scene/scene_builder.h"
#include "core/scene/scene_parse.h"
#include "core/util/json_reader.h"

namespace rrf {

namespace {

/// The scene's material for an MTL material: the JSON's material of that name if there is one
/// (explicit entries override), else Lambert (Ks = 0) or Phong from Kd, Ks, Ns, scaled down with a
/// warning where Kd + Ks > 1 in some channel.
int mtlMaterial(SceneBuildState& b, const JsonReader& r, const ObjMaterial* m, const std::string& objPath) {
    const std::string name = m ? m->name : "default";
    if (const auto it = b.materialIndex.find(name); it != b.materialIndex.end()) return it->second;
    Material mat;
    mat.name = name;
    if (m) {
        mat.kd = m->kd;
        mat.ks = m->ks;
        mat.exponent = m->ns;
        mat.type = m->ks.isZero() ? Material::Type::Lambert : Material::Type::Phong;
        // In double: Kd and Ks near FLT_MAX would sum to infinity in float and scale to black.
        double sum = 0;
        for (int i = 0; i < 3; ++i) sum = std::max(sum, double(m->kd[i]) + double(m->ks[i]));
        if (sum > 1 + kEnergySlack) {
            const float s = float(1 / sum);
            mat.kd = m->kd * s;
            mat.ks = m->ks * s;
            b.scene.warnings.push_back(r.file() + ": " + r.pointer() + ": material '" + name + "' of '" + objPath +
                                       "' has Kd + Ks = " + formatNumber(sum) +
                                       " > 1; Kd and Ks scaled by " + formatNumber(s) + " (energy conservation)");
        }
    } else {
        b.scene.warnings.push_back(r.file() + ": " + r.pointer() + ": faces of '" + objPath +
                                   "' without usemtl get material 'default' (Lambert, albedo 0.5)");
    }
    b.materialIndex[name] = int(b.scene.materials.size());
    b.scene.materials.push_back(mat);
    return b.materialIndex[name];
}

}  // namespace

void addObjFileShapes(SceneBuildState& b, const JsonReader& r, bool emitters, std::vector<Light>& lightsOut) {
    r.checkKeys({"type", "name", "file", "transform", "split", "closed"});
    const JsonReader file = r.at("file");
    const std::string path = resolvePath(b.baseDir, file.string());
    ObjSplit split = ObjSplit::Groups;
    if (auto sp = r.find("split")) {
        const std::string v = sp->string();
        if (v == "materials") split = ObjSplit::Materials;
        else if (v != "groups") sp->fail("split must be \"groups\" or \"materials\", got '" + v + "'");
    }
    std::vector<std::string> known;
    for (const auto& kv : b.materialIndex) known.push_back(kv.first);
    ObjFile obj = loadObjFile(path, file.file(), file.pointer(), split, true, known);
    for (std::string& w : obj.warnings) b.scene.warnings.push_back(std::move(w));
    std::optional<Transform> transform;
    if (auto t = r.find("transform")) transform = parseTransform(*t);
    const std::string prefix = r.has("name") ? r.at("name").string() + "/" : "";
    for (const ObjPart& part : obj.parts) {
        const ObjMaterial* m = part.material >= 0 ? &obj.materials[size_t(part.material)] : nullptr;
        Object o;
        o.kind = Object::Kind::Triangles;
        o.name = prefix + part.name;
        o.positions = part.positions;
        o.normals = part.normals;
        if (transform) applyTransform(*transform, o);  // indices are still empty: only points and normals
        for (const Vec3& p : o.positions)
            if (const std::string why = coordinateRangeProblem(p); !why.empty())
                r.fail("OBJ part '" + o.name + "' has a point outside the scene's coordinate range: " + why);
        const bool emits = emitters && m && !m->ke.isZero();
        if (!emitters && m && !m->ke.isZero())
            b.scene.warnings.push_back(r.file() + ": " + r.pointer() + ": emitting faces of '" + o.name +
                                       "' are plain surfaces: the scene's \"lights\" replace the OBJ's emitters");
        size_t first = 0, lightCount = 0;
        size_t tinyEmitters = 0;  // emitting faces too small to be lights (radiometric_range.h)
        std::vector<Light> partLights;
        for (size_t f = 0; f < part.faceSizes.size(); first += part.faceSizes[f++]) {
            const size_t n = part.faceSizes[f];
            std::vector<uint32_t> tris;
            fanTriangulate(part.indices, first, n, tris);
            // A mirroring transform turns the winding: the triangles, and a rect's edges, are
            // swapped back so that the front stays the front.
            const bool flip = transform && transform->flipsOrientation();
            const Vec3 a = o.positions[tris[0]];
            if (emits && n == 4) {
                // Fan (0 1 2)(0 2 3) of a parallelogram a b c d (before any swap): c = b + d − a.
                const Vec3 b = o.positions[tris[1]], c = o.positions[tris[2]], d = o.positions[tris[5]];
                const float diag = std::max(length(c - a), length(d - b));
                if (length(c - (b + d - a)) <= float(kPlanarity) * diag) {
                    Light l;
                    l.radiance = m->ke;
                    l.type = Light::Type::Rect;
                    l.corner = a;
                    l.edge1 = flip ? d - a : b - a;
                    l.edge2 = flip ? b - a : d - a;
                    if (lightSizeProblem(l.edge1, l.edge2).empty()) partLights.push_back(l);
                    else ++tinyEmitters;
                    continue;
                }
            }
            if (flip)
                for (size_t i = 0; i + 3 <= tris.size(); i += 3) std::swap(tris[i + 1], tris[i + 2]);
            if (!emits) {
                o.indices.insert(o.indices.end(), tris.begin(), tris.end());
                continue;
            }
            Light l;
            l.radiance = m->ke;
            for (size_t i = 0; i + 3 <= tris.size(); i += 3) {
                l.type = Light::Type::Triangle;
                l.corner = o.positions[tris[i]];
                l.edge1 = o.positions[tris[i + 1]] - l.corner;
                l.edge2 = o.positions[tris[i + 2]] - l.corner;
                if (lightSizeProblem(l.edge1, l.edge2).empty()) partLights.push_back(l);
                else ++tinyEmitters;
            }
        }
        if (tinyEmitters > 0)
            b.scene.warnings.push_back(r.file() + ": " + r.pointer() + ": dropped " + std::to_string(tinyEmitters) +
                                       " emitting face" + (tinyEmitters == 1 ? "" : "s") + " of '" + o.name +
                                       "' with |edge1 x edge2| below " + formatNumber(kMinLightCross) +
                                       " (zero area, or too small for a float normal)");
        for (Light& l : partLights) {
            l.name = partLights.size() == 1 ? o.name : o.name + "." + std::to_string(lightCount);
            ++lightCount;
            lightsOut.push_back(l);
        }
        if (o.indices.empty()) continue;  // an emitter only
        o.material = mtlMaterial(b, r, m, path);
        o.closed = r.booleanOr("closed", false);
        dropDegenerateTriangles(r, o, b.scene.warnings);
        // Vertices no face of this object uses (emitting faces) stay; only the indices matter.
        o.id = int(b.scene.objects.size());
        b.claimObjectName(r, o.name);
        b.scene.objects.push_back(std::move(o));
    }
}

void adoptObjLights(Scene& scene, std::vector<Light> lights) {
    // The OBJ's emitters are the scene's lights; the one of largest power moves.
    // Unique names: a repeated name gets the next free "#k" (a per-name counter keeps this linear
    // for mesh lamps of many triangles; the set catches names that already end in "#k").
    std::set<std::string> used;
    std::map<std::string, size_t> suffix;
    for (Light& l : lights) {
        const std::string base = l.name;
        size_t& k = suffix[base];
        while (!used.insert(l.name).second) l.name = base + "#" + std::to_string(++k);
    }
    scene.lights = std::move(lights);
    size_t best = 0;
    for (size_t i = 1; i < scene.lights.size(); ++i)
        if (scene.lights[i].radiance.sum() * scene.lights[i].area() >
            scene.lights[best].radiance.sum() * scene.lights[best].area())
            best = i;
    scene.movableLight = int(best);
}

}  // namespace rrf
