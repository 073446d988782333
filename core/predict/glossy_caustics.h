#pragma once
/// Glossy caustics for the glossy gather (docs/design.md §13, "Caustics in the gather"): the light
/// that reaches a diffusely reflecting point x from an area light by way of one glossy reflection on a
/// flat face, sampled from the light instead of from x.
///
/// Why: the glossy gather takes x's diffuse indirect light from cosine-distributed rays and the
/// radiance where they land. Where they land on a sharply glossy face, that radiance holds the face's
/// glossy reflection of the light: bright (ks · Le) in the small set of directions that see the
/// light's mirror image, black elsewhere. Cosine rays find that image by chance, so a gathered
/// receiver of caustics (the ceiling above two polished boxes) is all fireflies. The same light is
/// an integral over pairs (light point l, face point y) that is easy to sample from the light side:
///
///   C(x) = kd/π ∫_light ∫_face Le f_g(y; l → y → x) G(y, l) G(x, y) V(x, y) V(y, l) dA_y dA_l
///
/// with f_g the face's glossy lobe ks (e+2)/(2π) cos^e α (its diffuse lobe stays with the cosine
/// rays) and G(a, b) = cosθ_a cosθ_b / |a − b|². For each face plane that x and the light are both in
/// front of: l uniform on the light (jittered grid, per-pixel toroidal shift, as exact direct light),
/// then y from a Gaussian on the plane around the mirror point y0 of the path x → y0 → l, whose
/// widths follow the lobe: the path's kink at y is α ≈ |δ⊥| (1/a + 1/b) for an offset δ across the
/// unfolded ray x → l′ (a = |y0 − x|, b = |l − y0|), so cos^e α ≈ exp(−e α²/2) gives
/// σ⊥ = 1/(√e (1/a + 1/b)) across and σ⊥ / cosθ along the ray's trace on the plane (widened by
/// kWiden so the tails stay below the lobe's). One ray x → y both tests visibility and that y lies on
/// the face (it must hit that object's plane at y); one shadow ray y → l. Unbiased for any exponent
/// (the Gaussian is only the importance density); for a mirror-like lobe nearly every sample lands.
///
/// The gather's cosine rays then leave out the glossy direct light at points of caster objects
/// (GBuffer::directWithoutGloss), so each path is counted once.
///
/// Casters: objects whose material is Phong with ks > 0 and exponent ≥ the gather's min_exponent,
/// made of at most kMaxCasterPlanes planes (boxes, quads, flat-shaded meshes): every point of the
/// object lies on one of them. A curved or smooth-shaded mesh's glossy light stays with the cosine
/// rays, and so does light an object reflects onto itself (the receiver's own object casts nothing
/// onto it).
///
/// Random numbers: sample s of (plane, light) pair u of pixel i draws from Rng(seed', i, u·N + s), the
/// light grid's shift from Rng(seed', i, 0xFFFF0000 + u), seed' = mix64(seed ^ kGlossyCausticStream):
/// the same estimate for any thread count.

#include <cstdint>
#include <vector>

#include "core/render/path_tracer.h"

namespace rrf {

/// The stream id mixed into the prediction seed for caustic samples ("CAUSTICS").
constexpr uint64_t kGlossyCausticStream = 0x4341555354494353ULL;
/// Most planes an object may have to cast caustics here.
constexpr int kMaxCasterPlanes = 16;

class GlossyCaustics {
public:
    /// `tracer` must outlive this. `samples` (≥ 1) per caster plane and area light; objects with a
    /// Phong exponent ≥ `minExponent` (> 0) cast.
    GlossyCaustics(const PathTracer& tracer, int samples, float minExponent, uint64_t seed);

    /// True if object `object` casts caustics (its points' glossy direct light belongs to C(x)).
    bool casts(int object) const {
        return object >= 0 && size_t(object) < planes_.size() && !planes_[size_t(object)].empty();
    }
    bool anyCaster() const { return anyCaster_; }
    /// Object `object` casts no caustics here (its points' light comes whole from elsewhere).
    void exclude(int object);

    /// C(x) above towards the viewer for a receiver at p with unit normal n (on the viewer's side),
    /// unit geometric normal ng on that side, diffuse albedo kd, of object `self` (never its own
    /// caster), with the movable light `movable`; `pixel` keys the random numbers.
    Vec3 radiance(const Vec3& p, const Vec3& n, const Vec3& ng, const Vec3& kd, int self, const Light& movable,
                  uint64_t pixel, TraceCounters& counters) const;

    /// The planes an object lies on (unit normal m, offset c: m·x = c, with m the faces' stored
    /// geometric normal), or none if it has more than kMaxCasterPlanes or is a sphere.
    struct Plane {
        Vec3 m;
        float c = 0.f;
    };
    static std::vector<Plane> planesOf(const Object& o);

private:
    const PathTracer& tracer_;
    int samples_;
    uint64_t seed_;
    std::vector<std::vector<Plane>> planes_;  ///< per object; empty: not a caster
    std::vector<Vec3> ks_;                    ///< per object
    std::vector<float> exponent_;             ///< per object
    bool anyCaster_ = false;
};

}  // namespace rrf
