#pragma once
/// Ground-truth render settings (the project's "render" section) and the estimator choice shared by
/// the path tracer, the data generator and the references.

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "core/util/json_reader.h"

namespace rrf {

enum class Estimator { NEE, Naive };

/// Ground-truth render settings ("render" section).
struct RenderSettings {
    int spp = 64;              ///< samples per pixel
    int width = 0, height = 0; ///< 0 = the scene camera's size
    Estimator estimator = Estimator::NEE;
    uint64_t seed = 1;
    int maxDepth = 64;         ///< hard bound on path length (Russian roulette ends paths before)
    float exposure = 0.f;      ///< stops, for PNG output
};

/// The "render" section for `s` (every key written).
nlohmann::json renderSettingsToJson(const RenderSettings& s);
/// Parses a "render" section (missing keys keep their defaults). Throws InputError naming the
/// reader's file and the JSON pointer (below the section's own) for unknown keys or bad values.
RenderSettings parseRenderSettings(const JsonReader& section);

}  // namespace rrf
