#pragma once
/// The project's "runs" section (core/project/runs.h) in JSON: each run's typed fields under the
/// keys run_fields.h names beside them, and the keys this build does not know written back as they
/// were read.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/project/runs.h"
#include "core/util/json_reader.h"

namespace rrf {

/// One run as the "runs" section holds it.
nlohmann::json toJson(const Run& run);
/// Reads one run. Throws InputError naming the file, the JSON pointer and what was expected when
/// `r` is not a run object or a key this build knows (in the run, its settings, metrics or
/// timings) has the wrong type. Damaged scene overrides in its settings are described in
/// `warnings` (sceneOverridesFromJson) and the rest of them kept.
Run runFromJson(const JsonReader& r, std::vector<std::string>& warnings);

/// Reads the project's "runs" section. Runs are the workbench's own records, so one damaged entry
/// must not lock the user out of the project: it is skipped and described in `warnings` (file, JSON
/// pointer, what was expected), and the other runs are kept.
std::vector<Run> readRuns(const JsonReader& section, std::vector<std::string>& warnings);
/// The "runs" section for `runs`.
nlohmann::json runsToJson(const std::vector<Run>& runs);

}  // namespace rrf
