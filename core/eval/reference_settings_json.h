#pragma once
/// The project's "reference" section (core/eval/reference_settings.h) in JSON.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/eval/reference_settings.h"
#include "core/util/json_reader.h"

namespace rrf {

/// {"noise", "error_fraction", "spp_cap", "spp_per_pass", "width", "height"} (every key written).
nlohmann::json toJson(const ReferenceSettings& s);
/// Parses a "reference" section (missing keys keep their defaults). Throws InputError naming the
/// reader's file and the JSON pointer for unknown keys or values out of range.
ReferenceSettings referenceSettingsFromJson(const JsonReader& section);

}  // namespace rrf
