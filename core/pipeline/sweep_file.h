#pragma once
/// Sweeps read back from the JSON files they were written to (sweepJson: `rrf sweep --out`, the
/// workbench's <project dir>/sweeps/<what>-<time>.json), so a project re-opened shows the sweeps it
/// ran: the Cost panel's series come back with every figure they had (errors with their noise
/// floors, the stages' times, CPU and GLSL frame times, break-evens). Per-object errors are read too.

#include <string>
#include <vector>

#include "core/pipeline/sweep.h"

namespace rrf {

/// The sweep `path` holds (what sweepJson wrote). Throws InputError naming the file and the JSON
/// pointer of a missing or mistyped member; members sweepJson writes for readers only ("metric",
/// "cost", ...) are ignored.
SweepResult readSweepFile(const std::string& path);

/// The sweep files in `dir` (its *.json, by name: the names start with the kind and the time they
/// were written, so one kind's sweeps come in the order they ran); none when `dir` does not exist.
std::vector<std::string> sweepFilesIn(const std::string& dir);

}  // namespace rrf
