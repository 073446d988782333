#pragma once
/// The FLIP figures of an evaluation (core/eval/flip_evaluation.h) in JSON, as the evaluation
/// report writes them.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/eval/flip_evaluation.h"

namespace rrf {

/// {"method", "pixels_per_degree", "exposures": {"start", "stop", "count"}, "hdr": stats,
/// "hdr_noise_floor" (null when unknown), "ldr": stats, "objects": [{"id", "name", "hdr": stats}]}
/// with stats = {"mean", "weighted_median", "weighted_first_quartile", "weighted_third_quartile",
/// "min", "max", "pixels", "non_finite_pixels"}; `names` are the objects' names by id.
nlohmann::json flipJson(const FlipEvaluation& f, const std::vector<std::string>& names);
/// FlipStats as flipJson writes them.
nlohmann::json flipStatsJson(const FlipStats& s);


}  // namespace rrf
