#pragma once
/// The part of an area light a receiver can see at all, and its unshadowed diffuse light in closed
/// form: the domain and the first factor of exact direct light (core/predict/exact_direct.h).
///
/// A receiver at p with unit normal n receives light only from the light's points above its horizon
/// (n·(x − p) ≥ 0) and, for a one-sided light, only when p is on the emitting side. Clipping the
/// parallelogram or triangle against that half-space (Sutherland–Hodgman) leaves a convex polygon of
/// at most 5 vertices; Lambert's formula over it gives ∫ cosθ dω exactly. The shadow proofs
/// (core/predict/shadow_proof.h) use the same polygon as the base of the pyramid every shadow ray of
/// the receiver lies in.

#include "core/scene/scene.h"

namespace rrf {

/// The light clipped to the receiver's hemisphere, in world space, in boundary order.
struct ClippedLight {
    Vec3 vertex[5];
    int count = 0;  ///< < 3: no part of the light is above the horizon (or p is behind a one-sided light)
    bool empty() const { return count < 3; }
};

/// ∫ cosθ dω (steradians) over the area light `l` seen from p, with n the unit receiver normal:
/// Lambert's formula ½ Σ_edges γ_k n·(q_k × q_k+1)/|q_k × q_k+1| over the parallelogram or triangle clipped to
/// the half-space n·(x − p) ≥ 0 (Sutherland–Hodgman), double precision. 0 behind a one-sided light.
/// `centroid` (optional) receives the clipped polygon's vertex mean (p when it is empty), `clipped`
/// (optional) the clipped polygon itself (empty where the result is 0).
double projectedSolidAngle(const Light& l, const Vec3& p, const Vec3& n, Vec3* centroid = nullptr,
                           ClippedLight* clipped = nullptr);

}  // namespace rrf
