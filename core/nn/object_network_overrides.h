#pragma once
/// Per-object network choices (issue 26, item 5): the project's "network" section sets every
/// object's network, and its "objects" map changes them for the objects where another choice pays
/// — the reflected input for a near-mirror, a wider network for the object with the hardest light —
/// keyed by the scene's object name:
///
///     "network": {"hidden": [20, 10], "inputs": {"reflected": false},
///                 "objects": {"tall-box":  {"inputs": {"reflected": true}},
///                             "short-box": {"inputs": {"reflected": true}, "hidden": [32, 16],
///                                           "encoding": [{"type": "one_blob", "inputs": "reflected", "bins": 8}]}}}
///
/// An entry may set "hidden", "inputs" (nn/derived_inputs.h) and "encoding" (nn/encoding.h); what it
/// leaves out is the section's value. Everything else (activation, targets, ensemble, partition, the
/// trainer) is the section's for every object. An entry's "encoding" is checked against the entry's
/// own inputs (a component on "reflected" needs "inputs": {"reflected": true} in the entry or the
/// section). Names are checked against the scene when a project is read (Project: an unknown name is
/// an InputError naming /network/objects/<name> and the scene's objects).
///
/// A command-line flag or sweep value for one of these settings sets it for every network: it
/// replaces the section's value and drops the entries' overrides of that setting
/// (setHiddenEverywhere, ...), so `--hidden 20,10` trains 20-10 networks throughout.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/nn/derived_inputs.h"
#include "core/nn/encoding_settings.h"
#include "core/util/json_reader.h"

namespace rrf {

/// The network choices of one object that differ from the section's; empty fields keep the section's.
struct ObjectNetworkOverride {
    std::optional<std::vector<int>> hidden;   ///< "hidden"
    std::optional<DerivedInputs> inputs;      ///< "inputs"
    std::optional<NetworkEncodingSettings> encoding;  ///< "encoding" (as the section's)

    bool empty() const { return !hidden && !inputs && !encoding; }
    bool operator==(const ObjectNetworkOverride& o) const {
        return hidden == o.hidden && inputs == o.inputs && encoding == o.encoding;
    }
    bool operator!=(const ObjectNetworkOverride& o) const { return !(*this == o); }
    /// The keys it sets (only those).
    nlohmann::json toJson() const;
};

/// Overrides by object name.
using ObjectNetworkOverrides = std::map<std::string, ObjectNetworkOverride>;

/// What one object's networks are: the section's values with its override applied.
struct ObjectNetworkChoice {
    std::vector<int> hidden;
    DerivedInputs inputs;
    NetworkEncodingSettings encoding;  ///< empty: the identity
};

/// The choice for object `name`: `base` with the override of `name` (if any) applied.
ObjectNetworkChoice objectNetworkChoice(const ObjectNetworkChoice& base, const ObjectNetworkOverrides& overrides,
                                        const std::string& name);

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

/// The setting for every network: the section's value set, each entry's override of it dropped
/// (entries left with nothing are removed).
void dropHiddenOverrides(ObjectNetworkOverrides& overrides);
void dropInputsOverrides(ObjectNetworkOverrides& overrides);
void dropEncodingOverrides(ObjectNetworkOverrides& overrides);

}  // namespace rrf
