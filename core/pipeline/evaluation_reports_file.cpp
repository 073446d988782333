// The report files of the evaluation stages (see evaluation_reports_file.h).
#include "core/pipeline/evaluation_reports_file.h"

#include <nlohmann/json.hpp>

#include "core/eval/error_metrics_json.h"
#include "core/eval/evaluation_json.h"
#include "core/eval/held_out_json.h"
#include "core/eval/light_grid_json.h"
#include "core/eval/reference_noise_json.h"
#include "core/util/atomic_file.h"
#include "core/util/json_reader.h"

namespace rrf {

using nlohmann::json;

namespace {

/// The report's "reference_source": only the fields `o` has.
json originJson(const ReferenceOrigin& o) {
    json j = json::object();
    if (const std::optional<StoredReference>& e = o.storeEntry) {
        j["store_entry"] = e->dir;
        j["id"] = e->key.id();
        j["spp"] = e->spp;
        j["seconds"] = e->seconds;
        j["noise"] = toJson(e->noise);
        j["wanted_noise"] = noiseFigureJson(e->wantedNoise);
        j["noise_target"] = {{"noise", o.noiseTarget.relativeRmse},
                             {"error_fraction", o.noiseTarget.errorFraction},
                             {"spp_cap", o.noiseTarget.sppCap}};
    }
    if (o.fixedSpp) j["fixed_spp"] = *o.fixedSpp;
    if (o.seed) j["seed"] = *o.seed;
    if (o.directory) j["directory"] = *o.directory;
    return j;
}

}  // namespace

void EvaluationReports::writeLight(const std::string& file, const Scene& scene, const Evaluation& e,
                                   const ReferenceOrigin& origin, const EvaluationImages& images) {
    json report = evaluationJson(scene, e);
    if (!origin.empty()) report["reference_source"] = originJson(origin);
    report["images"] = toJson(images);
    writeFileAtomically(file, report.dump(2) + "\n");
    reports_.push_back(jsonText(report));
}

void EvaluationReports::writeHeldOut(const std::string& file, const Scene& scene, const HeldOutSummary& s) const {
    json evaluations = json::array();
    for (const JsonText& r : reports_) evaluations.push_back(parseJsonText(r));
    writeFileAtomically(file, json{{"summary", heldOutJson(scene, s)},
                                   {"flip", flipJson(s)},
                                   {"uncertainty", uncertaintyJson(s, scene)},
                                   {"evaluations", evaluations}}
                                      .dump(2) + "\n");
}

void writeLightGridReport(const std::string& file, const Scene& scene, const LightGridMap& map,
                          const std::vector<LightGridSlice>& slices) {
    json report = lightGridJson(scene, map);
    json list = json::array();
    for (const LightGridSlice& s : slices) list.push_back({{"y", s.y}, {"image", s.image}});
    report["slices"] = list;
    writeFileAtomically(file, report.dump(2) + "\n");
}

}  // namespace rrf
