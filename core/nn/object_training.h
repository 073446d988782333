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
#include "core/nn/object_network_overrides.h"

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

/// What each network of an object predicts.
enum class TargetMode {
    Global,    ///< one 3-output net for direct + indirect (total radiance)
    Direct,    ///< one 3-output net for direct only
    Indirect,  ///< one 3-output net for indirect only
    Separate,  ///< two 3-output nets per object, "direct" and "indirect"
    Joint      ///< one 6-output net: outputs 0–2 direct, 3–5 indirect
};

/// "global" | "direct" | "indirect" | "separate" | "joint"; parse throws std::invalid_argument.
const char* targetModeName(TargetMode m);
TargetMode parseTargetMode(const std::string& s);

/// How each object's input space is partitioned (Ren et al. 2013; nn/partition_tree.h). The tree
/// grows level by level: a node's network is trained on the node's records, and the node is split
/// (median of the widest allowed axis) while
///   its network's validation relative RMSE (relativeRmse, ε = 0.01) is above `goal`,
///   both children would hold at least `minRecordsPerWeight` × P records (P: the MLP's weights and
///   biases; an input encoding's trainable parameters, e.g. hash-grid tables, are not counted),
///   the node is shallower than `maxDepth` and the tree has fewer than `maxLeaves` leaves;
/// within a level the worst nodes split first when `maxLeaves` runs out. Every node trains on its
/// own records from scratch, nodes of a level (of all objects and targets) in parallel. Once both
/// children are trained, the split is kept only if they help: their combined validation error (RMS
/// over both children's validation records) must be at most (1 − minSplitGain) × the node's;
/// otherwise the node stays a leaf with its own network (a plane through the feature that caused
/// the error — e.g. a shadow that moves with the light — leaves each half as hard as the whole).
///
/// The initialisers are the project's defaults (the "partition" keys a project file leaves out).
struct PartitionSettings {
    /// The project's leaf budget per object and target.
    static constexpr int kDefaultMaxLeaves = 16;

    double goal = 0.05;               ///< "goal": validation relative RMSE a leaf must reach (0, 10]
    int maxDepth = 8;                 ///< "max_depth": 0 … 20; 0 = one network per object
    int maxLeaves = kDefaultMaxLeaves;  ///< "max_leaves": 1 … 4096; 1 = one network per object
    double minRecordsPerWeight = 8;   ///< "min_records_per_weight": 1 … 1000 (Ren et al.: 8–10)
    /// "min_split_gain": 0 … 0.99, the relative error reduction a split must bring to be kept
    /// (0 = keep every split). The default keeps a split only when its leaves lower the node's
    /// validation error by at least 10 % (a split that does not help only adds seams and parameters).
    double minSplitGain = 0.1;
    PartitionAxes axes;               ///< "split_axes": any of "position", "light"

    /// True when a tree can grow beyond its root.
    bool enabled() const { return maxDepth > 0 && maxLeaves > 1; }
    bool operator==(const PartitionSettings& o) const {
        return goal == o.goal && maxDepth == o.maxDepth && maxLeaves == o.maxLeaves &&
               minRecordsPerWeight == o.minRecordsPerWeight && minSplitGain == o.minSplitGain && axes == o.axes;
    }
};

/// What to train and how. The initialisers are the project's defaults, the only ones: a project file
/// without a "network" or "trainer" section, or a section without the key, gets them
/// (NetworkSettings, Project::networkOrDefault). Tests and tools that want another setting say so.
struct ObjectTrainingOptions {
    std::vector<int> hidden = MlpArch().hidden;  ///< the report's 20-10 network (nn/mlp.h)
    Activation activation = Activation::Tanh;
    /// "ensemble": networks trained per leaf from different initial weights and mini-batch orders
    /// (one split), merged into the one network that predicts their mean (nn/ensemble.h); 1 = one
    /// network, as Ren et al. Each member costs a full training run.
    int ensemble = 1;
    /// The "encoding" setting (nn/encoding_settings.h, nn/encoding_presets.h); empty = the identity.
    /// Each network gets networkEncoding(encoding, its records' input count); its first layer reads
    /// the features.
    NetworkEncodingSettings encoding;
    /// The "inputs" object: inputs every network derives from its records (nn/derived_inputs.h).
    DerivedInputs inputs;
    /// The "objects" map: hidden sizes, inputs and encoding of named objects (nn/object_network_overrides.h).
    ObjectNetworkOverrides perObject;
    /// Indirect light only: direct light is computed exactly by default, as in Ren et al.;
    /// Project::networkOrDefault learns direct light too when the project predicts it with networks.
    TargetMode targets = TargetMode::Indirect;
    TrainerConfig trainer = TrainerConfig::projectDefault();
    PartitionSettings partition;  ///< default: kd-trees of at most kDefaultMaxLeaves networks
    std::vector<int> objects;  ///< object ids to train; empty = all
    bool parallel = true;      ///< train objects concurrently (TBB); results are identical either way

    /// The section's hidden sizes, inputs and encoding (what an object without an override gets).
    ObjectNetworkChoice sharedChoice() const { return {hidden, inputs, encoding}; }
    /// Those of the object called `name`: sharedChoice() with its override applied.
    ObjectNetworkChoice choiceFor(const std::string& name) const { return objectNetworkChoice(sharedChoice(), perObject, name); }
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
