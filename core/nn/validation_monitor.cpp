#include "core/nn/validation_monitor.h"

#include <cmath>
#include <stdexcept>

namespace rrf {

ValidationMonitor::ValidationMonitor(AdamLoss loss, const MinMaxScaler& outputScaler, const MatX<float>& yNormalised,
                                     const MatX<float>& variance, double goal)
    : loss_(loss, outputScaler), goal_(goal), y_(yNormalised.cast<double>()) {
    invScale_ = 1.0 / outputScaler.scale.array();
    offset_ = outputScaler.offset;
    // Without validation samples y_ may be 0 x 0, whose rows do not match the scaler's (an Eigen
    // precondition, asserted in the sanitizer build): there is nothing to convert then.
    if (y_.size() > 0) {
        yRaw_ = (y_.array().colwise() * invScale_.array()).matrix();
        yRaw_.colwise() += offset_;
    }
    weight_.resize(y_.rows(), y_.cols());
    for (Eigen::Index j = 0; j < y_.cols(); ++j)
        for (Eigen::Index k = 0; k < y_.rows(); ++k) weight_(k, j) = loss_.rawWeight(k, y_(k, j));
    if (variance.size() > 0) {
        if (variance.rows() != y_.rows() || variance.cols() != y_.cols())
            throw std::invalid_argument("validation: target variance is " + std::to_string(variance.rows()) + " x " +
                                        std::to_string(variance.cols()) + ", targets are " + std::to_string(y_.rows()) +
                                        " x " + std::to_string(y_.cols()));
        if (!variance.allFinite() || (variance.array() < 0.f).any())
            throw std::invalid_argument("validation: target variance must be finite and non-negative");
        var_ = variance.cast<double>();
        noiseKnown_ = true;
        if (y_.size() > 0) {
            const auto denom = (yRaw_.array().abs() + kRelativeEpsilon).square();
            noiseFloor_ = std::sqrt((var_.array() / denom).mean());
        }
    }
}

ValidationEpoch ValidationMonitor::observe(const MatX<double>& pred) {
    ValidationEpoch e;
    if (empty()) return e;
    MatX<double> pRaw = (pred.array().colwise() * invScale_.array()).matrix();
    pRaw.colwise() += offset_;
    const Eigen::ArrayXXd d2 = (pRaw - yRaw_).array().square();
    const Eigen::ArrayXXd relDenom = (yRaw_.array().abs() + kRelativeEpsilon).square();
    const double n = double(y_.size());
    e.loss = (weight_.array() * d2).sum() / n;
    e.relativeRmse = std::sqrt((d2 / relDenom).mean());
    if (noiseKnown_) e.relativeRmseCorrected = std::sqrt(std::max(0.0, ((d2 - var_.array()) / relDenom).mean()));
    const double judged = noiseKnown_ ? e.relativeRmseCorrected : e.relativeRmse;
    e.goalReached = goal_ > 0 && judged <= goal_;

    last_ = pRaw;
    lastLoss_ = e.loss;
    if (!hasBest_) {
        hasBest_ = true;
        best_ = pRaw;
        bestLoss_ = e.loss;
        e.outcome = ValidationOutcome::Improved;
        return e;
    }
    const double delta = e.loss - bestLoss_;
    if (delta < 0) {
        e.outcome = ValidationOutcome::Improved;
        best_ = pRaw;
        bestLoss_ = e.loss;
    } else if (delta == 0) {
        e.outcome = ValidationOutcome::Unchanged;
    } else {
        double sigma = 0;
        if (noiseKnown_) {
            const Eigen::ArrayXXd wd = weight_.array() * (pRaw - best_).array();
            sigma = 2.0 * std::sqrt((wd.square() * var_.array()).sum()) / n;
        }
        e.outcome = delta <= 2.0 * sigma ? ValidationOutcome::FailedWithinNoise : ValidationOutcome::Failed;
    }
    return e;
}

void ValidationMonitor::acceptLastAsBest() {
    if (!hasBest_) return;
    best_ = last_;
    bestLoss_ = lastLoss_;
}

bool FailureCounter::update(ValidationOutcome outcome, double rate) {
    switch (outcome) {
        case ValidationOutcome::Improved: count_ = 0; break;
        case ValidationOutcome::FailedWithinNoise: break;
        case ValidationOutcome::Unchanged:
            if (countUnchanged_ && rate <= rateBound_) ++count_;
            break;
        case ValidationOutcome::Failed:
            if (rate <= rateBound_) ++count_;
            break;
    }
    return reached();
}

}  // namespace rrf
