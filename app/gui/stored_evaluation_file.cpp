// The workbench's stored evaluation (stored_evaluation_file.h): the Objects table as JSON, with the key
// and model set it is valid for.
#include "app/gui/stored_evaluation_file.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/eval/error_metrics.h"
#include "core/eval/error_metrics_json.h"
#include "core/eval/reference_store_file.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/util/json_reader.h"

namespace rrf {

using nlohmann::json;

namespace {

constexpr const char* kFormat = "rrf-evaluation-1";

double figureOf(const JsonReader& r) {
    return r.value().is_null() ? std::numeric_limits<double>::quiet_NaN() : r.number();
}

json rowJson(const panels::ObjectErrorRow& row) {
    return {{"object", row.objectId}, {"name", row.name},          {"stats", toJson(row.stats)},
            {"flip", noiseFigureJson(row.flip)}, {"samples", row.samples}, {"train_seconds", row.trainSeconds}};
}

panels::ObjectErrorRow rowOf(const JsonReader& r) {
    r.checkKeys({"object", "name", "stats", "flip", "samples", "train_seconds"});
    panels::ObjectErrorRow row;
    row.objectId = int(r.at("object").integer(-1, std::numeric_limits<int>::max()));
    row.name = r.at("name").string();
    row.stats = errorStatsFromJson(r.at("stats").value(), r.file(), r.pointer() + "/stats");
    row.flip = figureOf(r.at("flip"));
    row.samples = r.at("samples").unsignedInteger();
    row.trainSeconds = r.at("train_seconds").number();
    return row;
}

json infoJson(const panels::EvaluationInfo& e) {
    json terms = json::array();
    for (Term t : kTerms) {
        const int i = int(t);
        json rows = json::array();
        for (const panels::ObjectErrorRow& row : e.rows[i]) rows.push_back(rowJson(row));
        terms.push_back({{"term", termName(t)}, {"available", e.available[i]}, {"overall", toJson(e.overall[i])}, {"rows", rows}});
    }
    json spread = json::array();
    for (const auto& [name, rho] : e.spreadSpearmanPerObject) spread.push_back({{"name", name}, {"rho", noiseFigureJson(rho)}});
    const FootprintCounts& f = e.footprint;
    return {{"light_position", {e.lightPosition.x, e.lightPosition.y, e.lightPosition.z}},
            {"reference_spp", e.referenceSpp},
            {"reference_noise_known", e.referenceNoiseKnown},
            {"footprint",
             {{"next_to_light", f.nextToLight}, {"object_edge", f.objectEdge}, {"normal_edge", f.normalEdge},
              {"depth_step", f.depthStep}, {"emitter_pixels", f.emitterPixels}}},
            {"seconds", e.seconds},
            {"terms", terms},
            {"flip_hdr", noiseFigureJson(e.flipHdr)},
            {"flip_noise_floor", noiseFigureJson(e.flipNoiseFloor)},
            {"flip_ldr", noiseFigureJson(e.flipLdr)},
            {"spread_spearman", noiseFigureJson(e.spreadSpearman)},
            {"spread_relative", noiseFigureJson(e.spreadRelative)},
            {"spread_per_object", spread}};
}

panels::EvaluationInfo infoOf(const JsonReader& r) {
    r.checkKeys({"light_position", "reference_spp", "reference_noise_known", "footprint", "seconds", "terms", "flip_hdr",
                 "flip_noise_floor", "flip_ldr", "spread_spearman", "spread_relative", "spread_per_object"});
    panels::EvaluationInfo e;
    e.lightPosition = r.at("light_position").vec3();
    e.referenceSpp = int(r.at("reference_spp").integer(0, std::numeric_limits<int>::max()));
    e.referenceNoiseKnown = r.at("reference_noise_known").boolean();
    const JsonReader f = r.at("footprint");
    f.checkKeys({"next_to_light", "object_edge", "normal_edge", "depth_step", "emitter_pixels"});
    e.footprint.nextToLight = f.at("next_to_light").unsignedInteger();
    e.footprint.objectEdge = f.at("object_edge").unsignedInteger();
    e.footprint.normalEdge = f.at("normal_edge").unsignedInteger();
    e.footprint.depthStep = f.at("depth_step").unsignedInteger();
    e.footprint.emitterPixels = f.at("emitter_pixels").unsignedInteger();
    e.seconds = r.at("seconds").number();
    const JsonReader terms = r.at("terms");
    if (terms.requireArray() != size_t(kTermCount)) terms.fail("expected one entry per term (" + std::to_string(kTermCount) + ")");
    for (Term t : kTerms) {
        const int i = int(t);
        const JsonReader term = terms.at(size_t(i));
        term.checkKeys({"term", "available", "overall", "rows"});
        if (term.at("term").string() != termName(t)) term.at("term").fail(std::string("expected \"") + termName(t) + "\"");
        e.available[i] = term.at("available").boolean();
        e.overall[i] = errorStatsFromJson(term.at("overall").value(), r.file(), term.pointer() + "/overall");
        const JsonReader rows = term.at("rows");
        for (size_t k = 0, n = rows.requireArray(); k < n; ++k) e.rows[i].push_back(rowOf(rows.at(k)));
    }
    e.flipHdr = figureOf(r.at("flip_hdr"));
    e.flipNoiseFloor = figureOf(r.at("flip_noise_floor"));
    e.flipLdr = figureOf(r.at("flip_ldr"));
    e.spreadSpearman = figureOf(r.at("spread_spearman"));
    e.spreadRelative = figureOf(r.at("spread_relative"));
    const JsonReader spread = r.at("spread_per_object");
    for (size_t k = 0, n = spread.requireArray(); k < n; ++k) {
        const JsonReader s = spread.at(k);
        s.checkKeys({"name", "rho"});
        e.spreadSpearmanPerObject.emplace_back(s.at("name").string(), figureOf(s.at("rho")));
    }
    e.valid = true;
    return e;
}

}  // namespace

void storeEvaluation(const std::string& path, const panels::EvaluationInfo& e, const EvaluationSource& source) {
    const json doc = {{"format", kFormat},
                      {"key", toJson(source.key)},
                      {"models", source.models},
                      {"models_checksum", source.modelsChecksum},
                      {"evaluation", infoJson(e)}};
    writeFileAtomically(path, doc.dump(1) + "\n");
}

StoredEvaluation loadEvaluation(const std::string& path, const EvaluationSource& source) {
    StoredEvaluation out;
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return out;
    try {
        const json doc = readJsonFile(path);
        const JsonReader r(doc, path);
        r.checkKeys({"format", "key", "models", "models_checksum", "evaluation"});
        if (r.at("format").string() != kFormat) r.at("format").fail(std::string("expected \"") + kFormat + "\"");
        const ReferenceKey key = referenceKeyFromJson(r.at("key").value(), path, "/key");
        const std::string models = r.at("models").string();
        const std::string checksum = r.at("models_checksum").string();
        // Stale is not damaged: the evaluation judged another ground truth or model set.
        if (!(key == source.key)) {
            out.why = "the scene, light, camera or size changed since it was made";
            return out;
        }
        if (models != source.models || checksum != source.modelsChecksum) {
            out.why = "it judged another model set (" + models + ") than the one loaded";
            return out;
        }
        out.info = infoOf(r.at("evaluation"));
    } catch (const std::exception& e) {
        out.info.reset();
        out.why = std::string("the stored evaluation cannot be read: ") + e.what();
        out.damaged = true;
    }
    return out;
}

}  // namespace rrf
