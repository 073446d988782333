#pragma once
/// The network settings of a project (its "network" section, docs/design.md §10): per object, what
/// its networks predict (TargetMode), their hidden sizes, activation, inputs and encoding (with the
/// "objects" overrides), ensembles and the kd-tree each object's input space is cut into
/// (PartitionSettings). The trainer is not among them: it is the "trainer" section
/// (nn/trainer_config.h), and ObjectTrainingOptions (nn/object_training.h) joins the two where a
/// training starts.

#include <string>
#include <vector>

#include "core/nn/encoding_settings.h"
#include "core/nn/mlp.h"
#include "core/nn/object_network_overrides.h"
#include "core/nn/partition_tree.h"

namespace rrf {

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

/// What each object's networks are: the project's "network" section, without the trainer (which is
/// its "trainer" section, held apart: ObjectTrainingOptions joins the two where training starts).
/// The initialisers are the project's defaults, the only ones: a project file without a "network"
/// section, or a section without the key, gets them (NetworkSettings, Project::networkOrDefault).
/// Tests and tools that want another setting say so.
struct NetworkOptions {
    /// "hidden": 32-16, not the report's 20-10 (MlpArch's): on the Cornell box's default data the
    /// wider network lowers the held-out error at the same training time, while 48-24 fits worse
    /// (docs/results-history.md, "The default network").
    std::vector<int> hidden{32, 16};
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
    PartitionSettings partition;  ///< default: kd-trees of at most kDefaultMaxLeaves networks

    /// The section's hidden sizes, inputs and encoding (what an object without an override gets).
    ObjectNetworkChoice sharedChoice() const { return {hidden, inputs, encoding}; }
    /// Those of the object called `name`: sharedChoice() with its override applied.
    ObjectNetworkChoice choiceFor(const std::string& name) const { return objectNetworkChoice(sharedChoice(), perObject, name); }
};

}  // namespace rrf
