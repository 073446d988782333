#pragma once
/// A trained radiance regression network: architecture, weights, mapminmax normalisation, the input
/// encoding and its parameters, the trainer settings and the training record, plus fitting from raw
/// data and the model file format.
///
///     raw inputs (rawInputs()) --encoding.derived--> + derived inputs (scaledInputs(); nn/derived_inputs.h)
///        --inputScaler--> x' in [-1, 1] --encoding--> features (arch.inputs) --MLP-->
///
/// Model file (".rrfm"), little-endian:
///
///     offset 0   8 bytes   magic "RRFMODEL"
///     offset 8   u32       format version (4)
///     offset 12  u32       header length H in bytes
///     offset 16  u64       checksum64 (core/data/dataset_file.h) of the H header bytes
///     offset 24  H bytes   JSON header (UTF-8): architecture, object, target, trainer settings,
///                          input encoding ("input_encoding": {"inputs": raw input count,
///                          "derived": toJson(DerivedInputs), "components": toJson(InputEncoding)}),
///                          training record (history, stop
///                          reason, errors), payload description with the payload's byte count and
///                          FNV-1a 64 checksum; for a merged ensemble "ensemble": {"members": K,
///                          "output_bias": K arrays of the members' own output biases} (optional:
///                          without it the ensemble predicts as before but has no spread)
///     offset 24+H          payload: IEEE-754 float64 values, in this order:
///                          params[P], input_offset[in], input_scale[in], output_offset[out], output_scale[out],
///                          encoding_params[E]
///                          (P: the MLP's weights and biases; in: raw inputs plus derived inputs, the
///                          scaler's size; E: encoding.numParams())
///
/// Version 3 files (no "derived") load without derived inputs, exactly as before. Version 2 files (no "input_encoding", no encoding_params) load as the identity encoding; version 1
/// files (no header checksum either: the header starts at offset 16) too, their header's integrity
/// unchecked (a model set of version 3 checksums its files as a whole).
///
/// Weights are stored as raw doubles, so a loaded model holds the very same bits and predicts
/// bit-identically. Files are written atomically (temporary file + rename).

#include <string>

#include "core/nn/encoding.h"
#include "core/nn/mlp.h"
#include "core/nn/partition_tree.h"
#include "core/nn/trainer.h"
#include "core/nn/trainer_config.h"

namespace rrf {

/// Root-mean-square errors in RAW target units (radiance), over every entry of a subset.
struct ModelErrors {
    double train = 0, validation = 0, test = 0;  ///< NaN for an empty subset
};

struct NetworkModel {
    MlpArch arch;                  ///< arch.inputs = the encoding's features (the raw inputs for the identity)
    MinMaxScaler inputScaler, outputScaler;  ///< inputScaler: scaledInputs() features (raw, then derived)
    VecX<double> params;           ///< flat weights, layout in nn/mlp.h
    /// Map from the normalised raw and derived inputs to the MLP's inputs; no components = the
    /// identity (Ren et al.'s raw inputs, plus the derived ones). A model built in code may leave an
    /// identity's `inputs` at 0 when it derives nothing.
    InputEncoding encoding;
    VecX<double> encodingParams;   ///< encoding.numParams() trainable values (hash-grid tables); empty for fixed encodings
    int objectId = -1;             ///< -1 when not tied to a scene object
    std::string objectName;
    std::string target = "global"; ///< "global", "direct", "indirect" or "joint" (6 outputs: direct, indirect)
    TrainerConfig trainer;
    TrainResult training;
    ModelErrors errors;
    /// A merged ensemble's members' own output biases in normalised output units, member after
    /// member (K × outputs values, K = training.members ≥ 2; nn/ensemble.h): what makes every
    /// member's output, and so their spread, recoverable. Empty for a single network and for
    /// ensembles from model files written before they were stored (which then have no spread).
    VecX<double> memberOutputBias;

