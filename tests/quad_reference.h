#pragma once
/// Reference ray–quadrilateral intersection (Lagae & Dutré 2005).
///
/// The seed report intersected its quads with A. Lagae and P. Dutré, "An efficient
/// ray-quadrilateral intersection test", Journal of Graphics Tools 10(4), 2005. The renderer
/// uses Embree's quads instead; this implementation is kept as an independent reference that the
/// tests compare Embree against, and as the definition of the bilinear (u, v) of a hit.
///
/// Vertex order: the four vertices go once around the boundary,
///
///     v01 ---- v11          Embree's RTC_GEOMETRY_TYPE_QUAD takes the same boundary order
///      |        |           v0 v1 v2 v3, i.e. v00 = v0, v10 = v1, v11 = v2, v01 = v3.
///      |        |           u runs from v00 towards v10, v runs from v00 towards v01.
///     v00 ---- v10
///
/// Either winding (clockwise or counter-clockwise as seen from the ray) is accepted; the test is
/// two-sided. The quad must be planar and convex (parallelograms, trapezoids, general convex
/// planar quads), as the paper requires.

#include "core/util/vec3.h"

namespace rrf {

/// Intersects the ray origin + t·dir (t > 0, dir need not be normalised) with the quad
/// v00 v10 v11 v01. On a hit returns true and sets `t` (in units of |dir|) and the bilinear
/// coordinates (u, v) of the hit point:
///
///     x = (1-u)(1-v)·v00 + u(1-v)·v10 + u·v·v11 + (1-u)·v·v01.
///
/// On a miss returns false and leaves t, u, v untouched.
///
/// The paper's algorithm, step by step: (1) barycentric test of the plane hit against triangle
/// v00 v10 v01 (alpha along v00→v10, beta along v00→v01), rejecting alpha < 0 or beta < 0;
/// (2) if alpha + beta > 1, the same test against triangle v11 v10 v01 sharing the edge v10 v01;
/// (3) t from the first triangle's terms; (4) the barycentric coordinates (alpha11, beta11) of v11
/// with respect to v00, v10, v01, computed in the projection plane where the normal is largest;
/// (5) (u, v) from (alpha, beta): directly for parallelograms (alpha11 = beta11 = 1), by one
/// division for trapezoids (alpha11 = 1 or beta11 = 1), and otherwise from the quadratic
/// A u² + B u + C = 0 with A = 1 - beta11, B = alpha(beta11-1) - beta(alpha11-1) - 1, C = alpha,
/// solved with the numerically stable form q = -(B + sign(B)·sqrt(B² - 4AC))/2, u ∈ {q/A, C/q}.
///
/// Deliberate differences from the paper's listing, none of which changes a result away from the
/// quad's edges:
///  - arithmetic is done in double, as befits a reference;
///  - the "ray parallel to the quad" rejection compares |det| with 1e-6·|dir|·|e01|·|e03| (the
///    paper's epsilon 1e-6, made relative) instead of an absolute 1e-6, so it behaves the same at
///    every scene scale and rejects zero-area quads, whose det is rounding noise;
///  - the discriminant is clamped at 0 and, of the two roots, the one closer to [0, 1] is taken
///    (the paper takes q/A unless it lies outside [0, 1]), so a hit on an edge cannot switch to
///    the spurious root because of rounding;
///  - a hit whose (u, v) lies outside [0, 1] by more than 1e-5, or is not finite, is a miss:
///    the two wedge tests intersect the planes of two different triangles, which differ slightly
///    for float vertices, and a nearly parallel ray can pass both far outside the quad; NaN only
///    arises at the collapsed corner of a degenerate quad (v11 == v10, say). Returned (u, v) are
///    clamped to [0, 1].
bool intersectQuadLagaeDutre(const Vec3& origin, const Vec3& dir, const Vec3& v00, const Vec3& v10,
                             const Vec3& v11, const Vec3& v01, float& t, float& u, float& v);

/// The point of the quad at bilinear coordinates (u, v), in the convention above.
Vec3 bilinearQuadPoint(const Vec3& v00, const Vec3& v10, const Vec3& v11, const Vec3& v01, float u, float v);

}  // namespace rrf
