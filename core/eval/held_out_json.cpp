// The held-out summary in JSON (see held_out_json.h).
#include "core/eval/held_out_json.h"

namespace rrf {

nlohmann::json toJson(const Spread& s) {
    auto value = [&](double v) { return s.count ? nlohmann::json(v) : nlohmann::json(nullptr); };
    return {{"mean", value(s.mean)}, {"min", value(s.min)}, {"max", value(s.max)}, {"count", s.count}};
}

nlohmann::json toJson(const HeldOutSummary::Row& r) {
    return {{"rmse", toJson(r.rmse)},
            {"rmse_noise_floor", toJson(r.rmseNoiseFloor)},
            {"rmse_corrected", toJson(r.rmseCorrected)},
            {"relative_rmse", toJson(r.relativeRmse)},
            {"relative_rmse_noise_floor", toJson(r.relativeRmseNoiseFloor)},
            {"relative_rmse_corrected", toJson(r.relativeRmseCorrected)}};
}

nlohmann::json uncertaintyJson(const HeldOutSummary& s, const Scene& scene) {
    if (!s.spearman.count) return nullptr;
    nlohmann::json objects = nlohmann::json::array();
    for (size_t id = 0; id < s.spearmanPerObject.size(); ++id) {
        if (!s.spearmanPerObject[id].count) continue;
        objects.push_back({{"id", int(id)},
                           {"name", id < scene.objects.size() ? scene.objects[id].name : ""},
                           {"spearman", toJson(s.spearmanPerObject[id])}});
    }
    return {{"spearman", toJson(s.spearman)}, {"objects", objects}};
}

nlohmann::json flipJson(const HeldOutSummary& s) {
    if (!s.flipHdr.count) return nullptr;
    return {{"hdr", toJson(s.flipHdr)}, {"hdr_noise_floor", toJson(s.flipHdrNoiseFloor)}, {"ldr", toJson(s.flipLdr)}};
}

nlohmann::json heldOutJson(const Scene& scene, const HeldOutSummary& s) {
    nlohmann::json terms = nlohmann::json::object();
    for (int t = 0; t < kTermCount; ++t) {
        nlohmann::json objects = nlohmann::json::array();
        for (size_t id = 0; id < s.perObject[t].size(); ++id) {
            nlohmann::json o = toJson(s.perObject[t][id]);
            o["id"] = int(id);
            o["name"] = id < scene.objects.size() ? scene.objects[id].name : "";
            objects.push_back(o);
        }
        terms[termName(Term(t))] = {{"available", s.available[t]}, {"overall", toJson(s.overall[t])}, {"objects", objects}};
    }
    return terms;
}

}  // namespace rrf
