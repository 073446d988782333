#pragma once
/// The noise of a Monte Carlo reference, measured as the evaluation measures errors against it
/// (docs/design.md §14): the RMSE and relative RMSE noise floors of core/eval/error_metrics.h — the
/// error a perfect prediction is expected to show against this reference — over the pixels of a
/// footprint mask. This is the one convergence figure of a render: the reference store renders until
/// it is small enough (core/eval/reference_store.h) and the workbench's render status shows it. (The
/// standard error of the image mean is not one: it averages the noise away and reads as "converged"
/// on a visibly noisy image.) core/eval/reference_noise_json.h writes and reads it.

#include "core/eval/evaluation.h"
#include "core/predict/footprint_mask.h"
#include "core/util/image.h"

namespace rrf {

/// Noise floors per term (index int(Term)); NaN where the term's variance is unknown.
struct ReferenceNoise {
    double rmse[kTermCount];
    double relativeRmse[kTermCount];
    ReferenceNoise();
};

/// Relative RMSE noise floor, sqrt(mean v / (|ref| + 0.01)²), of `image` with per-pixel variance of
/// the mean `variance` over the pixels in `mask` (all channels); NaN when `variance` is empty or the
/// mask keeps no finite pixel.
double relativeNoiseFloor(const Image& image, const Image& variance, const std::vector<uint32_t>& mask);

/// The noise floors of every term of `reference` over the pixels `mask` keeps (mask.kept).
ReferenceNoise referenceNoise(const Reference& reference, const FootprintMask& mask);

}  // namespace rrf
