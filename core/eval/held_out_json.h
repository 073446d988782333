#pragma once
/// The held-out summary (core/eval/held_out.h) in JSON, as `rrf evaluate --held-out` writes it.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/eval/held_out.h"

namespace rrf {

/// {"mean", "min", "max", "count"}; the three numbers are null when count is 0.
nlohmann::json toJson(const Spread& s);
/// {"rmse", "rmse_noise_floor", "rmse_corrected", "relative_rmse", "relative_rmse_noise_floor",
/// "relative_rmse_corrected"}, each a spread.
nlohmann::json toJson(const HeldOutSummary::Row& r);
/// {"hdr", "hdr_noise_floor", "ldr"} spreads, or null when no evaluation had FLIP figures.
nlohmann::json flipJson(const HeldOutSummary& s);
/// {"spearman": spread, "objects": [{"id", "name", "spearman": spread}]}, or null when no
/// evaluation had a spread.
nlohmann::json uncertaintyJson(const HeldOutSummary& s, const Scene& scene);
/// The spreads per term: {term: {"available", "overall": row, "objects": [row + "id", "name"]}}.
nlohmann::json heldOutJson(const Scene& scene, const HeldOutSummary& s);

}  // namespace rrf
