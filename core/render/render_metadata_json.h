#pragma once
/// render.json, the metadata of a render output directory (render/render_outputs.h writes it beside
/// the images): settings, effects, statistics, light position, scene hash and contents.

#include <string>

#include <nlohmann/json.hpp>

#include "core/render/render_outputs.h"
#include "core/render/renderer.h"

namespace rrf {

/// Metadata of a render as JSON (settings, effects, statistics, light position, scene hash). The
/// statistics are `stats` when given (a render restored from a store, whose renderer never ran),
/// else the renderer's.
nlohmann::json renderMetadata(const Scene& scene, const Renderer& renderer, const RenderSnapshot& snapshot,
                              const RenderStats* stats = nullptr);
/// render.json's text: renderMetadata with "variance_images" when `varianceImages` is given
/// (writeVarianceImages' names), indented by 2, with a final newline.
std::string renderMetadataText(const Scene& scene, const Renderer& renderer, const RenderSnapshot& snapshot,
                               const RenderStats* stats, const VarianceImageNames* varianceImages);

}  // namespace rrf
