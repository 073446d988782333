#pragma once
/// Network and trainer settings of a project ("network" and "trainer" sections), shared by the CLI
/// and the GUI:
///
///     "network": {"hidden": [20, 10], "activation": "tanh", "targets": "separate"},
///     "trainer": {"type": "levenberg_marquardt", ...}   (see nn/trainer_config.h)
///
/// "targets": "separate" (default: one direct and one indirect net per object, so direct light can
/// also be computed exactly while the networks predict indirect light), "joint" (one 6-output net),
/// "global", "direct" or "indirect".

#include <string>

#include <nlohmann/json.hpp>

#include "core/nn/object_training.h"

namespace rrf {

struct NetworkSettings {
    ObjectTrainingOptions options;  ///< hidden sizes, activation, targets, trainer

    /// The project defaults: ObjectTrainingOptions' defaults with separate direct and indirect nets.
    NetworkSettings() { options.targets = TargetMode::Separate; }
    /// Reads the "network" section and, when given, the "trainer" section (missing keys keep their
    /// defaults). Throws InputError naming `file` and the JSON pointer for unknown keys or bad values.
    static NetworkSettings fromJson(const nlohmann::json& network, const nlohmann::json* trainer, const std::string& file);
    nlohmann::json networkJson() const;
    nlohmann::json trainerJson() const { return options.trainer.toJson(); }
};

/// Reads hidden sizes written as text, "20,10" (the spelling of `network.hidden` = [20, 10] outside a
/// JSON file, e.g. a sweep value); throws SettingError naming `setting` if malformed or out of 1..4096.
std::vector<int> parseHiddenSizes(const std::string& text, const std::string& setting);

}  // namespace rrf
