#pragma once
/// FLIP figures of an evaluation (core/eval/flip.h for the method): HDR-FLIP of the prediction's
/// global term against the reference's, over the exposure range of the reference alone (so every
/// model judged against one reference is judged at the same exposures), LDR-FLIP of the same images
/// as the display shows them at exposure 0, pooled like the other figures: over the object pixels the
/// footprint mask keeps, overall and per object.
///
/// FLIP has no noise correction (it is not a mean of squares), so its noise floor is measured: the
/// HDR-FLIP of the reference against the reference plus one draw of its own noise (Gaussian with the
/// per-pixel variance of the mean, a counter-based stream keyed by pixel and channel). A perfect
/// prediction against the noisy reference differs from it by the reference's noise, which this draw
/// imitates; a model's FLIP near that figure is at the limit the reference can judge. Unknown (NaN)
/// when the reference has no variance.
///
/// Only the global term: the direct and indirect terms are parts of an image nobody looks at alone,
/// and a perceptual metric is about what is seen. core/eval/flip_evaluation_json.h writes the figures.

#include <cstdint>
#include <vector>

#include "core/eval/error_metrics.h"
#include "core/eval/flip.h"

namespace rrf {

struct Evaluation;
struct Reference;

/// The FLIP figures of one evaluation (global term).
struct FlipEvaluation {
    bool available = false;          ///< computed (the global term was predicted and flipEvaluation ran)
    FlipSettings settings;           ///< the viewing conditions (pixels per degree)
    FlipExposureRange range;         ///< HDR-FLIP's exposures, from the reference's global image
    Image hdrMap;                    ///< HDR-FLIP per pixel, in [0, 1] (NaN where an input is non-finite)
    Image ldrMap;                    ///< LDR-FLIP per pixel at exposure 0
    FlipStats hdr;                   ///< HDR-FLIP over the kept object pixels
    FlipStats ldr;                   ///< LDR-FLIP over the kept object pixels
    std::vector<FlipStats> hdrPerObject;  ///< index = object id (pixels = 0 out of view)
    /// Mean HDR-FLIP of the reference against itself plus one draw of its noise, over the same
    /// pixels; NaN (unknown) without the reference's variance.
    double hdrNoiseFloor = ErrorStats::kUnknownNoise;
    double seconds = 0.0;            ///< time the FLIP figures took
};

/// One channel's Gaussian draw for pixel `pixel`, channel `c` (mean 0, variance 1): Box-Muller on
/// the counter-based stream (seed, pixel, c), a pure function of its arguments.
float flipNoiseNormal(uint64_t seed, uint64_t pixel, int c);

/// `image` plus one draw of Gaussian noise of per-pixel, per-channel variance `variance` (same size;
/// non-finite or negative variances add nothing), keyed by `seed`. Throws std::invalid_argument for
/// differing sizes.
Image withDrawnNoise(const Image& image, const Image& variance, uint64_t seed);

/// The FLIP figures of `e` (its prediction and footprint mask) against `reference` (the one `e` was
/// evaluated against); not available when the global term was not predicted.
FlipEvaluation flipEvaluation(const Evaluation& e, const Reference& reference, const FlipSettings& settings = {});

}  // namespace rrf
