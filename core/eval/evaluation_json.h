#pragma once
/// The report of an evaluation (core/eval/evaluation.h) in JSON, as `rrf evaluate` and the
/// pipeline's evaluation stage write it.

#include <nlohmann/json.hpp>

#include "core/eval/evaluation.h"

namespace rrf {

/// Report of one evaluation: settings, timings, NaN/Inf counts, errors per term and object (each with
/// the reference's noise floor and the noise-corrected figures, null when unknown), and "flip"
/// (flipJson) when the FLIP figures were computed.
nlohmann::json evaluationJson(const Scene& scene, const Evaluation& e);
/// {"files": [...], "false_colour_ranges": {map: [lo, hi]}, "non_finite_map_pixels": n}.
nlohmann::json toJson(const EvaluationImages& images);

}  // namespace rrf
