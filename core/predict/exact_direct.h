#pragma once
/// Exact direct light for prediction (docs/design.md §13.1): the direct term computed per pixel
/// instead of learned, as in Ren et al. 2013, with the estimator real-time renderers use for polygon
/// lights so that a few dozen shadow rays per pixel leave little noise.
///
/// For a receiver at p with normal n (facing the viewer), material kd, ks, exponent e, and an area
/// light (rect or triangle) of radiance Le:
///
///   diffuse  = kd/π · Le · Ω⊥ · R,   Ω⊥ = ∫_light cosθ dω in closed form (Lambert's polygon formula,
///              after clipping the parallelogram or triangle to n's hemisphere: projectedSolidAngle),
///              R = Σ_j f_j V_j / Σ_j f_j  the visibility ratio of Heitz et al. 2018, with
///              f_j = cosθ_j cosθ'_j / d_j² the unshadowed integrand and V_j ∈ {0,1} the shadow ray
///              of light sample j. R = 1 wherever every sample is visible, so unoccluded pixels are
///              exact (no variance); in penumbra R is a ratio of two correlated sums, low in noise
///              and consistent (its bias vanishes as N grows).
///   glossy   = (1/N) Σ_j Le · ks (e+2)/(2π) cos^e α_j · cosθ_j cosθ'_j A / d_j² · V_j
///              plain next-event estimation with the same samples and shadow rays (unbiased).
///
/// If no sample lands above the receiver's horizon although the clipped light is not empty (a
/// sliver of the light just above the horizon), R is the visibility of one ray to the clipped
/// polygon's centroid. Point lights are exact with one shadow ray.
///
/// Light samples: N per area light, a jittered grid of ⌈√N⌉ columns × ⌈N/⌈√N⌉⌉ rows over the
/// light's (u, v) square (Light::pointAt: a triangle folds the square onto itself), sample s in cell (s mod cols, s div cols), rotated per pixel by a
/// uniform toroidal shift (Cranley–Patterson) so that every sample is uniform on the light for any N
/// (partial last row included). Sample s of pixel i takes its jitter from Rng(seed', i, s) and the
/// shift from Rng(seed', i, kShiftSample), two numbers per area light in scene order, with
/// seed' = mix64(seed ^ kExactDirectStream). shaders/direct_light.glsl repeats all of this (64-bit
/// Rng emulated with 32-bit words), so the GLSL result is the same estimate up to float rounding and
/// the shadow-ray test's edge cases.
///
/// Shadow rays are the path tracer's (PathTracer::occluded: Embree plus the movable light), from
/// Accel::spawnOrigin, stopping short of the light sample as PathTracer's NEE does.

#include <cstdint>
#include <vector>

#include "core/render/brdf.h"
#include "core/render/path_tracer.h"

namespace rrf {

/// ∫ cosθ dω (steradians) over the area light `l` seen from p, with n the unit receiver normal:
/// Lambert's formula ½ Σ_edges γ_k n·(q_k × q_k+1)/|q_k × q_k+1| over the parallelogram or triangle clipped to
/// the half-space n·(x − p) ≥ 0 (Sutherland–Hodgman), double precision. 0 behind a one-sided light.
/// `centroid` (optional) receives the clipped polygon's vertex mean (p when it is empty).
double projectedSolidAngle(const Light& l, const Vec3& p, const Vec3& n, Vec3* centroid = nullptr);

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
};

class ExactDirect {
public:
    /// `tracer` (its scene, accelerator and movable light) must outlive this. `samples` ≥ 1.
    ExactDirect(const PathTracer& tracer, int samples, uint64_t seed);

    /// Direct radiance leaving the surface point p of object `object` towards wo (unit), with n the
    /// unit normal on wo's side, the movable light as `movable` (PathTracer::movableLightAt) and
    /// `pixel` the random-number stream. May be non-finite only for non-finite input.
    Vec3 radiance(const Vec3& p, const Vec3& n, const Vec3& wo, int object, const Light& movable, uint64_t pixel,
                  TraceCounters& counters) const;

    int samples() const { return samples_; }
    /// seed' above: the key the GLSL path is given.
    uint64_t streamSeed() const { return seed_; }

private:
    bool visible(const Vec3& p, const Vec3& n, const Vec3& target, const Light& movable, TraceCounters& c) const;

    const PathTracer& tracer_;
    int samples_;
    uint64_t seed_;
    SampleGrid grid_;
    std::vector<Brdf> brdfs_;  ///< per material
};

}  // namespace rrf
