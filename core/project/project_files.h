#pragma once
/// The files a project keeps beside its project file — its runs (runs/<id>/: images, models,
/// reports), its reference store (references/) and its generated dataset (data/) — travel with it
/// when it is saved under another directory (Save As), so that every run still re-opens from the
/// new place. Run artifacts are stored relative to the project directory (run_recording.h); files
/// outside it are relinked (their relative paths re-expressed from the new directory) instead.

#include <string>
#include <vector>

#include "core/project/runs.h"

namespace rrf {

/// What carryProjectFiles did.
struct CarriedFiles {
    int linked = 0;   ///< files hard-linked into the new directory (no copy of the bytes)
    int copied = 0;   ///< files copied (hard links impossible, e.g. across file systems)
    int relinked = 0; ///< artifact paths outside the project directory rewritten for the new one
    std::vector<std::string> problems;  ///< files that could not be carried (path and reason)
};

/// Brings runs/<id>/ of every run in `runs`, references/ and data/ from `oldDir` to `newDir` (both
/// project directories), hard-linking each file and copying when linking fails; a file already at
/// its destination is left alone. Artifacts and the "dataset" setting that point outside `oldDir`
/// are rewritten relative to `newDir`. Nothing happens when the two directories are the same.
/// Problems do not stop the others: they are listed in the result.
CarriedFiles carryProjectFiles(const std::string& oldDir, const std::string& newDir, std::vector<Run>& runs);

}  // namespace rrf
