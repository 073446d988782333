#pragma once
/// The JSON of a project's "network" section (nn/network_settings.h for the format): the section,
/// its "hidden" array and its "partition" object, read and written here.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/nn/network_settings.h"
#include "core/util/json_reader.h"

namespace rrf {

/// Reads a "network" section over `base`: missing keys keep base's values. Throws InputError naming
/// the reader's file and the JSON pointer for unknown keys or bad values, and, given the scene's
/// object names, for an "objects" entry that names none of them.
NetworkSettings networkSettingsFromJson(const JsonReader& network, const NetworkSettings& base,
                                        const std::vector<std::string>* sceneObjects = nullptr);
/// networkSettingsFromJson over the project defaults (a project file's section).
inline NetworkSettings networkSettingsFromJson(const JsonReader& network,
                                               const std::vector<std::string>* sceneObjects = nullptr) {
    return networkSettingsFromJson(network, NetworkSettings(), sceneObjects);
}
/// The section, every key written (NetworkSettings::keys()).
nlohmann::json toJson(const NetworkSettings& s);

/// Reads a "hidden" array: at least one layer size, each 1 … kMaxHiddenSize (InputError naming the
/// file and pointer otherwise).
std::vector<int> hiddenSizesFromJson(const JsonReader& hidden);

/// Reads a "partition" object over `base` (missing keys keep base's values); InputError names the
/// file and JSON pointer of an unknown key, a wrong type or an out-of-range value.
PartitionSettings partitionFromJson(const JsonReader& r, const PartitionSettings& base);
/// The "partition" object, every key written.
nlohmann::json partitionJson(const PartitionSettings& p);

}  // namespace rrf
