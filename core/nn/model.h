#pragma once
/// A trained radiance regression network: architecture, weights, mapminmax normalisation, the
/// trainer settings and the training record, plus fitting from raw data and the model file format.
///
/// Model file (".rrfm"), little-endian:
///
///     offset 0   8 bytes   magic "RRFMODEL"
///     offset 8   u32       format version (1)
///     offset 12  u32       header length H in bytes
///     offset 16  H bytes   JSON header (UTF-8): architecture, object, target, trainer settings,
///                          training record (history, stop reason, errors), payload description
///                          with the payload's byte count and FNV-1a 64 checksum
///     offset 16+H          payload: IEEE-754 float64 values, in this order:
///                          params[P], input_offset[in], input_scale[in], output_offset[out], output_scale[out]
///
/// Weights are stored as raw doubles, so a loaded model holds the very same bits and predicts
/// bit-identically. Files are written atomically (temporary file + rename).

#include <string>

#include <nlohmann/json.hpp>

#include "core/nn/mlp.h"
#include "core/nn/trainer.h"
#include "core/nn/trainer_config.h"

namespace rrf {

/// Root-mean-square errors in RAW target units (radiance), over every entry of a subset.
struct ModelErrors {
    double train = 0, validation = 0, test = 0;  ///< NaN for an empty subset
};

struct NetworkModel {
    MlpArch arch;
    MinMaxScaler inputScaler, outputScaler;
    VecX<double> params;           ///< flat weights, layout in nn/mlp.h
    int objectId = -1;             ///< -1 when not tied to a scene object
    std::string objectName;
    std::string target = "global"; ///< "global", "direct", "indirect" or "joint" (6 outputs: direct, indirect)
    TrainerConfig trainer;
    TrainResult training;
    ModelErrors errors;

    /// Predicts raw outputs (outputs × N) for raw inputs (inputs × N) in float, in fixed chunks:
    /// the result depends only on the stored bits and the inputs.
    MatX<float> predict(const Eigen::Ref<const MatX<float>>& rawInputs) const;
    /// The same in double (reference for tests and for checking the float path).
    MatX<double> predictDouble(const Eigen::Ref<const MatX<double>>& rawInputs) const;
    /// Throws std::invalid_argument unless sizes agree and every number is finite.
    void validate() const;
};

/// Fits one network on raw data (inputs × N, targets × N, samples as columns):
/// 70/15/15 split (splitSamples(N, cfg.seed(), stream)), mapminmax scalers fitted on all N samples
/// (as Matlab's train does), initial weights initialParams(arch, seed, stream), training with `cfg`,
/// and RMSEs in raw units. `arch.inputs`/`arch.outputs` must match the data. N must be ≥ 1.
NetworkModel fitNetwork(const MlpArch& arch, const TrainerConfig& cfg, const Eigen::Ref<const MatX<float>>& inputs,
                        const Eigen::Ref<const MatX<float>>& targets, const TrainObserver& observer = {},
                        uint64_t stream = 0);
/// The same with the variance of each target's Monte Carlo mean (raw units, the shape of `targets`;
/// empty = unknown), which makes the error goal and the validation-failure count noise-aware
/// (nn/validation_monitor.h).
NetworkModel fitNetwork(const MlpArch& arch, const TrainerConfig& cfg, const Eigen::Ref<const MatX<float>>& inputs,
                        const Eigen::Ref<const MatX<float>>& targets, const MatX<float>& targetVariance,
                        const TrainObserver& observer = {}, uint64_t stream = 0);

/// Writes `model` to `path` atomically. Throws std::runtime_error on I/O failure and
/// std::invalid_argument if the model holds non-finite numbers.
void saveModel(const NetworkModel& model, const std::string& path);

/// Reads a model file. Any defect (missing file, wrong magic or version, truncation, trailing bytes,
/// bad header, sizes that disagree with the architecture, checksum mismatch, NaN/Inf weights) is an
/// InputError naming the file.
NetworkModel loadModel(const std::string& path);

/// Header of a model (everything but the payload) as JSON; what saveModel writes.
nlohmann::json modelHeader(const NetworkModel& model);

}  // namespace rrf