    /// Predicts raw outputs (outputs × N) for raw inputs (inputs × N) in float, in fixed chunks:
    /// the result depends only on the stored bits and the inputs.
    MatX<float> predict(const Eigen::Ref<const MatX<float>>& rawInputs) const;
    /// The same in double (reference for tests and for checking the float path).
    MatX<double> predictDouble(const Eigen::Ref<const MatX<double>>& rawInputs) const;
    /// Members whose outputs predictMembers gives: K when memberOutputBias is stored, else 0.
    int spreadMembers() const {
        return arch.outputs > 0 && !arch.hidden.empty() ? int(memberOutputBias.size() / arch.outputs) : 0;
    }
    /// Every member's raw outputs (outputs × N each, `spreadMembers()` matrices) for raw inputs: the
    /// members as they were trained, recovered from the merged weights (nn/ensemble.h); their mean is
    /// predict() to float rounding. Empty when spreadMembers() is 0.
    std::vector<MatX<float>> predictMembers(const Eigen::Ref<const MatX<float>>& rawInputs) const;
    /// Throws std::invalid_argument unless sizes agree and every number is finite (and a stored
    /// ensemble's member biases fit its architecture and average to its output bias).
    void validate() const;
    /// Raw record inputs the model reads (12 + n): the encoding's inputs, or what the identity's
    /// first layer reads less the derived inputs.
    int rawInputs() const { return encoding.isIdentity() ? arch.inputs - encoding.derived.count() : encoding.inputs; }
    /// Rows the input scaler normalises: the raw inputs, then the derived ones.
    int scaledInputs() const { return rawInputs() + encoding.derived.count(); }
    /// Trainable numbers: the MLP's weights and biases plus the encoding's parameters.
    int64_t numParams() const { return int64_t(arch.numParams()) + int64_t(encodingParams.size()); }
};

/// Throws std::invalid_argument unless `model`'s member output biases (if any) fit its architecture
/// and training record and average to its output bias (part of NetworkModel::validate).
void checkMemberBiases(const NetworkModel& model);

/// Bytes of the model's payload in its file (nn/model_file.h, float64): its MLP weights and biases,
/// the input and output scalers' offsets and scales, and the encoding's parameters. A function of the
/// architecture and encoding alone (the loader checks a file's payload against it before reading it);
/// also a model's size in the sweeps' `model_bytes` column.
int64_t modelPayloadBytes(const NetworkModel& model);

/// A partitioned radiance regression function (Ren et al. 2013): a kd-tree over the record inputs
/// (nn/partition_tree.h) whose leaf k is predicted by `leaves[k]`. A tree of one leaf is a plain
/// network, which is what older model sets load as. All leaves share architecture, object and target.
struct PartitionedNetwork {
    PartitionTree tree;
    std::vector<NetworkModel> leaves;  ///< index = leaf number

    PartitionedNetwork() = default;
    /// One network as a single-leaf tree (an unpartitioned model; implicit, so a plain network can
    /// stand wherever a partitioned one is expected).
    PartitionedNetwork(NetworkModel single);

