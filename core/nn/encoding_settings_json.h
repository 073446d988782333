#pragma once
/// The "encoding" array's codec (docs/file-formats.md, nn/encoding.h for the format): reads it into
/// the typed setting (nn/encoding_settings.h) and writes the setting back as it was read. The
/// project's "network" section, its "objects" entries and the model file's "input_encoding" read
/// the array here; nothing else sees the JSON.

#include <string>

#include <nlohmann/json.hpp>

#include "core/nn/derived_inputs.h"
#include "core/nn/encoding_settings.h"
#include "core/util/json_reader.h"

namespace rrf {

/// Reads an "encoding" array as written: each component's "type" (an unknown one lists the known
/// types), its "inputs" (a group name or a non-empty array of them) and its hyperparameter keys
/// (ranges checked, defaults where absent). InputError names the reader's file and the JSON pointer
/// of a value that is not an array or an object, an unknown key, a value of the wrong type or out
/// of range. Whether the groups fit a network is not checked here (readEncodingSettingsFor).
NetworkEncodingSettings readEncodingSettings(const JsonReader& r);
/// readEncodingSettings, then checked as a network of `inputs` record inputs and the `derived`
/// inputs builds it (buildInputEncoding): InputError names the pointer of a group it lacks, a group
/// named twice or encoded twice, or too many inputs for a type.
NetworkEncodingSettings readEncodingSettingsFor(const JsonReader& r, int inputs, const DerivedInputs& derived);
/// The array, each component with "type", "inputs" and the keys it was read with.
nlohmann::json encodingSettingsJson(const NetworkEncodingSettings& s);
/// readEncodingSettings of a JSON value (tests, tools): InputError names `file` and the pointer.
NetworkEncodingSettings encodingSettingsFromJson(const nlohmann::json& encoding, const std::string& file = "settings");

/// The EncodingFault of a setting at `pointer` of `file`: an InputError naming the file and the
/// pointer followed by the fault's.
EncodingFault failAtPointer(const std::string& file, const std::string& pointer);
/// failAtPointer of the reader's file and pointer.
inline EncodingFault failAtReader(const JsonReader& r) { return failAtPointer(r.file(), r.pointer()); }

}  // namespace rrf
