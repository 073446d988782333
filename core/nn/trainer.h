#pragma once
/// Training one network on normalised data: the deterministic train/validation/test split, the
/// per-epoch record and observer, and the two trainers (Levenberg–Marquardt in lm.cpp, Adam in
/// adam.cpp). Higher-level entry points that also fit the scalers and build a model are in
/// nn/model.h (one network) and nn/object_training.h (one network per object).
///
/// Losses reported here are in NORMALISED units (targets mapped to [-1, 1] by mapminmax): the MSE for
/// levenberg_marquardt and adam/mse, the relative L2 loss for adam/relative_l2 and adam/relative_l2_prediction. Errors in raw units are
/// computed by fitNetwork (nn/model.h). Every epoch also reports the validation relative RMSE (raw
/// units, noise-corrected when the targets' variance is known), the figure the error goal is stated in
/// (nn/validation_monitor.h).

#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "core/nn/encoding.h"
#include "core/nn/mlp.h"
#include "core/nn/trainer_config.h"
#include "core/nn/validation_monitor.h"

namespace rrf {

/// One point of the loss curve. Epoch 0 is the initial network, before any update.
struct EpochRecord {
    int epoch = 0;
    double trainLoss = 0;  ///< loss on the training samples used (Adam: mean over the epoch's batches)
    /// Loss on the validation set; NaN when the set is empty (objects with fewer than 7 samples).
    double validationLoss = std::numeric_limits<double>::quiet_NaN();
    double step = 0;       ///< μ (levenberg_marquardt) or learning rate (adam) used in this epoch
    double seconds = 0;    ///< wall time since training started
    /// Validation relative RMSE in raw units, noise-corrected when the targets' variance is known
    /// (the figure compared with the error goal); NaN for an empty validation set.
    double validationRelativeRmse = std::numeric_limits<double>::quiet_NaN();
    /// True when this epoch's validation loss rose, but within the targets' noise (not a failure).
    bool failureWithinNoise = false;
    /// The ensemble member that ran this epoch (nn/ensemble.h); 0 for a single network.
    int member = 0;
};

/// What a training run did.
struct TrainResult {
    std::vector<EpochRecord> history;  ///< epoch 0 … epochs
    int epochs = 0;                    ///< epochs run
    int bestEpoch = 0;                 ///< epoch whose weights were kept (best validation loss)
    std::string stopReason;            ///< e.g. "validation stop", "maximum epoch reached", "cancelled"
    bool cancelled = false;
    double trainLoss = 0, validationLoss = 0, testLoss = 0;  ///< final losses (NaN for an empty set)
    int64_t trainSamples = 0, validationSamples = 0, testSamples = 0;
    int64_t trainSamplesUsed = 0;      ///< < trainSamples when the trainer subsampled (max_samples)
    double seconds = 0;
    std::vector<std::string> messages; ///< notes for the user (subsampling, solver fallbacks)
    /// The error goal (validation relative RMSE; 0 = none) and whether the kept weights met it
    /// (stopReason "error goal reached").
    double errorGoal = 0;
    bool goalReached = false;
    /// The kept weights' validation relative RMSE against the (noisy) targets, its noise-corrected
    /// value and the targets' relative noise floor (both NaN when the variance is unknown); see
    /// nn/validation_monitor.h. NaN for an empty validation set.
    double validationRelativeRmse = std::numeric_limits<double>::quiet_NaN();
    double validationRelativeRmseCorrected = std::numeric_limits<double>::quiet_NaN();
    double validationRelativeNoise = std::numeric_limits<double>::quiet_NaN();
    /// Networks averaged into the kept weights (nn/ensemble.h) and the epochs all of them ran; the
    /// history, epochs, best epoch and stop reason are the first member's, every figure above is the
    /// mean network's.
    int members = 1;
    int64_t memberEpochs = 0;

    /// The figure a network is judged by (error goal, kd-tree splits, the CLI's "valid rel"): the
    /// noise-corrected validation relative RMSE where the targets' noise is known, else the plain one.
    double judgedValidationError() const {
        return std::isfinite(validationRelativeRmseCorrected) ? validationRelativeRmseCorrected : validationRelativeRmse;
    }
};

/// Hooks into a running trainer. Both callbacks may be empty; they are called on the training thread,
/// and objects train in parallel, so they must be thread-safe.
struct TrainObserver {
    std::function<void(const EpochRecord&)> onEpoch;
    std::function<void(const std::string&)> onMessage;
    /// Checked between epochs; when it becomes true the trainer stops, keeping its best weights.
    const std::atomic<bool>* cancel = nullptr;

