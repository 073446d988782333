#pragma once
/// A reference render's directory, as `rrf render`, `rrf pipeline`'s ground truth and the reference
/// store write it: the term images and render.json, which lists the light position, spp and
/// variance images.

#include <string>

#include "core/eval/evaluation.h"

namespace rrf {

/// Reads a directory written by `rrf render` (direct/indirect/global.exr or .pfm and render.json,
/// whose light position and spp it takes) and the variance images render.json lists under
/// "variance_images"; a render.json without that key (an older render) gives a reference whose
/// noise is unknown. Throws InputError naming the file.
Reference loadReference(const std::string& dir);

/// Writes render.json into `dir` for `ref`: its light position, spp, seconds and dropped samples,
/// the size width x height, "written_by" when `writtenBy` is not empty, and, when `ref` has them,
/// the variance images (written beside it as EXR) under "variance_images", so that loadReference
/// reads the directory back with its noise known. The term images are the caller's to write.
void writeReferenceDescription(const std::string& dir, const Reference& ref, int width, int height,
                               const std::string& writtenBy = "");

}  // namespace rrf
