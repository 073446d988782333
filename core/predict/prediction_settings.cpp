#include "core/predict/prediction_settings.h"

namespace rrf {

PredictionSettings PredictionSettings::fromJson(const JsonReader& r) {
    r.checkKeys({"direct", "direct_samples", "seed"});
    PredictionSettings s;
    s.direct = r.choiceOr("direct", s.directName(), {"network", "exact"}) == "exact" ? Direct::Exact : Direct::Network;
    s.directSamples = int(r.integerOr("direct_samples", s.directSamples, 1, kMaxDirectSamples));
    s.seed = r.unsignedOr("seed", s.seed);
    return s;
}

nlohmann::json PredictionSettings::toJson() const {
    return {{"direct", directName()}, {"direct_samples", directSamples}, {"seed", seed}};
}

}  // namespace rrf
