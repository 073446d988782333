#pragma once
/// The range of coordinates in which rays stay valid: one definition for the scene validator (every
/// shape after its transform, the camera, the lights and the light region), for light positions
/// given on the command line, in a project's scene_overrides or in the workbench.
///
/// Why 1e16: Embree refuses (asserts on) any ray whose origin or direction has a component beyond
/// FLT_LARGE = 1.844e18. Ray origins are the camera's eye and points on the scene's surfaces or
/// lights, so every such point must stay inside that box with room to spare: a hit point is
/// origin + t·dir, rounded in float, and the path tracer squares distances between two points of the
/// scene (NEE's d², at most 12·B² for coordinates ≤ B) and multiplies them by light areas (≤ 4·B²)
/// and radiance. B = 1e16 leaves a factor 184 below FLT_LARGE and keeps 12·B² = 1.2e33 five orders
/// of magnitude below FLT_MAX (3.4e38). The scene-scale hard cases (docs/design.md §7: scales 1e-3 …
/// 1e4) lie far inside it.

#include <string>

#include "core/scene/scene.h"

namespace rrf {

/// Largest |x|, |y| or |z| of any point of a scene (see the file comment).
constexpr double kMaxCoordinate = 1e16;

/// True when every component of `p` is finite and within [-kMaxCoordinate, kMaxCoordinate].
bool withinCoordinateRange(const Vec3& p);

/// "" when `p` is within the range; otherwise why not, naming the axis and the accepted range
/// ("y = 1e+19 is outside [-1e+16, 1e+16], the coordinate range in which rays stay valid").
std::string coordinateRangeProblem(const Vec3& p);

/// "" when light `l` with its centre moved to `centre` lies within the range (a rect light's four
/// corners, a point light's position); otherwise why not.
std::string lightPlacementProblem(const Light& l, const Vec3& centre);

/// `p` clamped into the coordinate range, component by component (NaN becomes 0).
Vec3 clampToCoordinateRange(const Vec3& p);

}  // namespace rrf
