#pragma once
/// Scene edits made in the workbench (material parameters, the movable light's position) are stored
/// in the project's "scene_overrides" section rather than written into the scene file, which may be
/// shared by several projects:
///
///     "scene_overrides": {
///       "light_position": [0, 0.9, 0],
///       "materials": { "white": { "kd": [0.8, 0.7, 0.6], "ks": [0, 0, 0], "exponent": 1 } }
///     }
///
/// They are applied right after the scene is loaded, so the CLI and the GUI see the same scene (and
/// datasets and models record the same scene hash). Editing goes through core/project/scene_edits.h,
/// which records the override and applies it in one step; core/project/scene_overrides_json.h reads
/// and writes the section.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace rrf {

/// New parameters of one material; a field left empty keeps the scene's value.
struct MaterialOverride {
    std::optional<Vec3> kd, ks;
    std::optional<float> exponent;
};

struct SceneOverrides {
    std::optional<Vec3> lightPosition;                  ///< centre of the movable light
    std::map<std::string, MaterialOverride> materials;  ///< by material name

    bool empty() const { return !lightPosition && materials.empty(); }
};

/// Applies `overrides` to `scene`. Entries that do not fit the scene (unknown material, a light
/// position outside the light region, a scene without lights) are skipped or clamped and described
/// in `problems` (prefixed with `where`, the section's JSON pointer); the rest still apply.
void applySceneOverrides(const SceneOverrides& overrides, Scene& scene, std::vector<std::string>& problems,
                         const std::string& where = "/scene_overrides");

/// Keeps kd + ks ≤ 1 per channel (energy conservation) by lowering the coefficient the user did not
/// just edit (ks when `kdEdited`, kd otherwise), and clamps both to [0, 1] and the exponent to
/// [0, kMaxPhongExponent] (core/scene/radiometric_range.h; a non-finite one becomes 1). Returns true
/// if anything changed.
bool enforceEnergyConservation(Material& m, bool kdEdited);

/// Clamps `p` into the scene's light region. When the region is empty `p` is kept as it is, unless
/// the light placed there would leave the coordinate range (core/scene/coordinate_range.h): then the
/// light's current position is returned.
Vec3 clampToLightRegion(const Scene& scene, const Vec3& p);

}  // namespace rrf
