#pragma once
/// Exact direct light for prediction (docs/design.md §13.1): the direct term computed per pixel
/// instead of learned, as in Ren et al. 2013, with the estimator real-time renderers use for polygon
/// lights, so that unshadowed light is closed-form and shadow rays are needed only in penumbra.
///
/// For a receiver at p with normal n (facing the viewer), material kd, ks, exponent e, mirror
/// direction r of the view direction, and an area light (rect or triangle) of radiance Le:
///
///   diffuse  = kd/π · Le · Ω⊥ · R_d,   Ω⊥ = ∫_light cosθ dω in closed form (Lambert's polygon
///              formula over the light clipped to n's hemisphere, core/predict/light_polygon.h)
///   glossy   = Le · ks (e+2)/(2π) · G · R_g,   G = ∫_light cos^e α cosθ dω by a quadrature of the
///              lobe's footprint on the light, or its closed form (core/predict/phong_lobe_integral.h)
///   R_d = Σ_j f_j V_j / Σ_j f_j,  R_g = Σ_j g_j f_j V_j / Σ_j g_j f_j      (Heitz et al. 2018)
///
/// with f_j = cosθ_j cosθ'_j / d_j² and g_j = cos^e α_j at light sample j, and V_j ∈ {0,1} its
/// shadow ray. The ratios are the visibility of the light weighted by each lobe: exactly 1 where
/// every sample is visible, 0 where none is, and in penumbra a ratio of two correlated sums, low in
/// noise and consistent (the bias vanishes as N grows). If no sample lands above the receiver's
/// horizon although the clipped light is not empty, R_d is the visibility of one ray to the clipped
/// polygon's centroid; if no sample has glossy weight, R_g = R_d. Point lights are exact with one
/// shadow ray.
///
/// Rays only where they are needed (core/predict/shadow_casters.h): receivers that provably see all
/// of a light or none of it get R = 1 or 0, exactly what their rays would give, without sample rays;
/// receivers with a few convex casters clip their N sample rays against just those; the others
/// trace them through Embree in packets of 16 rays from their common origin
/// (PathTracer::occludedPacket).
///
/// Light samples: N per area light, a jittered grid of ⌈√N⌉ columns × ⌈N/⌈√N⌉⌉ rows over the
/// light's (u, v) square (Light::pointAt: a triangle folds the square onto itself), sample s in cell (s mod cols, s div cols), rotated per pixel by a
/// uniform toroidal shift (Cranley–Patterson) so that every sample is uniform on the light for any N
/// (partial last row included). Sample s of pixel i takes its jitter from Rng(seed', i, s) and the
/// shift from Rng(seed', i, kShiftSample), two numbers per area light in scene order, with
/// seed' = mix64(seed ^ kExactDirectStream). shaders/direct_light.glsl repeats all of this (64-bit
/// Rng emulated with 32-bit words, the same quadrature, brute-force shadow rays and no proofs), so
/// the GLSL result is the same estimate up to float rounding and the shadow-ray test's edge cases.
///
/// Shadow rays are the path tracer's (Embree plus the movable light), from Accel::spawnOrigin,
/// stopping short of the light sample as PathTracer's NEE does.

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/predict/gbuffer.h"
#include "core/predict/light_polygon.h"
#include "core/predict/shadow_casters.h"
#include "core/render/brdf.h"
#include "core/render/path_tracer.h"
#include "core/util/image.h"

