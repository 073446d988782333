#pragma once
/// The range of coordinates in which rays stay valid: one definition for the scene validator (every
/// shape after its transform, the camera, the lights and the light region), for light positions
/// given on the command line, in a project's scene_overrides or in the workbench.
///
/// Why 1e9: Embree refuses (asserts on) any ray whose origin or direction has a component beyond
/// FLT_LARGE = 1.844e18, and ray origins are the camera's eye and points on the scene's surfaces or
/// lights. The tighter limit is float arithmetic on those points: the accelerator and the path tracer
/// normalise cross products of two edges (primitive normals, light areas, ray–light intersection),
/// whose squared length is up to (12·B²)² for coordinates within ±B (edges up to 2√3·B). That stays
/// below FLT_MAX = 3.4e38 for B ≤ 1.2e9, so B = 1e9 (beyond it normals collapse to zero and the
/// scene renders black). The scene-scale hard cases (docs/design.md §7: scales 1e-3 … 1e4) lie far
/// inside it, and a room scaled to the bound renders the same image as at scale 1.

#include <string>

#include "core/scene/scene.h"

namespace rrf {

/// Largest |x|, |y| or |z| of any point of a scene (see the file comment); a float, as scene
/// coordinates are.
constexpr float kMaxCoordinate = 1e9f;

/// True when every component of `p` is finite and within [-kMaxCoordinate, kMaxCoordinate].
bool withinCoordinateRange(const Vec3& p);

/// "" when `p` is within the range; otherwise why not, naming the axis and the accepted range
/// ("y = 1e+19 is outside [-1e+09, 1e+09], the coordinate range in which rays stay valid").
std::string coordinateRangeProblem(const Vec3& p);

/// "" when light `l` with its centre moved to `centre` lies within the range (a rect light's four
/// corners, a point light's position); otherwise why not.
std::string lightPlacementProblem(const Light& l, const Vec3& centre);

}  // namespace rrf
