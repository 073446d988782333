#pragma once
/// Writing a finished (or cancelled) ground-truth render to a directory: `global`, `direct` and
/// `indirect` images in the chosen format, each term's per-pixel variance of the mean
/// (`variance_<term>`, always a float format: the noise floor of any error measured against the
/// render) and `render.json` recording the settings, the derived effects, timings, the NaN/Inf count
/// and the variance files — so an image never travels without what made it or how noisy it is.

#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/util/image_io.h"
#include "core/render/renderer.h"
#include "core/render/term.h"

namespace rrf {

/// render.json's "variance_images": the file name in the output directory by term name.
using VarianceImageNames = std::map<std::string, std::string>;

struct RenderOutputs {
    std::vector<std::string> images;     ///< paths written, global first
    std::vector<std::string> variances;  ///< variance_<term> paths written, direct, indirect, global
    std::string metadata;                ///< path of render.json
};

/// Writes each term's variance of the mean, `variances[int(t)]`, as variance_<term>.<ext> into `dir`
/// (created if missing), in `format` if it holds floats (EXR, PFM) and EXR otherwise. Appends the paths
/// to `written` and returns render.json's "variance_images" entry: {"<term>": file name in `dir`}.
VarianceImageNames writeVarianceImages(const std::string& dir, const std::array<const Image*, kTermCount>& variances,
                                       ImageFormat format, std::vector<std::string>& written);

/// Replaces directory `dir` (created if missing) as a whole (core/util/directory_replace.h) with
/// global/direct/indirect.<ext> in `format` at `exposureStops` and in each of `moreFormats` (format,
/// exposure: e.g. PNG previews beside the EXRs), variance_<term>.<exr|pfm> and render.json (with
/// "variance_images"; both left out below 2 spp, where the variance is unknown). The previous
/// render's files (isRenderOutputEntry) go, other files in `dir` are kept; a kill at any step leaves
/// the old render or the new one. Throws std::runtime_error naming the file or directory on failure.
RenderOutputs writeRenderOutputs(const std::string& dir, const Scene& scene, const Renderer& renderer,
                                 const RenderSnapshot& snapshot, ImageFormat format, float exposureStops,
                                 const std::vector<std::pair<ImageFormat, float>>& moreFormats = {},
                                 const RenderStats* stats = nullptr);

/// True for the names a render output directory's set consists of: render.json and
/// <term>.<any extension> or variance_<term>.<any extension>.
bool isRenderOutputEntry(const std::string& name);

/// Creates `dir` and its parents; throws std::runtime_error naming it if that is impossible.
void makeDirectories(const std::string& dir);

}  // namespace rrf
