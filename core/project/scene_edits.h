#pragma once
/// The scene edits the workbench makes (moving the light, changing a material), each one function
/// used by every place that makes it (Scene panel, scripted sessions, re-opening a run): the edit is
/// applied to project.scene and recorded in project.overrides, so a save keeps it and the CLI sees
/// the same scene.

#include "core/project/project.h"

namespace rrf {

/// Moves the scene's movable light to `position`, clamped into the light region, and records it.
/// Returns the position used; does nothing (and returns `position`) when the scene has no light.
Vec3 moveLight(Project& project, const Vec3& position);

/// Replaces material `index` with `edited`, keeping kd + ks ≤ 1 per channel by lowering the
/// coefficient the user did not just edit (see enforceEnergyConservation; `kdEdited` says which),
/// making it Phong once ks is non-zero, and records it. Returns true when energy conservation
/// changed what was asked for (the panel says so). An index out of range changes nothing.
bool editMaterial(Project& project, int index, Material edited, bool kdEdited);

}  // namespace rrf
