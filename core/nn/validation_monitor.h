#pragma once
/// What both trainers measure on the validation set after every epoch, and the two stop rules built
/// on it: the error goal and the validation-failure count (docs/design.md §10, "Stopping").
///
/// Targets are Monte Carlo means, so they carry their own noise: with y = t + n, Var(n) = v (the
/// per-record variance of the mean the data generator stores), a prediction p scores
/// E[(p − y)²] = (p − t)² + v. The monitor therefore reports
///   relative RMSE              sqrt(mean (p − y)² / (|y| + ε)²)                 (the error metric's figure)
///   noise-corrected            sqrt(max(0, mean ((p − y)² − v) / (|y| + ε)²))   (the error against the truth)
///   relative noise floor       sqrt(mean v / (|y| + ε)²)                         (a perfect network's score)
/// over every channel of every validation record, ε = kRelativeEpsilon as in core/eval/error_metrics.h.
/// The goal is met when the corrected figure (the plain one when the noise is unknown) is ≤ goal.
///
/// A validation FAILURE is an epoch whose validation loss is above the best epoch's. Between two
/// networks p and b the loss difference Δ = mean w((p − y)² − (b − y)²) contains the noise term
/// −2 mean w (p − b) n, whose standard deviation is σ = 2 sqrt(Σ w² (p − b)² v) / N (w the loss's
/// per-entry weight in raw units, N the entries). A rise Δ ≤ 2σ is "within the noise": it does not
/// count toward max_fail / patience, so noisy targets cannot end training early. Without the
/// variance σ = 0 and every rise counts (Matlab's rule).

#include <cstdint>
#include <limits>

#include "core/nn/mlp.h"
#include "core/nn/training_loss.h"

namespace rrf {

/// How one epoch's validation compares with the best epoch so far.
enum class ValidationOutcome {
    Improved,           ///< lower loss: these weights become the best
    Unchanged,          ///< exactly equal loss
    FailedWithinNoise,  ///< higher loss, but by no more than twice the noise term's standard deviation
    Failed              ///< higher loss beyond the targets' noise
};

/// One epoch's validation figures.
struct ValidationEpoch {
    double loss = std::numeric_limits<double>::quiet_NaN();          ///< mean loss (the trainer's units)
    double relativeRmse = std::numeric_limits<double>::quiet_NaN();  ///< against the noisy targets
    double relativeRmseCorrected = std::numeric_limits<double>::quiet_NaN();  ///< NaN when noise unknown
    ValidationOutcome outcome = ValidationOutcome::Unchanged;
    bool goalReached = false;
};

class ValidationMonitor {
public:
    /// `yNormalised`: validation targets (outputs × N, normalised by `outputScaler`); `variance`: the
    /// raw variance of each target's mean (same shape), or an empty matrix when unknown. `goal` ≤ 0
    /// disables the goal. Throws std::invalid_argument if the variance has another shape or a
    /// negative or non-finite entry.
    ValidationMonitor(AdamLoss loss, const MinMaxScaler& outputScaler, const MatX<float>& yNormalised,
                      const MatX<float>& variance, double goal);

    bool empty() const { return y_.cols() == 0; }
    bool noiseKnown() const { return noiseKnown_; }
    /// sqrt(mean v / (|y| + ε)²); NaN when the noise is unknown or the set is empty.
    double relativeNoiseFloor() const { return noiseFloor_; }

    /// Scores one epoch's predictions (outputs × N, normalised). The first call sets the best;
    /// later calls compare with it and keep the predictions as the best when they improved.
    ValidationEpoch observe(const MatX<double>& predNormalised);
    /// Makes the last observed predictions the best (the trainer keeps weights that met the goal).
    void acceptLastAsBest();
    double bestLoss() const { return bestLoss_; }

private:
    TrainingLoss<double> loss_;
    double goal_;
    MatX<double> y_, yRaw_, var_, weight_;  // weight_: raw per-entry loss weight
    MatX<double> best_, last_;
    bool noiseKnown_ = false, hasBest_ = false;
    double bestLoss_ = std::numeric_limits<double>::infinity(), lastLoss_ = 0;
    double noiseFloor_ = std::numeric_limits<double>::quiet_NaN();
    VecX<double> invScale_, offset_;
};

/// Counts validation failures toward a limit (LM's max_fail, Adam's patience).
///  - An improvement resets the count; a failure within the noise never counts.
///  - `countUnchanged`: whether an epoch with exactly the best loss counts (Adam's patience counts
///    every epoch without improvement; trainlm's max_fail ignores ties).
///  - `countBelowRate`: a failure counts only in an epoch whose step size (Adam's learning rate) is
///    ≤ this value, so early stopping cannot fire while the rate is still high (∞ for LM).
/// `limit` ≤ 0 never stops.
class FailureCounter {
public:
    FailureCounter(int limit, bool countUnchanged, double countBelowRate = std::numeric_limits<double>::infinity())
        : limit_(limit), countUnchanged_(countUnchanged), rateBound_(countBelowRate) {}
    /// Records one epoch; returns true when the count has reached the limit.
    bool update(ValidationOutcome outcome, double rate);
    int count() const { return count_; }
    bool reached() const { return limit_ > 0 && count_ >= limit_; }

private:
    int limit_;
    bool countUnchanged_;
    double rateBound_;
    int count_ = 0;
};

}  // namespace rrf
