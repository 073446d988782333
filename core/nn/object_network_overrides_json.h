#pragma once
/// The JSON of the per-object network entries (nn/object_network_overrides.h): the "network"
/// section's "objects" map, read and written here.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/nn/object_network_overrides.h"
#include "core/util/json_reader.h"

namespace rrf {

/// The keys the override sets (only those).
nlohmann::json toJson(const ObjectNetworkOverride& o);
/// Reads an "objects" map. `base` holds the section's values (an entry's "encoding" is checked
/// against the entry's inputs, else base's). InputError names the file and the JSON pointer of a
/// value that is not an object, an unknown key, a bad hidden size (hiddenSizesFromJson), a bad
/// "inputs" or an "encoding" the entry's inputs cannot take. An empty entry is dropped.
ObjectNetworkOverrides objectOverridesFromJson(const JsonReader& objects, const ObjectNetworkChoice& base);
/// The map with every entry's keys (empty entries left out).
nlohmann::json objectOverridesJson(const ObjectNetworkOverrides& overrides);

/// Throws InputError at `at` (its file and pointer) unless `name` is one of `sceneObjects`, listing
/// them: "no object named \"x\" in the scene (expected one of \"a\", \"b\")".
void requireSceneObjectName(const JsonReader& at, const std::string& name, const std::vector<std::string>& sceneObjects);
/// Throws InputError naming `objects`' file and /…/objects/<name> for the first entry whose name is
/// not in `sceneObjects`, listing them.
void checkOverrideNames(const JsonReader& objects, const std::vector<std::string>& sceneObjects);

}  // namespace rrf
