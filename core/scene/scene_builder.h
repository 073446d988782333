#pragma once
/// State and geometry helpers shared by the two halves of the scene reader: scene_json.cpp (the
/// scene JSON: camera, materials, JSON shapes, lights, light region) and scene_obj_shapes.cpp (OBJ
/// shapes that bring their own MTL materials and emitters). Internal to core/scene.

#include <map>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "core/scene/transform.h"
#include "core/util/json_reader.h"

namespace rrf {

/// A primitive whose doubled area is below this fraction of its squared size counts as zero-area:
/// float vertices of collinear points leave a cross product of about 1e-7 of the size squared.
constexpr double kDegenerateArea = 1e-6;
/// Allowed distance of a quad corner from the quad's plane, relative to the quad's diagonal.
constexpr double kPlanarity = 1e-4;
/// Slack for "kd + ks <= 1": decimal inputs such as 0.7 + 0.3 do not sum to exactly 1.
constexpr double kEnergySlack = 1e-6;

/// What the reader has built so far: the scene, the directory relative paths start from, the
/// materials by name and the object names in use (name -> JSON pointer of first use).
struct SceneBuildState {
    Scene& scene;
    std::string baseDir;
    std::map<std::string, int> materialIndex;
    std::map<std::string, std::string> objectNames;

    /// Records `name` as used at `r`'s pointer; a name used before is an error at `r`.
    void claimObjectName(const JsonReader& r, const std::string& name);
};

/// Applies `t` to the object's points and normals (normals by the inverse transpose); a mirroring
/// transform reverses each primitive so that normals stay outward.
void applyTransform(const Transform& t, Object& o);

/// Removes zero-area triangles (counted in `warnings`); an object left empty is an error at `r`.
void dropDegenerateTriangles(const JsonReader& r, Object& o, std::vector<std::string>& warnings);

/// An OBJ shape without "material": one object per part (ObjSplit), materials from the MTL,
/// and — when `emitters` (the scene JSON has no "lights") — area lights from faces whose
/// material has Ke > 0, appended to `lightsOut`: a planar parallelogram quad becomes a rect
/// light, any other face a fan of triangle lights. Emitting faces are black emitters, as in the
/// Cornell box.
void addObjFileShapes(SceneBuildState& b, const JsonReader& r, bool emitters, std::vector<Light>& lightsOut);

/// Makes the OBJ files' emitters the scene's lights: unique names (a repeated name gets the next
/// free "#k") and the light of largest power movable.
void adoptObjLights(Scene& scene, std::vector<Light> lights);

}  // namespace rrf
