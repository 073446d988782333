#pragma once
/// The unshadowed glossy light of a modified-Phong receiver under an area light, without random
/// numbers: the glossy factor of exact direct light (core/predict/exact_direct.h).
///
///   G = ∫_light max(0, r·ω)^e · max(0, n·ω) dω      (r the mirror direction of ωo, n the normal)
///
/// so that the glossy radiance of an unshadowed receiver is Le · ks (e+2)/(2π) · G. Next-event
/// estimation with uniform light samples needs hundreds of samples for a lobe of exponent 1000 that
/// covers a small part of the light; G is a smooth integral over a known domain, so a quadrature
/// gets it to ~1e-5 with a few dozen integrand evaluations and no shadow rays:
///
///  1. Footprint. cos^e α falls below ε = 1e-6 · 2π/(e+2) outside the cone tan²α ≤ τ² with
///     τ² = ε^(−2/e) − 1 (the neglected light is below 1e-6 · Le · ks · Ω_light). The cone meets the
///     light's plane in a conic Q(u, v) ≥ 0 in the light's own (u, v) coordinates; when it is an
///     ellipse its bounding box, clipped to the light, is the domain, else the whole light is.
///     An ellipse on the backward half of the cone, or an empty one, means G = 0 to ε.
///  2. Closed form. When the ellipse lies inside the light and the cone above the horizon, the light
///     holds the whole lobe: G = ∫_hemisphere cos^e α (n·ω) dω = 2π (n·r)/(e+2) (the components of ω
///     across r integrate to zero), and the glossy radiance is Le · ks · (n·r).
///  3. Quadrature. Otherwise an iterated 8-point Gauss–Legendre rule over the domain (u outer, v
///     inner), each axis split into panels at the mirror ray's hit on the light, so that each panel
///     holds one flank of the peak (8 nodes then integrate a half-Gaussian cut anywhere to ~1e-5,
///     where one panel over the whole peak would be off by 1.5e-2), and for a triangle at the kink
///     u = 1 − v1 of the inner limit min(v1, 1 − u).
///
/// The lobe is evaluated as (1 − sin²α)^(e/2) with sin α from the component of (x − p) across r,
/// which is linear in (u, v) and so is formed without cancellation: float cos α would round the
/// peak of a lobe of exponent 1e6 away. Float throughout, in the order shaders/direct_light.glsl
/// repeats, so that the two agree to rounding.

#include "core/scene/scene.h"

namespace rrf {

/// Nodes per panel and axis of the quadrature above.
constexpr int kLobeNodes = 8;

/// G above for the area light `l` seen from p (unit normal n, unit mirror direction r, exponent
/// e ≥ 0). 0 behind a one-sided light. Finite for finite input, any e up to 1e6 and beyond.
float phongLobeIntegral(const Light& l, const Vec3& p, const Vec3& n, const Vec3& r, float e);

/// τ² of the footprint cone for exponent e (above): +inf for e ≤ 0 and for lobes so wide that the
/// cone is the whole hemisphere.
float lobeFootprintTan2(float e);

}  // namespace rrf
