#pragma once
/// Glossy gather (docs/design.md §13, "Glossy gather"): the indirect light of a sharply glossy surface is traced one
/// bounce further and taken from the radiance regression functions where those rays land, instead of
/// being asked of the surface's own network.
///
/// Why: the indirect light leaving a near-mirror is the scene's lit image seen in the mirror direction,
///     L_ind(x, ωo) = ∫ f(x, ωo, ωi) L(y(x, ωi), −ωi) cosθi dωi,
/// a function of (x, ωo, light) with every edge and shadow of the scene in it, which a small network
/// cannot fit (docs/results.md), while the radiance L at the secondary point y is what the rest of the
/// prediction already does well: exact direct light plus y's network. This is the path termination of
/// Neural Radiance Caching (Müller et al. 2021) after one bounce: query the cache where the footprint
/// is wide, not where the lobe is sharp.
///
/// Estimator, per pixel x of an object whose material is Phong with exponent ≥ min_exponent (or
/// that "objects" names):
///   L_ind(x) ≈ 1/Ns Σ_s ks (e+2)/(e+1) cosθ_s · L(y_s)  +  1/Nd Σ_d kd · L(y_d)
/// with ω_s drawn from the Phong lobe around the mirror direction and ω_d from the cosine hemisphere
/// (each lobe sampled on its own, so both terms are exact in expectation and the diffuse part's noise
/// does not ride on the sharp lobe's samples), each lobe's (u, v) on a jittered grid shifted per pixel
/// (Cranley–Patterson), as exact direct light does. L(y) = direct light at y towards x (exact, with
/// `direct_samples` light samples; the direct network under "direct": "network") + y's indirect
/// network, or y's own gather when y is on a gathered object (one level); a ray that reaches an emitter or escapes
/// adds nothing (light seen directly is x's direct term). Lobe samples below the surface add nothing.
///
/// Random numbers: sample k of pixel i draws from Rng(seed', i, k), its shift from
/// Rng(seed', i, kShiftSample), seed' = mix64(seed ^ kGlossyGatherStream): the same image for any
/// thread count. The secondary points are keyed by their index in their batch, under a seed of
/// their own per (level, object, batch) (Predictor::gather).

#include <cstdint>
#include <vector>

#include "core/predict/gbuffer.h"
#include "core/predict/glossy_caustics.h"
#include "core/predict/prediction_settings.h"
#include "core/render/brdf.h"
#include "core/render/path_tracer.h"
#include "core/util/image.h"

namespace rrf {

/// The stream id mixed into the prediction seed for the gather's directions ("GATHERGL").
constexpr uint64_t kGlossyGatherStream = 0x474154484552474CULL;

/// True if `settings` gather the indirect light of at least one object of `scene`.
bool gatherApplies(const Scene& scene, const PredictionSettings& settings);

class GlossyGather {
public:
    /// `tracer` must outlive this. `lobeSamples`, `diffuseSamples` ≥ 0 (0 drops that lobe's term).
    GlossyGather(const PathTracer& tracer, const RecordLayout& layout, int lobeSamples, int diffuseSamples,
                 uint64_t seed);

    /// True for materials the exponent rule gathers: Phong with exponent ≥ minExponent (> 0).
    static bool applies(const Material& m, float minExponent) {
        return minExponent > 0.f && m.type == Material::Type::Phong && m.exponent >= minExponent;
    }
    /// True if `settings` gather object `o` of `scene`: by its material's exponent, or by name
    /// ("gather": {"objects": [...]}, e.g. a diffuse receiver of caustics).
    static bool gathers(const Scene& scene, const Object& o, const PredictionSettings& settings);

    /// The secondary rays of `count` pixels of `gb` (their indices in `pixels`): raysPerPixel() per
    /// pixel, pixel j's at [j·raysPerPixel(), (j+1)·raysPerPixel()), with the weight each one's
    /// radiance gets (f·cosθ/pdf over the lobe's sample count; 0 for a direction below the surface).
    struct Batch {
        GBuffer secondary;           ///< what the rays hit (buildGBufferFromRays)
        std::vector<Vec3> weight;    ///< per ray
    };
    /// With `caustics`, the cosine rays that land on a caster leave out its glossy direct light
    /// (GBuffer::directWithoutGloss): GlossyCaustics carries it.
    Batch trace(const GBuffer& gb, const uint32_t* pixels, size_t count, const GlossyCaustics* caustics = nullptr) const;

    /// L_ind of pixel j of the batch from the radiance towards it at each secondary sample
    /// (`radiance`: the secondary prediction's global image, width = rays); emitter and background
    /// samples count 0.
    Vec3 gathered(const Batch& b, const Image& radiance, size_t j) const;

    int raysPerPixel() const { return lobeSamples_ + diffuseSamples_; }

private:
    const PathTracer& tracer_;
    const RecordLayout& layout_;
    int lobeSamples_, diffuseSamples_;
    uint64_t seed_;
};

}  // namespace rrf
