// The report of an evaluation in JSON (see evaluation_json.h).
#include "core/eval/evaluation_json.h"

#include "core/eval/error_metrics_json.h"
#include "core/eval/flip_evaluation_json.h"
#include "core/eval/uncertainty_json.h"
#include "core/predict/footprint_mask_json.h"

namespace rrf {

namespace {
nlohmann::json vec(const Vec3& v) { return {v.x, v.y, v.z}; }
}  // namespace

nlohmann::json evaluationJson(const Scene& scene, const Evaluation& e) {
    const Prediction& p = e.prediction;
    nlohmann::json terms = nlohmann::json::object();
    for (int t = 0; t < kTermCount; ++t) {
        const TermErrors& te = e.terms[t];
        nlohmann::json objects = nlohmann::json::array();
        for (size_t id = 0; id < te.perObject.size(); ++id) {
            nlohmann::json o = toJson(te.perObject[id]);
            o["id"] = int(id);
            o["name"] = id < scene.objects.size() ? scene.objects[id].name : "";
            objects.push_back(o);
        }
        terms[termName(Term(t))] = {{"available", te.available}, {"overall", toJson(te.overall)}, {"objects", objects}};
    }
    nlohmann::json report = {
        {"light_position", vec(e.lightPosition)},
        {"footprint_mask", toJson(e.footprint.counts)},
        {"reference",
         {{"spp", e.referenceSpp},
          {"seconds", e.referenceSeconds},
          {"non_finite_samples_dropped", e.referenceNonFinite},
          {"noise", e.referenceNoiseKnown ? "per-pixel variance of the mean known: noise floor and corrected figures given"
                                          : "unknown (the reference has no variance images): noise floor and corrected figures are null"}}},
        {"prediction",
         {{"gbuffer_seconds", e.gbufferSeconds},
          {"inference_seconds", p.inferenceSeconds},
          {"exact_direct_seconds", p.directSeconds},
          {"gather_seconds", p.gatherSeconds},
          {"pixels_gathered", p.pixelsGathered},
          {"pixels_predicted", p.pixelsPredicted},
          {"pixels_without_network", p.pixelsWithoutNetwork},
          {"objects_without_network", p.objectsWithoutNetwork},
          {"non_finite_values", p.nonFinite},
          {"unavailable", p.unavailableWhy}}},
        {"metric",
         "per channel, averaged over RGB; relative error |d|/(|ref|+0.01); overall = all object pixels the footprint mask keeps; "
         "*_noise_floor = the figure the reference's own noise gives (sqrt of the mean variance of the mean, relative: "
         "divided by (|ref|+0.01)^2); *_corrected = sqrt(max(0, mean(d^2 - variance))) (relative: each term divided by "
         "(|ref|+0.01)^2), an estimate of the error against the noise-free truth"},
        {"terms", terms},
    };
    if (e.flip.available) {
        std::vector<std::string> names;
        for (const auto& o : scene.objects) names.push_back(o.name);
        report["flip"] = flipJson(e.flip, names);
    }
    if (e.uncertainty.available) {
        std::vector<std::string> names;
        for (const auto& o : scene.objects) names.push_back(o.name);
        report["uncertainty"] = toJson(e.uncertainty, names);
        report["prediction"]["spread_pixels"] = p.spreadPixels;
        report["prediction"]["spread_seconds"] = p.spreadSeconds;
    }
    return report;
}

nlohmann::json toJson(const EvaluationImages& images) {
    nlohmann::json ranges = nlohmann::json::object();
    for (const auto& [name, range] : images.falseColourRanges) ranges[name] = {range.first, range.second};
    return {{"files", images.files}, {"false_colour_ranges", ranges}, {"non_finite_map_pixels", images.nonFiniteMapPixels}};
}

}  // namespace rrf