namespace rrf {

/// The stream id mixed into the prediction seed, so exact direct light never shares random numbers
/// with other uses of the same seed ("EXACTDIR").
constexpr uint64_t kExactDirectStream = 0x4558414354444952ULL;
/// seed' = mix64(seed ^ kExactDirectStream): the key of every random number of exact direct light.
inline uint64_t exactDirectSeed(uint64_t seed) { return mix64(seed ^ kExactDirectStream); }
/// Sample index of the per-pixel toroidal shift (no light sample uses it: samples are < 65536).
constexpr uint64_t kShiftSample = 0xFFFFFFFFULL;

/// Columns and rows of the jittered grid for `samples` light samples.
struct SampleGrid {
    int cols = 1, rows = 1;
    explicit SampleGrid(int samples);
    /// Sample s's point on the unit square: its cell (s mod cols, s div cols) jittered by two numbers
    /// of `rng` (u, then v), shifted toroidally by (su, sv), kept below 1. The glossy gather's
    /// directions and caustic light samples use it; traceSamples repeats it lane by lane.
    void point(int s, Rng& rng, float su, float sv, float& u, float& v) const {
        u = (float(s % cols) + rng.uniform()) / float(cols) + su;
        v = (float(s / cols) + rng.uniform()) / float(rows) + sv;
        if (u >= 1.f) u -= 1.f;
        if (v >= 1.f) v -= 1.f;
        u = std::min(u, 0x1.fffffep-1f);
        v = std::min(v, 0x1.fffffep-1f);
    }
};

class ExactDirect {
public:
    struct Options {
        /// Settle receivers by their ShadowCasters (else every sample ray goes to Embree): off only
        /// to check that the casters change no estimate (tests) and to time them (bench_direct).
        bool proofs = true;
    };

    /// `tracer` (its scene, accelerator and movable light) must outlive this. `samples` ≥ 1.
    ExactDirect(const PathTracer& tracer, int samples, uint64_t seed, Options options);
    ExactDirect(const PathTracer& tracer, int samples, uint64_t seed) : ExactDirect(tracer, samples, seed, Options{}) {}

    /// Direct radiance leaving the surface point p of object `object` towards wo (unit), with n the
    /// unit normal on wo's side, the movable light as `movable` (PathTracer::movableLightAt) and
    /// `pixel` the random-number stream. May be non-finite only for non-finite input. `settled`
    /// (optional) counts how each area light's shadow rays were decided. `gloss` false leaves out
    /// the material's glossy lobe (GBuffer::directWithoutGloss).
    Vec3 radiance(const Vec3& p, const Vec3& n, const Vec3& wo, int object, const Light& movable, uint64_t pixel,
                  TraceCounters& counters, ShadowCasters::Counts* settled = nullptr, bool gloss = true) const;

    /// radiance() at every object pixel of `gb` (pixel key y·width + x, wo towards the camera as the
    /// G-buffer stores it, without gloss where GBuffer::directWithoutGloss says), rows in parallel;
    /// other pixels 0. Non-finite values become 0 and are
    /// counted in `nonFinite`. The same image for any thread count.
    Image image(const GBuffer& gb, const Light& movable, uint64_t& nonFinite, ShadowCasters::Counts* settled = nullptr,
                TraceCounters* counters = nullptr) const;

    int samples() const { return samples_; }
    /// seed' above: the key the GLSL path is given.
    uint64_t streamSeed() const { return seed_; }

private:
    /// The sums of one area light's N samples: Σf, Σf·V, Σg·f, Σg·f·V.
    struct Sums {
        float f = 0.f, fv = 0.f, g = 0.f, gv = 0.f;
    };
    /// `casters`: answer the rays with ShadowCasters::blocked (verdict Segments); null: Embree.
    Sums traceSamples(const Light& l, int areaIndex, const Vec3& p, const Vec3& n, const Vec3& mirror,
                      const Brdf& brdf, const Light& movable, const ShadowCasters::Casters* casters, uint64_t pixel,
                      TraceCounters& c) const;
    bool visible(const Vec3& p, const Vec3& n, const Vec3& target, const Light& movable, TraceCounters& c) const;

    const PathTracer& tracer_;
    int samples_;
    uint64_t seed_;
    SampleGrid grid_;
    Options options_;
    ShadowCasters casters_;
    std::vector<Brdf> brdfs_;  ///< per material
};

}  // namespace rrf
