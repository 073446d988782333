#pragma once
/// Uncertainty without a reference: an ensemble's members' spread (core/predict/member_spread.h)
/// as a per-pixel map, and how well it ranks the true error where a reference exists
/// (docs/design.md §14d).
///
///  - Relative spread of a pixel: mean_c sd_c / (|pred_c| + 0.01), the relative error's form
///    (core/eval/error_metrics.h) with the prediction in the reference's place, since a moved light
///    has no reference.
///  - Against a reference, per object and over all objects (the pixels the footprint mask keeps
///    whose spread is known): Spearman's rank correlation between the relative spread and the
///    relative error mean_c |d_c| / (|ref_c| + 0.01). 1: the spread orders the pixels exactly as
///    their error does; 0: it says nothing about which pixels are wrong. The error is against a
///    Monte Carlo reference, whose own noise is error the spread cannot predict: a noisy reference
///    lowers the correlation, so it is judged against converged references.
/// The mean relative spread and mean relative error are reported beside it: a spread much smaller
/// than the error means the members agree on a shared mistake (bias), which no ensemble shows.

#include <cstdint>
#include <vector>

#include "core/util/image.h"

namespace rrf {

struct Prediction;

/// Spearman's rank correlation of `a` and `b` (equal lengths): Pearson's correlation of their
/// ranks, tied values taking the mean of their ranks. NaN for fewer than 2 pairs or when either
/// side is constant. Throws std::invalid_argument when the lengths differ.
double spearman(const std::vector<double>& a, const std::vector<double>& b);

/// Relative spread per pixel (all three channels hold it): mean_c sd_c / (|pred_c| + 0.01); 0 where
/// `known` (per pixel, may be empty = all) is 0. Throws std::invalid_argument when sizes differ.
Image relativeSpreadMap(const Image& spread, const Image& prediction, const std::vector<uint8_t>& known);

/// The top of the relative spread's colour scale: the 99th percentile over the pixels `known` marks
/// (every pixel when it is empty), at least 1e-6.
float relativeSpreadScale(const Image& relativeSpread, const std::vector<uint8_t>& known);

/// The spread against the true error over one set of pixels.
struct UncertaintyStats {
    uint64_t pixels = 0;             ///< pixels with a known, finite spread and error
    double meanRelativeSpread = 0;   ///< mean relative spread
    double meanRelativeError = 0;    ///< mean relative error against the reference
    double spearman = 0;             ///< rank correlation; NaN when undefined (null in JSON)
};

/// The uncertainty of a prediction judged against a reference (global term).
struct UncertaintyEvaluation {
    bool available = false;                 ///< the prediction carried a spread
    std::vector<UncertaintyStats> perObject;  ///< by object id
    UncertaintyStats overall;
};

/// The statistics of `prediction`'s spread against `reference` (global images) over `masks`
/// (pixel indices by object) and `covered` (all of them); unavailable when the prediction has no
/// spread.
UncertaintyEvaluation evaluateUncertainty(const Prediction& prediction, const Image& reference,
                                          const std::vector<std::vector<uint32_t>>& masks,
                                          const std::vector<uint32_t>& covered);

}  // namespace rrf