    /// The leaves' common architecture (the first leaf's; validate() checks the others).
    const MlpArch& arch() const { return leaves.front().arch; }
    /// The leaves' common input encoding and raw input count (the first leaf's).
    const InputEncoding& encoding() const { return leaves.front().encoding; }
    int rawInputs() const { return leaves.front().rawInputs(); }
    int objectId() const { return leaves.front().objectId; }
    const std::string& target() const { return leaves.front().target; }
    int leafCount() const { return int(leaves.size()); }
    /// Weights, biases and encoding parameters of all leaves together.
    int64_t numParams() const;
    /// Leaf number of every column of `rawInputs` (inputs × N).
    std::vector<int> findLeaves(const Eigen::Ref<const MatX<float>>& rawInputs) const;
    /// Raw outputs (outputs × N) for raw inputs (inputs × N): every column is predicted by its leaf's
    /// network (NetworkModel::predict on the columns of that leaf, in ascending order), so a single
    /// leaf gives exactly NetworkModel::predict.
    MatX<float> predict(const Eigen::Ref<const MatX<float>>& rawInputs) const;
    /// The same in double; the leaf of a column is looked up on its float value, as predict does.
    MatX<double> predictDouble(const Eigen::Ref<const MatX<double>>& rawInputs) const;
    /// Members every leaf's predictMembers gives (the smallest over the leaves; 0 when one leaf has none).
    int spreadMembers() const;
    /// NetworkModel::predictMembers column by column through the leaves; empty when spreadMembers() is 0.
    std::vector<MatX<float>> predictMembers(const Eigen::Ref<const MatX<float>>& rawInputs) const;
    /// Throws std::invalid_argument unless the tree is valid for the inputs, there is one valid
    /// network per leaf and all share architecture, encoding, object and target.
    void validate() const;
};

/// How far a partitioned model jumps across its split planes, measured at the records `rawInputs`
/// (inputs × N): every record is projected onto each plane on its root-to-leaf path and predicted
/// just below the plane (the largest float under the split) and on it, i.e. by the leaves on either
/// side at one point; the result is the RMS of |a − b| / (|b| + 0.01) over all entries (the relative
/// figure of §14), 0 for a single leaf. The seam test bounds it by the error goal.
double seamJump(const PartitionedNetwork& model, const Eigen::Ref<const MatX<float>>& rawInputs);

/// The relative RMSE of docs/design.md §14 over every entry: sqrt(mean ((p − t) / (|t| + 0.01))²),
/// NaN for no columns. The partitioning's error goal is stated in it.
double relativeRmse(const Eigen::Ref<const MatX<float>>& predicted, const Eigen::Ref<const MatX<float>>& target);

/// Fits one network on raw data (inputs × N, targets × N, samples as columns):
/// 70/15/15 split (splitSamples(N, cfg.seed(), stream)), mapminmax scalers fitted on all N samples
/// (as Matlab's train does), initial weights initialParams(arch, seed, stream), training with `cfg`,
/// and RMSEs in raw units. `arch.inputs`/`arch.outputs` must match the data. N must be ≥ 1. The
/// network reads the normalised inputs themselves (the identity encoding).
NetworkModel fitNetwork(const MlpArch& arch, const TrainerConfig& cfg, const Eigen::Ref<const MatX<float>>& inputs,
                        const Eigen::Ref<const MatX<float>>& targets, const TrainObserver& observer = {},
                        uint64_t stream = 0);
/// The same with the variance of each target's Monte Carlo mean (raw units, the shape of `targets`;
/// empty = unknown), which makes the error goal and the validation-failure count noise-aware
/// (nn/validation_monitor.h).
NetworkModel fitNetwork(const MlpArch& arch, const TrainerConfig& cfg, const Eigen::Ref<const MatX<float>>& inputs,
                        const Eigen::Ref<const MatX<float>>& targets, const MatX<float>& targetVariance,
                        const TrainObserver& observer = {}, uint64_t stream = 0);
/// The same behind an input encoding: `inputs` has encoding.inputs rows (the raw record inputs) and
/// arch.inputs must be encoding.outputs() (the identity: inputs.rows() plus the derived inputs). The
/// derived inputs (encoding.derived) are computed from the raw records before the scaler is fitted. The encoding's initial
/// parameters are encoding.initialParams(seed, stream). A fixed encoding (no parameters) encodes the
/// normalised data once and trains the MLP on the features with either trainer; a trainable one
/// (hash grid) trains jointly with Adam (trainAdam) and is a SettingError naming "network.encoding"
/// under Levenberg–Marquardt. `members` > 1 trains an ensemble on the one split and keeps the
/// network of its mean (nn/ensemble.h; the model's hidden layers are `members` times arch's), which a
/// trainable encoding cannot join: a SettingError naming "network.ensemble".
NetworkModel fitNetwork(const MlpArch& arch, const InputEncoding& encoding, const TrainerConfig& cfg,
                        const Eigen::Ref<const MatX<float>>& inputs, const Eigen::Ref<const MatX<float>>& targets,
                        const MatX<float>& targetVariance, const TrainObserver& observer = {}, uint64_t stream = 0,
                        int members = 1);

/// The bytes saveModel writes for `model` (what loadModel/parseModel read back bit for bit).
/// Throws std::invalid_argument if the model holds non-finite numbers.
std::string modelFileBytes(const NetworkModel& model);

/// Writes `model` to `path` atomically. Throws std::runtime_error on I/O failure and
/// std::invalid_argument if the model holds non-finite numbers.
void saveModel(const NetworkModel& model, const std::string& path);

/// Reads a model file. Any defect (missing file, wrong magic or version, truncation, trailing bytes,
/// header checksum mismatch, bad header or an integer field out of range, sizes that disagree with the architecture, checksum mismatch, NaN/Inf weights) is an
/// InputError naming the file.
NetworkModel loadModel(const std::string& path);

/// Parses the bytes of a model file read from `path` (named in errors), as loadModel does.
NetworkModel parseModel(const std::string& bytes, const std::string& path);

}  // namespace rrf
