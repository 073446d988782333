#pragma once
/// Held-out light positions (docs/design.md §15): evaluation at K light positions drawn
/// from the light region on a random stream that the data generator never uses, and the spread
/// (mean, min, max) of the errors across them — the generalisation a user cares about.
/// core/eval/held_out_json.h writes the summary.

#include <cstdint>
#include <string>
#include <vector>

#include "core/eval/evaluation.h"

namespace rrf {

/// K positions uniform in `region` (a single point when the region is empty or degenerate in an
/// axis), a pure function of (region, k, seed). The stream is domain-separated from the generator's
/// record stream, so for the same seed these are not the training positions.
std::vector<Vec3> heldOutLightPositions(const Bounds3& region, int k, uint64_t seed);

struct Spread {
    double mean = 0, min = 0, max = 0;
    int count = 0;  ///< evaluations that had the figure (object visible; for noise figures: noise known)
    void add(double v);
    /// Mean, or NaN (an unknown figure, "unknown" in tables) when no evaluation had it.
    double meanOrUnknown() const { return count ? mean : ErrorStats::kUnknownNoise; }
};

/// Spread of RMSE and relative RMSE per term, per object and overall, across evaluations, each with
/// the spread of the references' noise floor and of the noise-corrected figure (over the evaluations
/// whose reference noise was known).
struct HeldOutSummary {
    struct Row {
        Spread rmse, relativeRmse;
        Spread rmseNoiseFloor, rmseCorrected, relativeRmseNoiseFloor, relativeRmseCorrected;
        void add(const ErrorStats& s);
    };
    bool available[kTermCount] = {true, true, true};
    std::vector<Row> perObject[kTermCount];  ///< index = object id
    Row overall[kTermCount];
    /// FLIP of the global term over all kept object pixels (core/eval/flip_evaluation.h), over the
    /// evaluations that computed it: HDR-FLIP mean, its noise floor (where the noise was known) and
    /// LDR-FLIP mean.
    Spread flipHdr, flipHdrNoiseFloor, flipLdr;
    /// The ensemble spread's rank correlation with the true error (core/eval/uncertainty.h) per
    /// object id and over all objects, across the evaluations whose prediction had a spread.
    std::vector<Spread> spearmanPerObject;
    Spread spearman;
};

HeldOutSummary summarizeHeldOut(const std::vector<Evaluation>& evaluations, size_t objectCount);
/// Fixed-width table: term, object, K, relative RMSE mean/min/max, its noise floor (mean), its
/// corrected value mean/min/max, then RMSE mean/min/max, noise floor and corrected (means); then a
/// line of the FLIP spread when the evaluations had FLIP figures.
std::string heldOutTable(const Scene& scene, const HeldOutSummary& s);

}  // namespace rrf
