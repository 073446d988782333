#pragma once
/// The error statistics of core/eval/error_metrics.h in JSON, as the evaluation reports, sweep files
/// and stored evaluations write them.

#include <string>

#include <nlohmann/json.hpp>

#include "core/eval/error_metrics.h"

namespace rrf {

/// A noise figure in JSON: the number, or null for NaN (unknown).
nlohmann::json noiseFigureJson(double value);
/// A noise figure read back: the number, NaN (unknown) for null or anything else that is not one.
double noiseFigureFromJson(const nlohmann::json& j);

/// {"pixels", "non_finite_pixels", "rmse", "rmse_noise_floor", "rmse_corrected", "relative_rmse",
/// "relative_rmse_noise_floor", "relative_rmse_corrected", "signed_relative_mean", "relmse",
/// "relmse_noise_floor", "relmse_corrected", "smape", "mae", "max_error", "mean_reference"};
/// the noise figures are null when unknown.
nlohmann::json toJson(const ErrorStats& s);
/// Reads what toJson() wrote (null noise figures → unknown, noiseKnown from them). Throws
/// InputError naming `file` and the member's pointer for a missing or mistyped member.
ErrorStats errorStatsFromJson(const nlohmann::json& j, const std::string& file, const std::string& pointer);

}  // namespace rrf
