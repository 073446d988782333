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
/// The workbench applies them right after loading a project.

#include <string>
#include <vector>

#include "core/project/project.h"

namespace rrf {

/// Applies project.doc["scene_overrides"] to project.scene. Entries that do not fit the scene
/// (unknown material, light position outside the light region, malformed values) are skipped and
/// described in `problems`; the rest still apply.
void applySceneOverrides(Project& project, std::vector<std::string>& problems);

/// Records the current parameters of material `index` as an override.
void recordMaterialOverride(Project& project, int index);
/// Records the current position of the movable light as an override.
void recordLightOverride(Project& project);

/// Keeps kd + ks ≤ 1 per channel (energy conservation) by lowering the coefficient the user did not
/// just edit (ks when `kdEdited`, kd otherwise), and clamps both to [0, 1]. Returns true if anything
/// changed.
bool enforceEnergyConservation(Material& m, bool kdEdited);

/// Clamps `p` into the scene's light region (unchanged when the region is empty).
Vec3 clampToLightRegion(const Scene& scene, const Vec3& p);

}  // namespace rrf
