#pragma once
/// Per-object training (docs/design.md §10): one network per scene object — or per object and target — fitted
/// from in-memory samples, objects in parallel.
///
/// The dataset reader fills one ObjectSamples per object and calls trainObjects(); the result holds a
/// PartitionedNetwork per trained object and target (saved by nn/model_set.h) and an entry, marked skipped, with a
/// message for every object that could not be trained.

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "core/nn/model.h"
#include "core/nn/network_options.h"
#include "core/nn/trainer_config.h"

namespace rrf {

/// All training records of one object. Storage is record-major: record i occupies
/// `inputs[i·numInputs … (i+1)·numInputs)`, `direct[3i … 3i+3)` and `indirect[3i … 3i+3)`, exactly the
/// layout of a features × N column-major Eigen matrix, so the trainer maps it without a copy.
///
/// Input record (numInputs = 12 + n floats), in this order:
///   hit point x (3), view direction ω (3), light position (3), shading normal (3), BRDF parameters (n).
/// Targets: direct radiance RGB and indirect radiance RGB (linear, not tone-mapped), as estimated by
/// the data generator. NaN/Inf must not be present (the dataset reader drops and counts them).
struct ObjectSamples {
    int objectId = -1;          ///< scene object index; also keys the object's split and initial weights
    std::string name;           ///< for messages and model headers
    int numInputs = 0;          ///< 12 + n
    std::vector<float> inputs;  ///< size() · numInputs
    std::vector<float> direct;  ///< size() · 3
    std::vector<float> indirect;///< size() · 3
    /// Variance of each target's Monte Carlo mean (raw units, size() · 3 each, as direct/indirect),
    /// or both empty when the dataset does not store it: the error goal then ignores target noise.
    std::vector<float> directVariance, indirectVariance;

    /// Number of records.
    size_t size() const { return numInputs > 0 ? inputs.size() / size_t(numInputs) : 0; }
    /// Appends one record (convenience for tests and small tools).
    void add(const float* in, const float directRgb[3], const float indirectRgb[3]);
    /// Views as features × N matrices (no copy).
    Eigen::Map<const MatX<float>> inputMatrix() const;
    Eigen::Map<const MatX<float>> directMatrix() const;
    Eigen::Map<const MatX<float>> indirectMatrix() const;
    /// Throws std::invalid_argument when the three arrays disagree in length.
    void validate() const;
};

/// What to train and how: the network settings (NetworkOptions: the project's "network" section),
/// the trainer (its "trainer" section) and which objects. A project holds the two sections apart
/// (Project::network, Project::trainer); they are joined here only where a training starts
/// (Project::trainingOptions, the CLI's flags, a sweep row, the pipeline's presets), so the trainer
/// is held once. The initialisers are the project's defaults (NetworkOptions',
/// TrainerConfig::projectDefault()).
struct ObjectTrainingOptions : NetworkOptions {
    TrainerConfig trainer = TrainerConfig::projectDefault();
    std::vector<int> objects;  ///< object ids to train; empty = all
    bool parallel = true;      ///< train objects concurrently (TBB); results are identical either way

    ObjectTrainingOptions() = default;
    /// `network` trained by `trainer`, every object.
    ObjectTrainingOptions(const NetworkOptions& network, const TrainerConfig& trainer)
        : NetworkOptions(network), trainer(trainer) {}
    /// The network settings alone (what a project's or run's "network" section holds).
    const NetworkOptions& network() const { return *this; }
    NetworkOptions& network() { return *this; }
};

/// Progress of all networks. Called concurrently from worker threads: must be thread-safe.
struct ObjectTrainingObserver {
    /// (object id, target: "global" | "direct" | "indirect" | "joint", record) for the epochs of each
    /// tree's root network (the object's network when it is not partitioned; of an ensemble, its first
    /// member); the networks of deeper nodes report through onMessage when they finish.
    std::function<void(int, const std::string&, const EpochRecord&)> onEpoch;
    std::function<void(const std::string&)> onMessage;
    /// Work accounting for progress bars, over every network of every tree (roots and split nodes):
    /// (epochs done, epochs added to the budget). Each network is budgeted its trainer's max_epochs
    /// (times the ensemble's members) when it is scheduled (roots before training starts, two children
    /// when a node splits); every epoch it runs reports (1, 0), and when it stops early the epochs it
    /// did not need are reported as done, so done reaches the budget exactly when the last network ends.
    std::function<void(int64_t, int64_t)> onWork;
    const std::atomic<bool>* cancel = nullptr;
};

struct ObjectModel {
    int objectId = -1;
    std::string objectName;
    std::string target;        ///< as NetworkModel::target
    bool skipped = false;      ///< no network (no samples, unknown object id, cancelled before start)
    std::string message;       ///< why it was skipped
    PartitionedNetwork model;  ///< valid unless skipped (a single-leaf tree when not partitioned)
};

/// Trains the selected objects, each network a kd-tree of networks when `options.partition` is
/// enabled (PartitionSettings). The result is in the order of `objects` (then direct before indirect)
/// and is bit-identical for any thread count. An object with no samples is skipped with a message;
/// a single-sample object trains (on that one sample, without validation or test sets).
/// Throws std::invalid_argument for malformed ObjectSamples or a network the trainer cannot handle,
/// and SettingError naming "network.encoding" for an encoding the records or the trainer cannot take
/// (checkEncodingTrainer, networkEncoding).
std::vector<ObjectModel> trainObjects(const std::vector<ObjectSamples>& objects, const ObjectTrainingOptions& options,
                                      const ObjectTrainingObserver& observer = {});

/// File name of an object's model inside a models/ directory: "object_<id>_<target>.rrfm".
std::string modelFileName(int objectId, const std::string& target);
/// File name of leaf `leaf` of a partitioned model: "object_<id>_<target>_leaf<leaf>.rrfm".
std::string leafModelFileName(int objectId, const std::string& target, int leaf);

}  // namespace rrf
