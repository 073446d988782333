#pragma once
/// The JSON of the project's "prediction" section (predict/prediction_settings.h), read and written here.

#include <nlohmann/json.hpp>

#include "core/predict/prediction_settings.h"
#include "core/util/json_reader.h"

namespace rrf {

/// Reads the section (missing keys keep their defaults). Throws InputError naming the reader's
/// file and the JSON pointer for unknown keys or bad values.
PredictionSettings predictionSettingsFromJson(const JsonReader& section);
/// The section, every key written.
nlohmann::json toJson(const PredictionSettings& s);

}  // namespace rrf
