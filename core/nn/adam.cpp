// Adam training on shuffled mini-batches, in float (see core/nn/trainer.h).
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "core/nn/trainer.h"
#include "core/util/rng.h"

namespace rrf {

namespace {

constexpr uint64_t kShuffleStream = 0x5348554646000000ULL;  // "SHUFF"
constexpr Eigen::Index kEvalChunk = 4096;
constexpr Eigen::Index kPrefetch = 8;
constexpr double kPi = 3.14159265358979323846;

double learningRate(const AdamConfig& c, int epoch /* 1-based */) {
    switch (c.schedule) {
        case LrSchedule::Constant: return c.learningRate;
        case LrSchedule::Step: return c.learningRate * std::pow(c.stepGamma, double((epoch - 1) / c.stepEpochs));
        case LrSchedule::Cosine:
        default: {
            const double t = c.maxEpochs > 1 ? double(epoch - 1) / double(c.maxEpochs - 1) : 0.0;
            return c.minLearningRate + 0.5 * (c.learningRate - c.minLearningRate) * (1.0 + std::cos(kPi * t));
        }
    }
}

/// Loss and ∂loss/∂pred of one batch (normalised units in, `dOut` scaled by 1/count so the summed
/// gradient of mlpBackward is the gradient of the mean).
class Loss {
public:
    Loss(AdamLoss kind, const MinMaxScaler& out) : kind_(kind) {
        invScale_ = (1.0 / out.scale.array()).cast<float>();
        offset_ = out.offset.cast<float>().array();
    }

    /// Returns the SUM of per-entry losses; fills dOut with the gradient of sum / `count`.
    double evaluate(const MatX<float>& pred, const Eigen::Ref<const MatX<float>>& y, MatX<float>* dOut,
                    double count) const {
        if (kind_ == AdamLoss::Mse) {
            const MatX<float> d = pred - y;
            if (dOut) *dOut = d * float(2.0 / count);
            return double(d.cast<double>().squaredNorm());
        }
        // Relative L2 in raw units: e = (p − y)/s, denominator uses the raw prediction as a constant.
        const Eigen::ArrayXXf diff = (pred - y).array().colwise() * invScale_;
        const Eigen::ArrayXXf raw = pred.array().colwise() * invScale_ + offset_.replicate(1, pred.cols());
        const Eigen::ArrayXXf denom = raw.square() + 0.01f;
        if (dOut) *dOut = ((diff / denom).colwise() * invScale_ * float(2.0 / count)).matrix();
        return (diff.square() / denom).cast<double>().sum();
    }

private:
    AdamLoss kind_;
    Eigen::ArrayXf invScale_, offset_;
};

/// Mean loss over a whole (validation or test) set, chunked to bound memory.
double meanLoss(const MlpArch& arch, const VecX<float>& w, const Loss& loss, const Eigen::Ref<const MatX<float>>& x,
                const Eigen::Ref<const MatX<float>>& y, std::vector<MatX<float>>& acts) {
    if (x.cols() == 0) return std::numeric_limits<double>::quiet_NaN();
    double sum = 0;
    for (Eigen::Index c = 0; c < x.cols(); c += kEvalChunk) {
        const Eigen::Index nc = std::min(kEvalChunk, x.cols() - c);
        mlpForward<float>(arch, w.data(), x.middleCols(c, nc), acts);
        sum += loss.evaluate(acts.back(), y.middleCols(c, nc), nullptr, 1.0);
    }
    return sum / (double(x.cols()) * double(y.rows()));
}

}  // namespace

TrainResult trainAdam(const MlpArch& arch, const AdamConfig& cfg, const TrainingData& data,
                      const MinMaxScaler& outputScaler, VecX<double>& params, const TrainObserver& observer) {
    arch.validate();
    const Eigen::Index P = arch.numParams();
    if (params.size() != P) throw std::invalid_argument("adam: parameter vector has the wrong size");
    if (data.xTrain.cols() == 0) throw std::invalid_argument("adam: no training samples");
    if (outputScaler.size() != arch.outputs) throw std::invalid_argument("adam: output scaler size mismatch");
    const auto t0 = std::chrono::steady_clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };

    TrainResult res;
    res.trainSamples = data.xTrain.cols();
    res.validationSamples = data.xValidation.cols();
    res.testSamples = data.xTest.cols();
    Eigen::Index n = data.xTrain.cols();
    if (cfg.maxSamples > 0 && n > cfg.maxSamples) {
        n = Eigen::Index(cfg.maxSamples);
        const std::string m = "adam: training on a random subsample of " + std::to_string(n) + " of " +
                              std::to_string(data.xTrain.cols()) + " training samples (max_samples)";
        res.messages.push_back(m);
        if (observer.onMessage) observer.onMessage(m);
    }
    res.trainSamplesUsed = n;

