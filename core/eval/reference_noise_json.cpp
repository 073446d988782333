// The noise floors of a reference in JSON (see reference_noise_json.h).
#include "core/eval/reference_noise_json.h"

#include "core/eval/error_metrics_json.h"

namespace rrf {

nlohmann::json toJson(const ReferenceNoise& noise) {
    nlohmann::json j = nlohmann::json::object();
    for (Term t : kTerms)
        j[termName(t)] = {{"rmse", noiseFigureJson(noise.rmse[int(t)])}, {"relative_rmse", noiseFigureJson(noise.relativeRmse[int(t)])}};
    return j;
}

ReferenceNoise referenceNoiseFromJson(const nlohmann::json& j) {
    ReferenceNoise n;
    for (Term t : kTerms) {
        if (!j.contains(termName(t))) continue;
        const nlohmann::json& o = j.at(termName(t));
        n.rmse[int(t)] = noiseFigureFromJson(o.at("rmse"));
        n.relativeRmse[int(t)] = noiseFigureFromJson(o.at("relative_rmse"));
    }
    return n;
}

}  // namespace rrf
