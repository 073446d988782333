#include "core/predict/prediction_settings_json.h"

namespace rrf {

PredictionSettings predictionSettingsFromJson(const JsonReader& r) {
    r.checkKeys({"direct", "direct_samples", "seed", "gather"});
    PredictionSettings s;
    s.direct = r.choiceOr("direct", s.directName(), {"network", "exact"}) == "exact" ? PredictionSettings::Direct::Exact : PredictionSettings::Direct::Network;
    s.directSamples = int(r.integerOr("direct_samples", s.directSamples, 1, kMaxDirectSamples));
    s.seed = r.unsignedOr("seed", s.seed);
    if (const std::optional<JsonReader> found = r.find("gather")) {
        const JsonReader& g = *found;
        g.checkKeys({"min_exponent", "lobe_samples", "diffuse_samples", "direct_samples", "second_lobe_samples",
                     "second_diffuse_samples", "caustic_samples", "objects"});
        s.gather.minExponent = g.numberOr("min_exponent", s.gather.minExponent, 0.0, 1e6);
        s.gather.lobeSamples = int(g.integerOr("lobe_samples", s.gather.lobeSamples, 0, kMaxGatherSamples));
        s.gather.diffuseSamples = int(g.integerOr("diffuse_samples", s.gather.diffuseSamples, 0, kMaxGatherSamples));
        s.gather.directSamples = int(g.integerOr("direct_samples", s.gather.directSamples, 1, kMaxDirectSamples));
        s.gather.secondLobeSamples = int(g.integerOr("second_lobe_samples", s.gather.secondLobeSamples, 0, kMaxGatherSamples));
        s.gather.secondDiffuseSamples =
            int(g.integerOr("second_diffuse_samples", s.gather.secondDiffuseSamples, 0, kMaxGatherSamples));
        s.gather.causticSamples = int(g.integerOr("caustic_samples", s.gather.causticSamples, 0, kMaxGatherSamples));
        if (const std::optional<JsonReader> objects = g.find("objects")) {
            const size_t n = objects->requireArray();
            for (size_t i = 0; i < n; ++i) s.gather.objects.push_back(objects->at(i).string());
        }
    }
    return s;
}

nlohmann::json toJson(const PredictionSettings& s) {
    const PredictionSettings::Gather& gather = s.gather;
    return {{"direct", s.directName()},
            {"direct_samples", s.directSamples},
            {"seed", s.seed},
            {"gather",
             {{"min_exponent", gather.minExponent},
              {"lobe_samples", gather.lobeSamples},
              {"diffuse_samples", gather.diffuseSamples},
              {"direct_samples", gather.directSamples},
              {"second_lobe_samples", gather.secondLobeSamples},
              {"second_diffuse_samples", gather.secondDiffuseSamples},
              {"caustic_samples", gather.causticSamples},
              {"objects", gather.objects}}}};
}

}  // namespace rrf
