#include "core/pipeline/sweep_file.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>

#include "core/eval/error_metrics_json.h"
#include "core/render/term.h"
#include "core/util/atomic_file.h"
#include "core/util/json_reader.h"

namespace rrf {

namespace {

using nlohmann::json;

/// A figure's key, where it is set.
template <class T>
void putFigure(json& j, const char* key, const std::optional<T>& v) {
    if (v) j[key] = *v;
}

/// The keys of `other` (unknown to this build) under the figures this build writes.
json figuresObject(const JsonText& other) {
    json j = parseJsonText(other);
    return j.is_object() ? j : json::object();
}

// Each take* moves `key` out of `rest` into the figure when it holds a value of the figure's type
// (integers as integers, numbers as numbers or null for unknown) and leaves it there otherwise, so
// a key this build cannot read is written back as it was.
bool isFigure(const json& v) { return v.is_number_float() || v.is_null(); }
double figureOf(const json& v) { return v.is_null() ? std::numeric_limits<double>::quiet_NaN() : v.get<double>(); }

void takeFigure(json& rest, const char* key, std::optional<double>& v) {
    const auto it = rest.find(key);
    if (it == rest.end() || !isFigure(*it)) return;
    v = figureOf(*it);
    rest.erase(it);
}
void takeCount(json& rest, const char* key, std::optional<int64_t>& v) {
    const auto it = rest.find(key);
    if (it == rest.end() || !it->is_number_integer()) return;
    if (it->is_number_unsigned() && it->get<uint64_t>() > uint64_t(std::numeric_limits<int64_t>::max())) return;
    v = it->get<int64_t>();
    rest.erase(it);
}
void takeCount(json& rest, const char* key, std::optional<uint64_t>& v) {
    const auto it = rest.find(key);
    if (it == rest.end() || !it->is_number_unsigned()) return;
    v = it->get<uint64_t>();
    rest.erase(it);
}
void takeTerm(json& rest, const std::string& term, std::optional<SweepTermFigures>& v) {
    const std::string keys[3] = {term + "_relative_rmse", term + "_relative_rmse_noise_floor", term + "_relative_rmse_corrected"};
    for (const std::string& k : keys)
        if (!rest.contains(k) || !isFigure(rest[k])) return;
    v = SweepTermFigures{figureOf(rest[keys[0]]), figureOf(rest[keys[1]]), figureOf(rest[keys[2]])};
    for (const std::string& k : keys) rest.erase(k);
}
bool isInt(const json& v) {
    return v.is_number_integer() && v.get<int64_t>() >= std::numeric_limits<int>::min() &&
           v.get<int64_t>() <= std::numeric_limits<int>::max() &&
           !(v.is_number_unsigned() && v.get<uint64_t>() > uint64_t(std::numeric_limits<int>::max()));
}
void takeCurve(json& rest, std::optional<std::vector<SweepCurvePoint>>& v) {
    const auto it = rest.find("curve");
    if (it == rest.end() || !it->is_array()) return;
    std::vector<SweepCurvePoint> curve;
    for (const json& p : *it) {
        if (!p.is_object() || p.size() != 6 || !p.contains("object") || !isInt(p["object"]) || !p.contains("target") ||
            !p["target"].is_string() || !p.contains("epoch") || !isInt(p["epoch"]))
            return;
        for (const char* k : {"seconds", "train_loss", "validation_loss"})
            if (!p.contains(k) || !isFigure(p[k])) return;
        curve.push_back({p["object"].get<int>(), p["target"].get<std::string>(), p["epoch"].get<int>(), figureOf(p["seconds"]),
                         figureOf(p["train_loss"]), figureOf(p["validation_loss"])});
    }
    v = std::move(curve);
    rest.erase(it);
}

/// A number or null (unknown) as sweepJson writes it (noiseFigureJson).
double sweepFileOptional(const JsonReader& r, const char* key) {
    const JsonReader v = r.at(key);
    return v.value().is_null() ? SweepRow::kUnknown : v.number();
}

SweepRow sweepFileRow(const JsonReader& r) {
    r.requireObject();
    SweepRow row;
    row.setting = r.at("setting").string();
    const JsonReader stages = r.at("stage_seconds");
    stages.requireObject();
    for (const auto& kv : stages.value().items()) row.stageSeconds.emplace_back(kv.key(), stages.at(kv.key()).number());
    row.overall = errorStatsFromJson(r.at("error").value(), r.file(), JsonReader::child(r.pointer(), "error"));
    const JsonReader objects = r.at("objects");
    for (size_t i = 0, n = objects.requireArray(); i < n; ++i) {
        const JsonReader o = objects.at(i);
        const size_t id = size_t(o.at("id").integer(0, 1 << 20));
        if (row.perObject.size() <= id) row.perObject.resize(id + 1);
        row.perObject[id] = errorStatsFromJson(o.value(), o.file(), o.pointer());
    }
    row.extra = sweepRowFiguresFromJson(r.at("extra"));
    row.spp = int(r.integerOr("spp", 0, 0, 1 << 30));
    if (r.has("one_off_seconds")) {  // a model row
        row.oneOffSeconds = r.at("one_off_seconds").number();
        row.frameSeconds = sweepFileOptional(r, "frame_seconds");
        row.glslFrameSeconds = sweepFileOptional(r, "glsl_frame_seconds");
        const JsonReader b = r.at("break_even");
        if (!b.value().is_null()) {
            row.breakEven.known = b.at("known").boolean();
            row.breakEven.extrapolated = b.at("extrapolated").boolean();
            if (row.breakEven.known) {
                row.breakEven.spp = b.at("spp").number();
                row.breakEven.seconds = b.at("seconds").number();
            }
        }
    }
    return row;
}

std::vector<SweepRow> sweepFileRows(const JsonReader& r) {
    std::vector<SweepRow> rows;
    for (size_t i = 0, n = r.requireArray(); i < n; ++i) rows.push_back(sweepFileRow(r.at(i)));
    return rows;
}

nlohmann::json breakEvenJson(const SweepRow& row) {
    if (!isModelRow(row)) return nullptr;
    const BreakEven& b = row.breakEven;
    return {{"error", comparableError(row.overall)},
            {"error_is_corrected", !std::isnan(row.overall.relativeRmseCorrected)},
            {"known", b.known},
            {"spp", b.known ? nlohmann::json(b.spp) : nlohmann::json(nullptr)},
            {"seconds", b.known ? nlohmann::json(b.seconds) : nlohmann::json(nullptr)},
            {"extrapolated", b.extrapolated}};
}

}  // namespace

json toJson(const SweepRowFigures& f) {
    json j = figuresObject(f.other);
    putFigure(j, "parameters", f.parameters);
    putFigure(j, "model_bytes", f.modelBytes);
    putFigure(j, "leaves", f.leaves);
    putFigure(j, "leaf_epochs", f.leafEpochs);
    putFigure(j, "pixels_without_network", f.pixelsWithoutNetwork);
    putFigure(j, "non_finite_prediction_values", f.nonFinitePredictionValues);
    for (const auto& [term, figures] : {std::pair{Term::Direct, &f.direct}, std::pair{Term::Indirect, &f.indirect}})
        if (*figures) {
            const std::string name = termName(term);
            j[name + "_relative_rmse"] = (*figures)->relativeRmse;
            j[name + "_relative_rmse_noise_floor"] = noiseFigureJson((*figures)->relativeRmseNoiseFloor);
            j[name + "_relative_rmse_corrected"] = noiseFigureJson((*figures)->relativeRmseCorrected);
        }
    putFigure(j, "non_finite_samples_dropped", f.nonFiniteSamplesDropped);
    putFigure(j, "records", f.records);
    putFigure(j, "mean_record_spp", f.meanRecordSpp);
    putFigure(j, "records_at_spp_cap", f.recordsAtSppCap);
    if (f.curve) {
        json curve = json::array();
        for (const SweepCurvePoint& p : *f.curve)
            curve.push_back({{"object", p.object}, {"target", p.target}, {"epoch", p.epoch}, {"seconds", p.seconds},
                             {"train_loss", p.trainLoss}, {"validation_loss", p.validationLoss}});
        j["curve"] = curve;
    }
    return j;
}

SweepRowFigures sweepRowFiguresFromJson(const JsonReader& r) {
    SweepRowFigures f;
    if (!r.isObject()) return f;  // no build writes anything else
    json rest = r.value();
    takeCount(rest, "parameters", f.parameters);
    takeCount(rest, "model_bytes", f.modelBytes);
    takeCount(rest, "leaves", f.leaves);
    takeCount(rest, "leaf_epochs", f.leafEpochs);
    takeCount(rest, "pixels_without_network", f.pixelsWithoutNetwork);
    takeCount(rest, "non_finite_prediction_values", f.nonFinitePredictionValues);
    takeTerm(rest, termName(Term::Direct), f.direct);
    takeTerm(rest, termName(Term::Indirect), f.indirect);
    takeCount(rest, "non_finite_samples_dropped", f.nonFiniteSamplesDropped);
    takeCount(rest, "records", f.records);
    takeFigure(rest, "mean_record_spp", f.meanRecordSpp);
    takeCount(rest, "records_at_spp_cap", f.recordsAtSppCap);
    takeCurve(rest, f.curve);
    f.other = jsonText(rest);
    return f;
}

json toJson(const SweepResultFigures& f) {
    json j = figuresObject(f.other);
    putFigure(j, "loglog_slope_rmse", f.loglogSlopeRmse);
    if (f.loglogSlopeRmseCorrected) j["loglog_slope_rmse_corrected"] = noiseFigureJson(*f.loglogSlopeRmseCorrected);
    putFigure(j, "generate_seconds", f.generateSeconds);
    return j;
}

SweepResultFigures sweepResultFiguresFromJson(const JsonReader& r) {
    SweepResultFigures f;
    if (!r.isObject()) return f;
    json rest = r.value();
    takeFigure(rest, "loglog_slope_rmse", f.loglogSlopeRmse);
    takeFigure(rest, "loglog_slope_rmse_corrected", f.loglogSlopeRmseCorrected);
    takeFigure(rest, "generate_seconds", f.generateSeconds);
    f.other = jsonText(rest);
    return f;
}

nlohmann::json sweepJson(const Scene& scene, const SweepResult& r) {
    auto rowsJson = [&](const std::vector<SweepRow>& rows) {
        nlohmann::json out = nlohmann::json::array();
        for (const SweepRow& row : rows) {
            nlohmann::json stages = nlohmann::json::object(), objects = nlohmann::json::array();
            for (const auto& kv : row.stageSeconds) stages[kv.first] = kv.second;
            for (size_t id = 0; id < row.perObject.size(); ++id) {
                nlohmann::json o = toJson(row.perObject[id]);
                o["id"] = int(id);
                o["name"] = id < scene.objects.size() ? scene.objects[id].name : "";
                objects.push_back(o);
            }
            nlohmann::json j = {{"setting", row.setting}, {"stage_seconds", stages}, {"error", toJson(row.overall)},
                                {"objects", objects}, {"extra", toJson(row.extra)}};
            if (row.spp > 0) j["spp"] = row.spp;
            if (isModelRow(row)) {
                j["one_off_seconds"] = row.oneOffSeconds;
                j["frame_seconds"] = noiseFigureJson(row.frameSeconds);
                j["glsl_frame_seconds"] = noiseFigureJson(row.glslFrameSeconds);
                j["break_even"] = breakEvenJson(row);
            }
            out.push_back(j);
        }
        return out;
    };
    return {{"what", r.what},
            {"light_position", {r.lightPosition.x, r.lightPosition.y, r.lightPosition.z}},
            {"resolution", {r.width, r.height}},
            {"reference",
             {{"spp", r.referenceSpp}, {"seconds", r.referenceSeconds}, {"relative_rmse_noise_floor", noiseFigureJson(r.relativeNoiseFloor)}}},
            {"error_term", "global"},
            {"pixels", "object pixels the footprint mask keeps (the reference's G-buffer)"},
            {"metric", "per channel averaged over RGB; relative error |d|/(|ref|+0.01); *_noise_floor = the figure the "
                       "reference's own noise gives, *_corrected = the figure with the reference's per-pixel variance of the "
                       "mean subtracted from the squared error (clamped at 0); null when unknown"},
            {"cost", "path tracer rows: render seconds to reach their spp; model rows: one_off_seconds = data generation + "
                     "training, frame_seconds = one CPU frame (G-buffer + networks), glsl_frame_seconds = one GLSL frame where "
                     "measured; break_even = the spp and seconds the path tracer needs to reach the model's corrected relative "
                     "RMSE, log-log interpolated on path_tracer (extrapolated on its fitted line outside it)"},
            {"cancelled", r.cancelled},
            {"extra", toJson(r.extra)},
            {"rows", rowsJson(r.rows)},
            {"path_tracer", rowsJson(r.pathTracer)}};
}

SweepResult readSweepFile(const std::string& path) {
    const nlohmann::json doc = parseJsonText(readFile(path), path);
    const JsonReader r(doc, path);
    r.requireObject();
    SweepResult s;
    s.what = r.at("what").string();
    s.lightPosition = r.at("light_position").vec3();
    const JsonReader resolution = r.at("resolution");
    if (resolution.requireArray() != 2) resolution.fail("expected [width, height]");
    s.width = int(resolution.at(size_t(0)).integer(1, 1 << 16));
    s.height = int(resolution.at(size_t(1)).integer(1, 1 << 16));
    const JsonReader reference = r.at("reference");
    s.referenceSpp = int(reference.at("spp").integer(0, int64_t(1) << 40));
    s.referenceSeconds = reference.at("seconds").number();
    s.relativeNoiseFloor = sweepFileOptional(reference, "relative_rmse_noise_floor");
    s.cancelled = r.at("cancelled").boolean();
    s.extra = sweepResultFiguresFromJson(r.at("extra"));
    s.rows = sweepFileRows(r.at("rows"));
    s.pathTracer = sweepFileRows(r.at("path_tracer"));
    return s;
}

std::vector<std::string> sweepFilesIn(const std::string& dir) {
    namespace fs = std::filesystem;
    std::vector<std::string> files;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return files;
    for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
        if (e.is_regular_file(ec) && e.path().extension() == ".json") files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    return files;
}

}  // namespace rrf
