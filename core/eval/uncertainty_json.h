#pragma once
/// The uncertainty figures of an evaluation (core/eval/uncertainty.h) in JSON, as the evaluation
/// report writes them.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/eval/uncertainty.h"

namespace rrf {

/// {"pixels", "mean_relative_spread", "mean_relative_error", "spearman"}.
nlohmann::json toJson(const UncertaintyStats& s);
/// {"available", "overall", "objects": [{id, name, ...}]}, names from `objectNames` by id.
nlohmann::json toJson(const UncertaintyEvaluation& u, const std::vector<std::string>& objectNames);

}  // namespace rrf
