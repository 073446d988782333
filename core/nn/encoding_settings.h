#pragma once
/// The "encoding" setting as a typed value (issue 27; docs/design.md §10a): what the project's
/// "network": {"encoding": [...]} array and an "objects" entry's "encoding" say, parsed once by the
/// project reader (nn/encoding_settings_json.h) and read by everything else without JSON — the
/// trainers, the time estimates, the sweeps, the CLI and the panels.
///
/// A setting does not fix a network's encoding: the "brdf" group's size is the records' BRDF
/// parameter count and "reflected" exists only where a network derives it, so each network builds
/// its InputEncoding from the setting for its own inputs (buildInputEncoding, networkEncoding in
/// nn/encoding_presets.h).
///
/// A component remembers how the file spelled it (a lone group as a string or in an array, which
/// hyperparameter keys were written) so that a project, model index or run record writes back the
/// JSON it read: the same JSON in, the same JSON out.

#include <functional>
#include <string>
#include <vector>

#include "core/nn/derived_inputs.h"
#include "core/nn/encoding.h"
#include "core/nn/encodings/encoding_params.h"

namespace rrf {

struct EncodingType;

/// One component of the setting: its type and hyperparameters, and the input groups it reads.
struct EncodingSettings {
    EncodingParams params;            ///< the type is the alternative (encodingTypeOf(params))
    std::vector<std::string> groups;  ///< "position", "view", "light", "normal", "brdf", "reflected", as written
    /// "inputs" was an array (a lone group may be written as a string or as a one-element array).
    bool groupsListed = false;
    /// The hyperparameter keys the component wrote (sorted); the others hold their defaults and are
    /// left out when written. Every key for a component made in code (component()).
    std::vector<std::string> keys;

    /// Its row of the encoding registry.
    const EncodingType& type() const;
    /// Same type, hyperparameters, groups and spelling (what its JSON compares).
    bool operator==(const EncodingSettings& o) const {
        return params == o.params && groups == o.groups && groupsListed == o.groupsListed && keys == o.keys;
    }
    bool operator!=(const EncodingSettings& o) const { return !(*this == o); }
};

/// The setting: the components in feature order; empty = the identity (Ren et al.'s raw inputs).
using NetworkEncodingSettings = std::vector<EncodingSettings>;

/// A component made in code (the named encodings, tests): every hyperparameter key counts as
/// written, and "inputs" is a string for one group and an array for several.
EncodingSettings encodingComponent(EncodingParams params, std::vector<std::string> groups);

/// True when `a` and `b` encode alike (types, hyperparameters and groups), however they are spelled:
/// a named encoding written with every key (a saved model's components) is that named encoding.
bool sameEncoding(const NetworkEncodingSettings& a, const NetworkEncodingSettings& b);

/// Reports a setting that does not fit a network: `at` is the JSON pointer below the setting of
/// what is wrong ("/0/inputs/1": component 0's second group; "/1": component 1 itself) and `what`
/// says why. It must throw (the builder does not go on after it returns).
using EncodingFault = std::function<void(const std::string& at, const std::string& what)>;

/// The encoding of a network of `inputs` record inputs (12 + brdfCount) and the `derived` inputs from
/// the setting `s`: each component's groups resolved to input indices, its encoding made and its
/// parameters placed (paramOffset). Calls `fault` for an unknown or repeated group, a group already
/// encoded by another component, a group this network lacks ("reflected" without the derived input,
/// an empty "brdf"), more inputs than the type reads, or hyperparameters out of range.
InputEncoding buildInputEncoding(const NetworkEncodingSettings& s, int inputs, const DerivedInputs& derived,
                                 const EncodingFault& fault);

}  // namespace rrf
