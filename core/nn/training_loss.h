#pragma once
/// The losses the trainers minimise and compare on the validation set, with their gradient with
/// respect to the network's (normalised) outputs. One definition for Adam's mini-batches, the
/// validation monitor (nn/validation_monitor.h) and the finite-difference test.
///
///   mse          (ŷ − ŷ_ref)²                         normalised [-1, 1] units
///   relative_l2  (p − y)² / (|y| + ε)²,  ε = 0.01       raw units: p, y the raw prediction and target
///   relative_l2_prediction  (p − y)² / (|p̄| + ε)²        p̄ = p held constant (no gradient through it)
///
/// The relative L2 loss is the squared per-channel term of the error metric's relative RMSE
/// (core/eval/error_metrics.h, ε = kRelativeEpsilon), with the target in the denominator as there:
/// minimising it minimises exactly the figure the goal is stated in. (Noise2Noise and Neural Radiance
/// Caching put the prediction in the denominator instead, because their targets are single noisy
/// samples; here a target is a mean of many paths and its noise is measured, so the metric's own
/// weighting is used.) Its weight 1/(|y| + ε)² is a constant per entry, so the loss is an ordinary
/// weighted least-squares problem.
///
/// That weight is biased when targets are noisy: a record whose noise made y small weighs more, so
/// the minimiser over noisy targets y = μ(1 + σz) is E[y·w]/E[w] ≈ μ(1 − 2σ²) — 0.5 % low at the
/// data's 5 % record noise, 2 % at 10 %. relative_l2_prediction puts the prediction in the
/// denominator as a constant (tiny-cuda-nn's RelativeL2, Neural Radiance Caching): its gradient
/// 2(p − y)/(|p̄| + ε)² has expectation 0 at p = E[y], so noisier, cheaper records stay unbiased.
/// The validation monitor weighs by the target (rawWeight) for both relative losses: its loss only
/// ranks epochs, and a weight that moved with the prediction would not rank them on one scale.

#include <algorithm>

#include <Eigen/Dense>

#include "core/nn/mlp.h"
#include "core/nn/trainer_config.h"
#include "core/util/relative_error.h"

namespace rrf {

/// A loss bound to an output scaler (normalised ↔ raw). Scalar type S is float for training and
/// double for tests.
template <typename S>
class TrainingLoss {
public:
    TrainingLoss(AdamLoss kind, const MinMaxScaler& out) : kind_(kind) {
        invScale_ = (1.0 / out.scale.array()).template cast<S>();
        offset_ = out.offset.template cast<S>().array();
    }

    AdamLoss kind() const { return kind_; }

    /// Per-entry weight w of the loss in RAW units, loss entry = w · (p − y)² (p, y raw): for mse
    /// w = scale_k² (the normalisation), for the relative losses w = 1 / (|y| + ε)². `yNormalised` is one
    /// target column's entry k.
    S rawWeight(Eigen::Index k, S yNormalised) const {
        if (kind_ == AdamLoss::Mse) return S(1) / (invScale_[k] * invScale_[k]);
        const S y = yNormalised * invScale_[k] + offset_[k];
        const S d = std::abs(y) + S(kRelativeEpsilon);
        return S(1) / (d * d);
    }

    /// Sum of the per-entry losses of `pred` against `y` (both normalised, outputs × N). When `dOut`
    /// is given it receives ∂(sum / count)/∂pred, so mlpBackward's summed gradient is the gradient
    /// of the mean over `count` entries.
    double evaluate(const MatX<S>& pred, const Eigen::Ref<const MatX<S>>& y, MatX<S>* dOut, double count) const {
        if (kind_ == AdamLoss::Mse) {
            const MatX<S> d = pred - y;
            if (dOut) *dOut = d * S(2.0 / count);
            return double(d.template cast<double>().squaredNorm());
        }
        // Raw difference (p − y) = (ŷ − ŷ_ref)/scale; raw target y = ŷ_ref/scale + offset.
        using ArrayS = Eigen::Array<S, Eigen::Dynamic, Eigen::Dynamic>;
        const ArrayS diff = (pred - y).array().colwise() * invScale_;
        const ArrayS yRaw = y.array().colwise() * invScale_ + offset_.replicate(1, y.cols());
        const ArrayS denom = kind_ == AdamLoss::RelativeL2
                                 ? ArrayS((yRaw.abs() + S(kRelativeEpsilon)).square())
                                 : ArrayS(((pred.array().colwise() * invScale_ + offset_.replicate(1, pred.cols())).abs() +
                                           S(kRelativeEpsilon))
                                              .square());
        // The denominator is a constant of the gradient in both relative losses.
        // ∂/∂ŷ of diff²/denom = 2 diff/denom · ∂diff/∂ŷ = 2 diff/denom · (1/scale).
        if (dOut) *dOut = ((diff / denom).colwise() * invScale_ * S(2.0 / count)).matrix();
        return (diff.square() / denom).template cast<double>().sum();
    }

private:
    AdamLoss kind_;
    Eigen::Array<S, Eigen::Dynamic, 1> invScale_, offset_;
};

/// Targets for relative_l2 without its noise bias (AdamConfig::debiasTargets). With y = μ + n,
/// Var(n) = v and w(y) = 1/(|y| + ε)², w(μ + n) ≈ w(μ)(1 − 2 sgn(μ) n/(|μ| + ε) + …), so the minimiser
/// Σ w y / Σ w of the loss over a record's noise sits at μ − 2 sgn(μ) v/(|μ| + ε) to first order
/// (−2σ²μ for relative noise σ ≫ ε/μ). Each target raised by its own 2 sgn(y) v/(|y| + ε) moves that
/// minimiser back to μ; what remains is of order σ⁴. The expansion needs σ ≪ 1: a record whose relative
/// variance v/(|y| + ε)² exceeds kDebiasMaxRelativeVariance (σ > 0.5, a few paths and one bright one)
/// is raised as if it had that variance, at most by half its value, so an outlier's own estimate of
/// its noise cannot triple it. `y` raw targets (outputs × N), `variance` the variance of each one's
/// Monte Carlo mean, same shape (entries ≤ 0 or NaN: unknown, left as they are). The validation
/// figures of a network trained on these targets are measured against them too (a difference of order
/// σ⁴ from the plain targets); its reported RMSEs (ModelErrors) against the records as they are.
/// On the Cornell box the plain targets left the networks' light on the ceiling visibly low at the
/// records' noise, and these targets removed most of that bias (docs/results-history.md, "The best
/// preset").
constexpr float kDebiasMaxRelativeVariance = 0.25f;
inline MatX<float> debiasedRelativeL2Targets(const Eigen::Ref<const MatX<float>>& y, const Eigen::Ref<const MatX<float>>& variance) {
    MatX<float> out = y;
    for (Eigen::Index i = 0; i < y.size(); ++i) {
        const float t = y.data()[i], d = std::abs(t) + float(kRelativeEpsilon);
        const float v = std::min(variance.data()[i], kDebiasMaxRelativeVariance * d * d);
        if (!(v > 0.f)) continue;
        out.data()[i] = t + (t < 0.f ? -2.f : 2.f) * v / d;
    }
    return out;
}

}  // namespace rrf
