// Adam training on shuffled mini-batches, in float (see core/nn/trainer.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "core/nn/adam_step.h"
#include "core/nn/trainers/sparse_adam.h"
#include "core/nn/trainer.h"
#include "core/nn/training_loss.h"
#include "core/util/rng.h"

namespace rrf {

namespace {

constexpr uint64_t kShuffleStream = 0x5348554646000000ULL;  // "SHUFF"
constexpr Eigen::Index kEvalChunk = 4096;
constexpr Eigen::Index kPrefetch = 8;
constexpr double kPiDouble = 3.14159265358979323846;  // vec3.h's kPi is a float

/// The network from its normalised inputs: the input encoding with its parameters `e` (unless it is
/// the identity, whose inputs go to the MLP unchanged), then the MLP with weights `w`.
struct EncodedNetwork {
    const MlpArch& arch;
    const InputEncoding& encoding;
    MatX<float> features;  ///< the last forward's encoded inputs (unused for the identity)

    bool encoded() const { return !encoding.isIdentity(); }
    /// Forward pass; `acts` as mlpForward. Returns what the MLP read (x itself for the identity).
    Eigen::Ref<const MatX<float>> forward(const VecX<float>& w, const VecX<float>& e, const Eigen::Ref<const MatX<float>>& x,
                                          std::vector<MatX<float>>& acts) {
        if (!encoded()) {
            mlpForward<float>(arch, w.data(), x, acts);
            return x;
        }
        encoding.forward<float>(e.data(), x, features);
        mlpForward<float>(arch, w.data(), features, acts);
        return features;
    }
};

/// Mean loss over a whole (validation or test) set, chunked to bound memory.
double meanLoss(EncodedNetwork& net, const VecX<float>& w, const VecX<float>& e, const TrainingLoss<float>& loss,
                const Eigen::Ref<const MatX<float>>& x, const Eigen::Ref<const MatX<float>>& y, std::vector<MatX<float>>& acts) {
    if (x.cols() == 0) return std::numeric_limits<double>::quiet_NaN();
    double sum = 0;
    for (Eigen::Index c = 0; c < x.cols(); c += kEvalChunk) {
        const Eigen::Index nc = std::min(kEvalChunk, x.cols() - c);
        net.forward(w, e, x.middleCols(c, nc), acts);
        sum += loss.evaluate(acts.back(), y.middleCols(c, nc), nullptr, 1.0);
    }
    return sum / (double(x.cols()) * double(y.rows()));
}

/// Network outputs (normalised) on `x`, in double for the validation monitor.
MatX<double> predictions(EncodedNetwork& net, const VecX<float>& w, const VecX<float>& e, const MatX<float>& x,
                         std::vector<MatX<float>>& acts) {
    MatX<double> out(net.arch.outputs, x.cols());
    for (Eigen::Index c = 0; c < x.cols(); c += kEvalChunk) {
        const Eigen::Index nc = std::min(kEvalChunk, x.cols() - c);
        net.forward(w, e, x.middleCols(c, nc), acts);
        out.middleCols(c, nc) = acts.back().cast<double>();
    }
    return out;
}

}  // namespace

double adamLearningRate(const AdamConfig& c, int epoch) {
    switch (c.schedule) {
        case LrSchedule::Constant: return c.learningRate;
        case LrSchedule::Step: return c.learningRate * std::pow(c.stepGamma, double((epoch - 1) / c.stepEpochs));
        case LrSchedule::Cosine:
        default: {
            const double t = c.maxEpochs > 1 ? double(epoch - 1) / double(c.maxEpochs - 1) : 0.0;
            return c.minLearningRate + 0.5 * (c.learningRate - c.minLearningRate) * (1.0 + std::cos(kPiDouble * t));
        }
    }
}

TrainResult trainAdam(const MlpArch& arch, const AdamConfig& cfg, const TrainingData& data,
                      const MinMaxScaler& outputScaler, VecX<double>& params, const TrainObserver& observer) {
    VecX<double> none;
    return trainAdam(arch, InputEncoding(), cfg, data, outputScaler, params, none, observer);
}

TrainResult trainAdam(const MlpArch& arch, const InputEncoding& encoding, const AdamConfig& cfg, const TrainingData& data,
                      const MinMaxScaler& outputScaler, VecX<double>& params, VecX<double>& encodingParams,
                      const TrainObserver& observer) {
    arch.validate();
    const Eigen::Index P = arch.numParams();
    if (params.size() != P) throw std::invalid_argument("adam: parameter vector has the wrong size");
    EncodedNetwork net{arch, encoding, {}};
    const Eigen::Index inputs = net.encoded() ? encoding.scaledInputs() : arch.inputs;
    const Eigen::Index E = net.encoded() ? Eigen::Index(encoding.numParams()) : 0;
    if (net.encoded() && encoding.outputs() != arch.inputs)
        throw std::invalid_argument("adam: the encoding writes " + std::to_string(encoding.outputs()) +
                                    " features, the network reads " + std::to_string(arch.inputs));
    if (encodingParams.size() != E) throw std::invalid_argument("adam: encoding parameter vector has the wrong size");
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

    res.errorGoal = cfg.errorGoal;
    const TrainingLoss<float> loss(cfg.loss, outputScaler);
    const bool hasVal = data.xValidation.cols() > 0;
    ValidationMonitor monitor(cfg.loss, outputScaler, data.yValidation, data.vValidation, cfg.errorGoal);
    // Patience counts only once the rate has decayed (the rate bound is relative to the peak rate).
    FailureCounter patience(cfg.patience, /*countUnchanged=*/true, cfg.patienceLrFraction * cfg.learningRate);
    auto figure = [](const ValidationEpoch& v) {
        return std::isnan(v.relativeRmseCorrected) ? v.relativeRmse : v.relativeRmseCorrected;
    };
    VecX<float> w = params.cast<float>(), best = w, grad(P), m = VecX<float>::Zero(P), v = VecX<float>::Zero(P);
    VecX<float> e = encodingParams.cast<float>(), bestE = e;
    SparseAdam encodingAdam(E);
    MatX<float> dFeatures;
    // Decoupled weight decay applies to weight matrices only; shrinking biases would shift outputs.
    VecX<float> decayMask = VecX<float>::Zero(P);
    for (int l = 0; l < arch.numLayers(); ++l)
        decayMask.segment(arch.weightOffset(l), arch.biasOffset(l) - arch.weightOffset(l)).setOnes();

    std::vector<MatX<float>> acts, deltas;
    const Eigen::Index B = std::min<Eigen::Index>(cfg.batchSize, n);
    MatX<float> xb(inputs, B), yb(arch.outputs, B), dOut;
    std::vector<uint32_t> order(static_cast<size_t>(n));
    std::iota(order.begin(), order.end(), 0u);

    bool goalReached = false;
    {
        const double tl = meanLoss(net, w, e, loss, data.xTrain.leftCols(n), data.yTrain.leftCols(n), acts);
        ValidationEpoch v;
        if (hasVal) v = monitor.observe(predictions(net, w, e, data.xValidation, acts));
        goalReached = v.goalReached;
        EpochRecord r{0, tl, v.loss, adamLearningRate(cfg, 1), elapsed()};
        r.validationRelativeRmse = figure(v);
        res.history.push_back(r);
        if (observer.onEpoch) observer.onEpoch(res.history.back());
    }

    int64_t step = 0;
    const float b1 = float(cfg.beta1), b2 = float(cfg.beta2);
    for (int epoch = 1;; ++epoch) {
        if (goalReached) { res.stopReason = "error goal reached"; break; }
        if (epoch > cfg.maxEpochs) { res.stopReason = "maximum epoch reached"; break; }
        if (hasVal && patience.reached()) { res.stopReason = "validation stop"; break; }
        if (observer.cancelled()) {
            res.stopReason = "cancelled";
            res.cancelled = true;
            break;
        }
        const double lr = adamLearningRate(cfg, epoch);
        // A fresh permutation per epoch, keyed by (seed, epoch): independent of everything else.
        Rng rng(cfg.seed, kShuffleStream, uint64_t(epoch));
        for (size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[rng.uniformInt(uint32_t(i))]);

        double epochLoss = 0;
        for (Eigen::Index b0 = 0; b0 < n; b0 += B) {
            const Eigen::Index nb = std::min(B, n - b0);
            xb.resize(inputs, nb);
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
            const Eigen::Ref<const MatX<float>> mlpIn = net.forward(w, e, xb, acts);
            epochLoss += loss.evaluate(acts.back(), yb, &dOut, double(nb) * arch.outputs);
            mlpBackward<float>(arch, w.data(), mlpIn, acts, dOut, deltas, grad.data(), E > 0 ? &dFeatures : nullptr);
            if (E > 0) encoding.backwardParams<float>(e.data(), xb, dFeatures, encodingAdam.grad.data(), &encodingAdam.touched);

            ++step;
            const float c1 = float(1.0 - std::pow(cfg.beta1, double(step)));
            const float c2 = float(1.0 - std::pow(cfg.beta2, double(step)));
            const float lrf = float(lr);
            adamStep({b1, b2, c1, c2, lrf, float(cfg.epsilon), float(cfg.weightDecay)}, grad, decayMask, w, m, v);
            if (E > 0) encodingAdam.step(e, b1, b2, lrf, float(cfg.epsilon));
        }
        const double trainLoss = epochLoss / (double(n) * arch.outputs);
        if (!w.allFinite() || !e.allFinite()) {
            // Divergence (e.g. a learning rate far too high): keep the best finite weights.
            res.stopReason = "diverged (non-finite weights)";
            w = best;
            e = bestE;
            res.epochs = epoch;
            break;
        }
        ValidationEpoch v;
        if (hasVal) {
            v = monitor.observe(predictions(net, w, e, data.xValidation, acts));
            if (v.outcome == ValidationOutcome::Improved) {
                best = w;
                bestE = e;
                res.bestEpoch = epoch;
            }
            patience.update(v.outcome, lr);
            if (v.goalReached) {
                // Weights that meet the goal are kept even if another epoch had a lower loss.
                goalReached = true;
                monitor.acceptLastAsBest();
                best = w;
                bestE = e;
                res.bestEpoch = epoch;
            }
        }
        res.epochs = epoch;
        EpochRecord r{epoch, trainLoss, v.loss, lr, elapsed()};
        r.validationRelativeRmse = figure(v);
        r.failureWithinNoise = v.outcome == ValidationOutcome::FailedWithinNoise;
        res.history.push_back(r);
        if (observer.onEpoch) observer.onEpoch(res.history.back());
    }

    if (hasVal) {
        w = best;
        e = bestE;
    } else if (res.stopReason.rfind("diverged", 0) != 0) res.bestEpoch = res.epochs;
    params = w.cast<double>();
    encodingParams = e.cast<double>();
    res.trainLoss = meanLoss(net, w, e, loss, data.xTrain, data.yTrain, acts);
    res.validationLoss = meanLoss(net, w, e, loss, data.xValidation, data.yValidation, acts);
    res.testLoss = meanLoss(net, w, e, loss, data.xTest, data.yTest, acts);
    if (hasVal) recordValidation(res, cfg.loss, outputScaler, data, cfg.errorGoal, predictions(net, w, e, data.xValidation, acts));
    res.seconds = elapsed();
    return res;
}

}  // namespace rrf
