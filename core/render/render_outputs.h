#pragma once
/// Writing a finished (or cancelled) ground-truth render to a directory: `global`, `direct` and
/// `indirect` images in the chosen format plus `render.json` recording the settings, the derived
/// effects, timings and the NaN/Inf count — so an image never travels without what made it.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/util/image_io.h"
#include "core/render/renderer.h"

namespace rrf {

struct RenderOutputs {
    std::vector<std::string> images;  ///< paths written, global first
    std::string metadata;             ///< path of render.json
};

/// Metadata of a render as JSON (settings, effects, statistics, light position, scene hash).
nlohmann::json renderMetadata(const Scene& scene, const Renderer& renderer, const RenderSnapshot& snapshot);

/// Writes global/direct/indirect.<ext> and render.json into `dir` (created if missing), each file
/// atomically. Throws std::runtime_error naming the file on failure.
RenderOutputs writeRenderOutputs(const std::string& dir, const Scene& scene, const Renderer& renderer,
                                 const RenderSnapshot& snapshot, ImageFormat format, float exposureStops);

/// Creates `dir` and its parents; throws std::runtime_error naming it if that is impossible.
void makeDirectories(const std::string& dir);

}  // namespace rrf
