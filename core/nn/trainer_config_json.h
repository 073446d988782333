#pragma once
/// The JSON of a trainer object (nn/trainer_config.h for the format): the project's "trainer"
/// section, a run's and a model file's trainer, read and written here.

#include <string>

#include <nlohmann/json.hpp>

#include "core/nn/trainer_config.h"
#include "core/util/json_reader.h"

namespace rrf {

/// Parses a trainer object (the project's "trainer" section, a run's or a model file's trainer).
/// A missing "type" means levenberg_marquardt; "lm" is accepted as a short name. Every error names
/// the reader's file and the JSON pointer of the offending key.
TrainerConfig trainerConfigFromJson(const JsonReader& r);
/// The same for a bare JSON object; `file` and `where` (the JSON pointer of `j`) only label errors.
TrainerConfig trainerConfigFromJson(const nlohmann::json& j, const std::string& file = "",
                                    const std::string& where = "/trainer");
/// The same for an object written inline, trainerConfigFromJson({{"type", "adam"}}) (tests): without
/// this overload such a braced list could also build a JsonReader, and the call would be ambiguous.
inline TrainerConfig trainerConfigFromJson(nlohmann::json::initializer_list_t object) {
    return trainerConfigFromJson(nlohmann::json(object));
}
/// Full settings, every key written, so a model file records exactly what trained it.
nlohmann::json toJson(const TrainerConfig& c);

}  // namespace rrf
