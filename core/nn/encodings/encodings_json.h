#pragma once
/// The JSON of every encoding type's hyperparameters (docs/file-formats.md; each type's keys are
/// documented beside its implementation, encodings/frequency.h, …): the codec the "encoding" array's
/// reader (nn/encoding_settings_json.h) and the model file (nn/encoding_json.h) use, so the encoding
/// classes and the registry (encodings/registry.h) hold typed EncodingParams only.

#include <nlohmann/json.hpp>

#include "core/nn/encodings/encoding_params.h"
#include "core/nn/encodings/registry.h"
#include "core/util/json_reader.h"

namespace rrf {

/// Reads "frequencies" and "include_input" of a component object (defaults where absent); InputError
/// names the reader's file and the key's pointer. Other keys are checked by the caller.
FrequencySettings frequencySettingsFromJson(const JsonReader& r);
/// Reads "bins" of a component object, as frequencySettingsFromJson.
OneBlobSettings oneBlobSettingsFromJson(const JsonReader& r);
/// Reads the hash grid's keys of a component object, as frequencySettingsFromJson; a combination out
/// of range (finest resolution, table size) fails at the component.
HashGridSettings hashGridSettingsFromJson(const JsonReader& r);
/// Reads the hyperparameter keys of `type` of a component object into that type's alternative.
EncodingParams encodingParamsFromJson(const EncodingType& type, const JsonReader& component);

/// Every hyperparameter key of the settings (what a component object written in full holds).
nlohmann::json toJson(const FrequencySettings& s);
nlohmann::json toJson(const OneBlobSettings& s);
nlohmann::json toJson(const HashGridSettings& s);
/// Every hyperparameter key of the alternative `params` holds.
nlohmann::json toJson(const EncodingParams& params);

}  // namespace rrf
