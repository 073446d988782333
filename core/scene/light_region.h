#pragma once
/// The light region of a scene whose movable light came from an OBJ file's emitter (scene JSON
/// without "light_region"), derived from the emitter and the room around it the way the Cornell box
/// project's hand-written region relates to its ceiling light:
///
///   - along the emitter's normal, from the emitter's centre into the side it lights, a quarter of
///     the scene's extent (objects and area lights) in that direction (the Cornell box: 0.39 of a
///     room 2 high);
///   - across it, the emitter's own extent on each side of its centre (half-size ×2);
///   - then shrunk so that the moved emitter stays inside the scene's bounds, and the emitter's
///     current centre always inside the region (an axis that cannot hold both collapses to it).
///
/// Every length is relative to the scene's own sizes, so millimetre and metre scenes get the same
/// region up to scale.

#include "core/scene/scene.h"

namespace rrf {

/// The region for the area light `lightIndex` of `scene` (its objects and that light). A point light
/// or a scene without objects gets the empty box (the light does not move).
Bounds3 deriveLightRegion(const Scene& scene, int lightIndex);

}  // namespace rrf
