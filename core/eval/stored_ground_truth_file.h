#pragma once
/// The workbench's last finished ground-truth render, kept beside the project (issue 29: everything
/// a project shows is restored on reopen), so that opening it again shows the image at once instead
/// of rendering it from nothing.
///
/// A render is determined by its ReferenceKey (core/eval/reference_store.h: scene content, camera,
/// light position, resolution, estimator, depth, seed) and its spp: the renderer's sample k of pixel
/// i is Rng(seed, i, k), so a stored render of the same key and spp has exactly the pixels a new one
/// would. A stored render of another key — the scene, the light or the size changed — is never
/// used, and the next finished render replaces it.
///
/// On disk, one directory (the workbench's is <project dir>/ground_truth):
///   ground_truth.json          {"format": "rrf-ground-truth-1", "key": the ReferenceKey (core/eval/reference_store_file.h), "spp",
///                               "passes", "samples", "non_finite_samples", "seconds", "relative_error",
///                               "rays", "shadow_rays", "variance": whether the variance images are there}
///   {direct,indirect,global}.exr, and variance_{direct,indirect,global}.exr when "variance"
/// written whole (core/util/directory_replace.h), never a mixture of two renders.
#include <optional>
#include <string>

#include "core/eval/reference_store.h"
#include "core/render/renderer.h"

namespace rrf {

/// The directory beside a project (in its folder) where the workbench keeps its ground truth.
constexpr const char* kGroundTruthDir = "ground_truth";

/// Writes `snapshot` (a finished render of `key`) into `dir` as one set, replacing what was there.
/// The variance images are written when the snapshot has them (varianceKnown()). Throws
/// std::runtime_error naming the directory when it cannot be written (the old set is then kept).
void storeGroundTruth(const std::string& dir, const ReferenceKey& key, const RenderSnapshot& snapshot,
                      const RenderStats& stats);

/// What loadGroundTruth found.
struct StoredGroundTruth {
    std::optional<RenderSnapshot> snapshot;  ///< the stored render, when it is the one asked for
    RenderStats stats;                       ///< its renderer's statistics (rays, samples, seconds)
    /// Why there is none: empty when nothing is stored (a first render), else e.g. "the scene, light,
    /// camera or size changed", "it has 16 spp, 64 are asked for", or the problem with a damaged
    /// file (named).
    std::string why;
};

/// The render stored in `dir` when its key is `key` and it has exactly `spp` samples per pixel.
/// Never throws: a missing, damaged or other render is reported in `why` (the caller renders).
StoredGroundTruth loadGroundTruth(const std::string& dir, const ReferenceKey& key, int spp);

}  // namespace rrf
