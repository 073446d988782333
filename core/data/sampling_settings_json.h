#pragma once
/// The JSON of the project's "sampling" section (data/sampling_settings.h), read and written here.

#include <nlohmann/json.hpp>

#include "core/data/sampling_settings.h"
#include "core/util/json_reader.h"

namespace rrf {

/// Reads a "sampling" section over `base`: missing keys keep base's values (the defaults for a
/// project file, the current settings for a script step). Throws InputError naming the reader's
/// file and the JSON pointer for unknown keys, wrong types or out-of-range values.
SamplingSettings samplingSettingsFromJson(const JsonReader& section, const SamplingSettings& base);
/// samplingSettingsFromJson over the project defaults (a project file's section).
inline SamplingSettings samplingSettingsFromJson(const JsonReader& section) {
    return samplingSettingsFromJson(section, SamplingSettings());
}
/// The section, every key written.
nlohmann::json toJson(const SamplingSettings& s);

}  // namespace rrf
