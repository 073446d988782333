#pragma once
/// The ranges of emission, Phong exponent and light size within which every value the tracers
/// compute stays a finite float: one definition for the scene JSON (materials, lights), the OBJ's
/// MTL (Kd, Ks, Ke, Ns, read in core/scene/obj_text_scan.cpp), a project's scene_overrides and
/// the workbench's material edits. Values outside are refused when the scene is read, before any
/// work, instead of a render that runs to its end and then cannot write NaN/Inf images.
///
/// Why these bounds (docs/design.md §7a). Every estimator multiplies an emitter's radiance Le (or a
/// point light's intensity I) by a BRDF value and a geometry factor, in float:
///  - path tracer NEE (core/render/path_tracer.cpp): `Le · f · (cos θ · cos θ' A / d²)`, a point
///    light `I · f · (cos θ / d²)`; an emitter hit by a BRDF ray `β · Le` with β ≤ 1 (Russian
///    roulette divides by the throughput itself);
///  - exact direct light (core/predict/exact_direct.cpp): `Le · Σ_N lobe · (cos θ cos θ' / d²) · A/N`
///    over N ≤ 65536 light samples, the product `Le · Σ` formed first;
///  - the variance images of a render and the per-record variances of a dataset hold the squares
///    of those sample values, stored as float.
/// f ≤ 1/π + (n+2)/(2π) ≈ 1.6e5 at the largest exponent n = 1e6, the hard case the sampling code is
/// built and tested for (docs/design.md §7). With Le ≤ 1e10 a sample Le · f · G stays below
/// √FLT_MAX ≈ 1.8e19 — so its square is a float too — for geometry factors G up to 1.1e4 at the
/// sharpest Phong lobe and up to 5.8e9 on Lambert surfaces (G = A/d² reaches 1e4 only within
/// 1 % of a light's size from its surface); exact direct light's `Le · Σ` stays below FLT_MAX for
/// 1/d² up to 2e18. 1e10 is far above any radiance a scene needs (the sun's luminance is 1.6e9
/// cd/m², the Cornell box lamp's 18) and leaves tiny lights room: area 1e-8 × radiance 1e6 is
/// tested. Albedos are bounded by energy conservation (kd + ks ≤ 1 per channel) where they are
/// read.
///
/// Light sizes: the largest area follows from the coordinate range (core/scene/coordinate_range.h:
/// edges ≤ 3.5e9, so |e1 × e2| ≤ 1.2e19 and Le · A ≤ 1.2e29). The smallest is a float limit: a
/// light's normal and the ray–light test divide by |e1 × e2| and by its square, which must stay a
/// normal float (≥ 1.2e-38), so |e1 × e2| ≥ 1e-18 (the square then is 1e-36, a hundred times
/// above the smallest normal float).

#include <string>

#include "core/util/vec3.h"

namespace rrf {

/// Largest emitted radiance of an area light and intensity of a point light, per channel.
constexpr float kMaxRadiance = 1e10f;
/// Largest Phong exponent (JSON "exponent", MTL Ns, scene_overrides, the workbench).
constexpr float kMaxPhongExponent = 1e6f;
/// Smallest |edge1 × edge2| of an area light (a rect's area, twice a triangle's).
constexpr float kMinLightCross = 1e-18f;

/// "" when every channel of `c` is finite and in [0, kMaxRadiance]; otherwise why not, naming
/// `what` ("radiance", "Ke"), the channel and the accepted range.
std::string emissionProblem(const Vec3& c, const std::string& what);

/// "" when `n` is finite and in [0, kMaxPhongExponent]; otherwise why not, naming `what`
/// ("exponent", "Ns") and the accepted range.
std::string exponentProblem(double n, const std::string& what);

/// "" when the cross product of an area light's edges is at least kMinLightCross long (computed
/// in double, so edges whose float product would underflow are measured right); otherwise why not.
std::string lightSizeProblem(const Vec3& edge1, const Vec3& edge2);

}  // namespace rrf
