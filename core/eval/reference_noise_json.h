#pragma once
/// The noise floors of a reference (core/eval/reference_noise.h) in JSON, as the reference store
/// and the evaluation reports write them.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/eval/reference_noise.h"

namespace rrf {

/// {"direct": {"rmse", "relative_rmse"}, "indirect": …, "global": …}; unknown figures are null.
nlohmann::json toJson(const ReferenceNoise& noise);
/// Reads what toJson() wrote: a missing term stays unknown, null or a non-number reads as unknown.
/// Throws nlohmann::json::exception when a listed term lacks "rmse" or "relative_rmse".
ReferenceNoise referenceNoiseFromJson(const nlohmann::json& j);

}  // namespace rrf
