#pragma once
/// The sweep file (docs/file-formats.md): a sweep's JSON report, written by sweepJson (`rrf sweep
/// --out`, the workbench's <project dir>/sweeps/<what>-<time>.json) and read back by readSweepFile,
/// so a project re-opened shows the sweeps it ran: the Cost panel's series come back with every
/// figure they had (errors with their noise floors, the stages' times, CPU and GLSL frame times,
/// break-evens). Per-object errors are read too.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/pipeline/sweep.h"
#include "core/util/json_reader.h"

namespace rrf {

/// The sweep as JSON: what, light position, resolution, reference, the readers' notes ("metric",
/// "cost"), "extra" (toJson of SweepResultFigures), then "rows" and "path_tracer", each row with its
/// setting, stage seconds, errors (overall and per object, named from `scene`), "extra" (toJson of
/// SweepRowFigures) and, for model rows, its cost and break-even.
nlohmann::json sweepJson(const Scene& scene, const SweepResult& r);

/// A row's figures as the object "extra" of a sweep file: one key per figure that is set
/// ("parameters", "model_bytes", "leaves", "leaf_epochs", "pixels_without_network",
/// "non_finite_prediction_values", "direct_relative_rmse" / "…_noise_floor" / "…_corrected" and the
/// same for "indirect", "non_finite_samples_dropped", "records", "mean_record_spp",
/// "records_at_spp_cap", "curve": [{"object", "target", "epoch", "seconds", "train_loss",
/// "validation_loss"}]), counts as integers, unknown figures as null, plus the keys of `other`.
nlohmann::json toJson(const SweepRowFigures& f);
/// The figures of a row's "extra": each key this build knows and can read sets its figure; every
/// other key (or one of another type, e.g. from a newer build) is kept in `other`. Never throws.
SweepRowFigures sweepRowFiguresFromJson(const JsonReader& r);
/// A sweep's figures as the top-level "extra": "loglog_slope_rmse", "loglog_slope_rmse_corrected",
/// "generate_seconds" where set (null when unknown), plus the keys of `other`.
nlohmann::json toJson(const SweepResultFigures& f);
/// The figures of the top-level "extra", as sweepRowFiguresFromJson.
SweepResultFigures sweepResultFiguresFromJson(const JsonReader& r);

/// The sweep `path` holds (what sweepJson wrote). Throws InputError naming the file and the JSON
/// pointer of a missing or mistyped member; members sweepJson writes for readers only ("metric",
/// "cost", ...) are ignored.
SweepResult readSweepFile(const std::string& path);

/// The sweep files in `dir` (its *.json, by name: the names start with the kind and the time they
/// were written, so one kind's sweeps come in the order they ran); none when `dir` does not exist.
std::vector<std::string> sweepFilesIn(const std::string& dir);

}  // namespace rrf
