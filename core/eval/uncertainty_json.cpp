// Uncertainty figures in JSON (see uncertainty_json.h).
#include "core/eval/uncertainty_json.h"

#include "core/eval/error_metrics_json.h"

namespace rrf {

nlohmann::json toJson(const UncertaintyStats& s) {
    // Undefined figures (no pixels, a constant side) are null, as unknown noise figures are.
    return {{"pixels", s.pixels},
            {"mean_relative_spread", noiseFigureJson(s.meanRelativeSpread)},
            {"mean_relative_error", noiseFigureJson(s.meanRelativeError)},
            {"spearman", noiseFigureJson(s.spearman)}};
}

nlohmann::json toJson(const UncertaintyEvaluation& u, const std::vector<std::string>& objectNames) {
    nlohmann::json objects = nlohmann::json::array();
    for (size_t id = 0; id < u.perObject.size(); ++id) {
        if (!u.perObject[id].pixels) continue;
        nlohmann::json o = toJson(u.perObject[id]);
        o["id"] = int(id);
        o["name"] = id < objectNames.size() ? objectNames[id] : "";
        objects.push_back(o);
    }
    return {{"available", u.available},
            {"measure", "relative spread mean_c sd_c / (|pred_c| + 0.01) of the ensemble members against the relative "
                        "error mean_c |d_c| / (|ref_c| + 0.01): Spearman rank correlation over the pixels"},
            {"overall", toJson(u.overall)},
            {"objects", objects}};
}

}  // namespace rrf
