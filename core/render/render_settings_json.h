#pragma once
/// The JSON of the project's "render" section (render/render_settings.h), read and written here.

#include <nlohmann/json.hpp>

#include "core/render/render_settings.h"
#include "core/util/json_reader.h"

namespace rrf {

/// The "render" section for `s` (every key written).
nlohmann::json renderSettingsToJson(const RenderSettings& s);
/// Parses a "render" section (missing keys keep their defaults). Throws InputError naming the
/// reader's file and the JSON pointer (below the section's own) for unknown keys or bad values.
RenderSettings parseRenderSettings(const JsonReader& section);

}  // namespace rrf