    bool cancelled() const { return cancel && cancel->load(std::memory_order_relaxed); }
};

/// Index sets of the 70/15/15 split.
struct DataSplit {
    std::vector<uint32_t> train, validation, test;
};

/// Random permutation of 0 … n−1 (Fisher–Yates driven by Rng(seed, stream)), cut 70/15/15 with
/// the training part rounded up: n = 1 gives one training sample and empty validation and test sets.
/// A pure function of (n, seed, stream).
DataSplit splitSamples(size_t n, uint64_t seed, uint64_t stream = 0);

/// Normalised data of one network, samples as columns (features × N).
struct TrainingData {
    MatX<float> xTrain, yTrain, xValidation, yValidation, xTest, yTest;
    /// Variance of each validation target's Monte Carlo mean in RAW units (outputs × N, as
    /// yValidation), or empty when unknown: the error goal and the failure count then ignore noise.
    MatX<float> vValidation;
};

/// Trains `params` (in: initial, out: the weights of the best validation epoch) with Matlab trainlm
/// semantics: per epoch JᵀJ and Jᵀe are accumulated in double over fixed chunks of the training set
/// (in parallel, reduced in a fixed order, so the result does not depend on the thread count), then
/// Δw = −(JᵀJ + μI)⁻¹Jᵀe is tried with μ raised ×mu_inc until the training SSE decreases (μ then
/// ×mu_dec). Stops on max_epochs, goal, error_goal (validation relative RMSE, computed in raw units
/// through `outputScaler`), ‖Jᵀe‖ < min_grad, μ > mu_max, max_fail validation failures (beyond the
/// targets' noise) or cancel. Trains on every training sample unless max_samples or max_epoch_gflop
/// bounds them, which the log then says. Throws std::invalid_argument when JᵀJ would not fit in
/// memory (use adam).
TrainResult trainLevenbergMarquardt(const MlpArch& arch, const LevenbergMarquardtConfig& cfg,
                                    const TrainingData& data, const MinMaxScaler& outputScaler,
                                    VecX<double>& params, const TrainObserver& observer = {});
/// The same with raw = normalised targets (identity output scaler).
TrainResult trainLevenbergMarquardt(const MlpArch& arch, const LevenbergMarquardtConfig& cfg,
                                    const TrainingData& data, VecX<double>& params,
                                    const TrainObserver& observer = {});

/// Training samples LM uses out of `available`: all, unless max_samples or the max_epoch_gflop
/// budget (3·N·P² flops per epoch for P parameters) is smaller. `reason` (if given) receives the
/// sentence the log prints when a bound applies, and stays empty otherwise.
int64_t lmSampleCount(const LevenbergMarquardtConfig& cfg, int64_t available, int64_t params,
                      std::string* reason = nullptr);

/// Learning rate of Adam's epoch `epoch` (1-based) under cfg's schedule (docs/design.md §12).
double adamLearningRate(const AdamConfig& cfg, int epoch);

/// Trains `params` with Adam on shuffled mini-batches in float. `outputScaler` converts normalised
/// outputs back to raw units for the relative L2 loss and the error goal. Stops on max_epochs,
/// error_goal, patience (counted only while the rate is ≤ patience_lr_fraction × learning_rate, and
/// not for rises within the targets' noise), divergence or cancel. Single-threaded and
/// deterministic; objects are parallelised one level up.
TrainResult trainAdam(const MlpArch& arch, const AdamConfig& cfg, const TrainingData& data,
                      const MinMaxScaler& outputScaler, VecX<double>& params,
                      const TrainObserver& observer = {});
/// The same for a network behind an input encoding (nn/encoding.h) whose parameters are trained
/// jointly with the weights: `data`'s x are the normalised raw and derived inputs (encoding.scaledInputs() rows) and
/// arch.inputs = encoding.outputs(). Per batch: encode → MLP forward → loss → MLP backward with
/// ∂loss/∂features → the encoding's parameter gradient; the weights take the dense Adam step, the
/// encoding parameters (`encodingParams`, in: initial, out: those of the kept epoch) a sparse one:
/// only the entries the batch touched, each once, without weight decay (instant-NGP). The identity
/// encoding is exactly trainAdam above.
TrainResult trainAdam(const MlpArch& arch, const InputEncoding& encoding, const AdamConfig& cfg, const TrainingData& data,
                      const MinMaxScaler& outputScaler, VecX<double>& params, VecX<double>& encodingParams,
                      const TrainObserver& observer = {});

/// Dispatches on cfg.type.
TrainResult trainNetwork(const MlpArch& arch, const TrainerConfig& cfg, const TrainingData& data,
                         const MinMaxScaler& outputScaler, VecX<double>& params,
                         const TrainObserver& observer = {});

/// Sets the kept weights' validation figures in `res` (relative RMSE, its noise-corrected value, the
/// noise floor, whether `goal` is met) from their normalised predictions on data.xValidation, scored
/// by a ValidationMonitor with `loss`'s weights. Nothing for an empty validation set.
void recordValidation(TrainResult& res, AdamLoss loss, const MinMaxScaler& outputScaler, const TrainingData& data,
                      double goal, const MatX<double>& predNormalised);

/// Mean squared error of the network on normalised data, computed in double in chunks
/// (NaN for an empty set).
double networkMse(const MlpArch& arch, const VecX<double>& params, const MatX<float>& x, const MatX<float>& y);

}  // namespace rrf