    const Loss loss(cfg.loss, outputScaler);
    const bool hasVal = data.xValidation.cols() > 0;
    VecX<float> w = params.cast<float>(), best = w, grad(P), m = VecX<float>::Zero(P), v = VecX<float>::Zero(P);
    // Decoupled weight decay applies to weight matrices only; shrinking biases would shift outputs.
    VecX<float> decayMask = VecX<float>::Zero(P);
    for (int l = 0; l < arch.numLayers(); ++l)
        decayMask.segment(arch.weightOffset(l), arch.biasOffset(l) - arch.weightOffset(l)).setOnes();

    std::vector<MatX<float>> acts, deltas;
    const Eigen::Index B = std::min<Eigen::Index>(cfg.batchSize, n);
    MatX<float> xb(arch.inputs, B), yb(arch.outputs, B), dOut;
    std::vector<uint32_t> order(static_cast<size_t>(n));
    std::iota(order.begin(), order.end(), 0u);

    double bestVal = std::numeric_limits<double>::infinity();
    {
        const double tl = meanLoss(arch, w, loss, data.xTrain.leftCols(n), data.yTrain.leftCols(n), acts);
        const double vl = meanLoss(arch, w, loss, data.xValidation, data.yValidation, acts);
        if (hasVal) bestVal = vl;
        res.history.push_back({0, tl, vl, learningRate(cfg, 1), elapsed()});
        if (observer.onEpoch) observer.onEpoch(res.history.back());
    }

    int64_t step = 0;
    int sinceBest = 0;
    const float b1 = float(cfg.beta1), b2 = float(cfg.beta2);
    for (int epoch = 1;; ++epoch) {
        if (epoch > cfg.maxEpochs) { res.stopReason = "maximum epoch reached"; break; }
        if (hasVal && cfg.patience > 0 && sinceBest >= cfg.patience) { res.stopReason = "validation stop"; break; }
        if (observer.cancelled()) {
            res.stopReason = "cancelled";
            res.cancelled = true;
            break;
        }
        const double lr = learningRate(cfg, epoch);
        // A fresh permutation per epoch, keyed by (seed, epoch): independent of everything else.
        Rng rng(cfg.seed, kShuffleStream, uint64_t(epoch));
        for (size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[rng.uniformInt(uint32_t(i))]);

        double epochLoss = 0;
        for (Eigen::Index b0 = 0; b0 < n; b0 += B) {
            const Eigen::Index nb = std::min(B, n - b0);
            xb.resize(arch.inputs, nb);
            yb.resize(arch.outputs, nb);
            for (Eigen::Index j = 0; j < nb; ++j) {
                // Shuffled columns are cache misses; fetching a few ahead hides most of the latency.
                if (j + kPrefetch < nb) {
                    const Eigen::Index ahead = order[size_t(b0 + j + kPrefetch)];
                    __builtin_prefetch(data.xTrain.col(ahead).data());
                    __builtin_prefetch(data.yTrain.col(ahead).data());
                }
                const Eigen::Index src = order[size_t(b0 + j)];
                xb.col(j) = data.xTrain.col(src);
                yb.col(j) = data.yTrain.col(src);
            }
            mlpForward<float>(arch, w.data(), xb, acts);
            epochLoss += loss.evaluate(acts.back(), yb, &dOut, double(nb) * arch.outputs);
            mlpBackward<float>(arch, w.data(), xb, acts, dOut, deltas, grad.data());

            ++step;
            const float c1 = float(1.0 - std::pow(cfg.beta1, double(step)));
            const float c2 = float(1.0 - std::pow(cfg.beta2, double(step)));
            m = b1 * m + (1.0f - b1) * grad;
            v = b2 * v + (1.0f - b2) * grad.cwiseAbs2();
            const float lrf = float(lr);
            w.array() -= lrf * ((m.array() / c1) / ((v.array() / c2).sqrt() + float(cfg.epsilon)) +
                                float(cfg.weightDecay) * decayMask.array() * w.array());
        }
        const double trainLoss = epochLoss / (double(n) * arch.outputs);
        const double vl = meanLoss(arch, w, loss, data.xValidation, data.yValidation, acts);
        if (!w.allFinite()) {
            // Divergence (e.g. a learning rate far too high): keep the best finite weights.
            res.stopReason = "diverged (non-finite weights)";
            w = best;
            res.epochs = epoch;
            break;
        }
        if (hasVal) {
            if (vl < bestVal) {
                bestVal = vl;
                best = w;
                res.bestEpoch = epoch;
                sinceBest = 0;
            } else {
                ++sinceBest;
            }
        }
        res.epochs = epoch;
        res.history.push_back({epoch, trainLoss, vl, lr, elapsed()});
        if (observer.onEpoch) observer.onEpoch(res.history.back());
    }

    if (hasVal) w = best;
    else if (res.stopReason.rfind("diverged", 0) != 0) res.bestEpoch = res.epochs;
    params = w.cast<double>();
    res.trainLoss = meanLoss(arch, w, loss, data.xTrain, data.yTrain, acts);
    res.validationLoss = meanLoss(arch, w, loss, data.xValidation, data.yValidation, acts);
    res.testLoss = meanLoss(arch, w, loss, data.xTest, data.yTest, acts);
    res.seconds = elapsed();
    return res;
}

}  // namespace rrf
