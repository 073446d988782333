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

#include "core/nn/derived_inputs.h"
#include "core/nn/encoding_settings.h"

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

/// The setting for every network: the section's value set, each entry's override of it dropped
/// (entries left with nothing are removed).
void dropHiddenOverrides(ObjectNetworkOverrides& overrides);
void dropInputsOverrides(ObjectNetworkOverrides& overrides);
void dropEncodingOverrides(ObjectNetworkOverrides& overrides);

}  // namespace rrf
