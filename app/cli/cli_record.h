#pragma once
/// `--record` on rrf render/train/evaluate: the command's work becomes a run of the project, as the
/// workbench records it (core/pipeline/run_recording.h). Off by default: the CLI rewrites a user's
/// project file only when asked.

#include <optional>
#include <string>

#include "core/project/runs.h"

namespace rrf::cli {

/// Help text of the --record flag, naming what the command records.
std::string recordHelp(const std::string& what);

/// Starts recording a run of `kind` when `record` is set: checks that `input` is a project (an
/// InputError naming --record for a bare scene file), gives the run an id and, when `out` is empty,
/// points it at <project dir>/runs/<id>/<sub> (sub may be empty). Without `record`, `out` must be
/// given (InputError naming --out) and nothing is returned.
std::optional<Run> beginRecording(bool record, const std::string& input, const std::string& kind, std::string& out,
                                  const std::string& sub);

/// Appends `run` to the project file `input`, saves it and says so.
void finishRecording(const std::string& input, const Run& run);

}  // namespace rrf::cli
