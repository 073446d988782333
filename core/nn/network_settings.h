#pragma once
/// Network settings of a project (its "network" section), shared by the CLI and the GUI; the
/// "trainer" section beside it is TrainerConfig (nn/trainer_config.h), held apart; both sections are
/// read and written by their codecs (nn/network_settings_json.h, nn/trainer_config_json.h):
///
///     "network": {"hidden": [20, 10], "activation": "tanh", "targets": "separate",
///                 "inputs": {"reflected": false},
///                 "encoding": [{"type": "hash_grid", "inputs": "position"}],
///                 "objects": {"tall-box": {"inputs": {"reflected": true}, "hidden": [32, 16]}},
///                 "partition": {"goal": 0.05, "max_depth": 8, "max_leaves": 16,
///                               "min_records_per_weight": 8, "min_split_gain": 0.1,
///                               "split_axes": ["position", "light"]}},
///     "trainer": {"type": "levenberg_marquardt", ...}   (see nn/trainer_config.h)
///
/// "partition" sets the kd-tree of networks per object and target (PartitionSettings in
/// nn/network_options.h); every key is optional, unknown keys are errors, and "max_leaves": 1 (or
/// "max_depth": 0) trains one network per object.
/// "inputs" adds derived inputs to every network (nn/derived_inputs.h: "reflected", the view direction
/// reflected about the normal; absent: none), which "encoding" components may then name as a group.
/// "objects" changes hidden sizes, inputs and encoding for the named objects (nn/object_network_overrides.h).
/// "encoding" is the input encoding of every network (nn/encoding.h; [] or absent: the raw inputs),
/// checked when read against records of kEncodingCheckInputs inputs; nn/encoding_presets.h names
/// a few. A trainable one (hash grid) needs the adam trainer (checked when training starts).
/// "targets": "separate" (default: one direct and one indirect net per object, so direct light can
/// also be computed exactly while the networks predict indirect light), "joint" (one 6-output net),
/// "global", "direct" or "indirect".

#include <string>
#include <vector>

#include "core/nn/network_options.h"

namespace rrf {

/// Largest hidden layer size (each size is 1 … this), one definition for the project reader, the
/// CLI's --hidden, sweep values, the Network panel and scripts.
constexpr int kMaxHiddenSize = 4096;
constexpr int kMaxPartitionLeaves = 4096;  ///< "partition": {"max_leaves"}
constexpr int kMaxEnsembleMembers = 16;    ///< "ensemble": networks averaged per leaf

struct NetworkSettings {
    /// Hidden sizes, activation, targets, inputs, encoding, per-object entries, partition;
    /// default-constructed, the project's defaults (NetworkOptions' initialisers).
    NetworkOptions options;

    /// The project's default leaf budget per object and target (its one definition is
    /// PartitionSettings::kDefaultMaxLeaves).
    static constexpr int kDefaultMaxLeaves = PartitionSettings::kDefaultMaxLeaves;
    /// The "network" section's keys ("hidden", "activation", "ensemble", "inputs", "encoding",
    /// "objects", "targets", "partition").
    static const std::vector<std::string>& keys();
};

/// Reads hidden sizes written as text, "20,10" (the spelling of `network.hidden` = [20, 10] outside a
/// JSON file, e.g. a sweep value); throws SettingError naming `setting` if malformed or out of 1..kMaxHiddenSize.
std::vector<int> parseHiddenSizes(const std::string& text, const std::string& setting);
/// The one text spelling of hidden sizes, "20,10" (what parseHiddenSizes reads back), for tables,
/// logs, job names and text fields; "" for none.
std::string hiddenSizesText(const std::vector<int>& sizes);

}  // namespace rrf
