#pragma once
/// The JSON of a data-generator run's statistics (data/generator_stats.h): the dataset header's
/// "stats" section, written and read here.

#include <string>

#include <nlohmann/json.hpp>

#include "core/data/generator_stats.h"
#include "core/util/json_reader.h"

namespace rrf {

/// The header's "stats" section.
nlohmann::json toJson(const GeneratorStats& s);
/// Reads a dataset header's "stats" section and its objects' counts. `file` names the dataset in
/// errors; a missing or mistyped field is an InputError naming its JSON pointer.
GeneratorStats generatorStatsFromHeader(const nlohmann::json& header, const std::string& file);

}  // namespace rrf
