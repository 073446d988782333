// The reports of a sweep (core/pipeline/sweep.h): CSV, training-curve CSV, JSON and the readable table.
// Every model row carries its cost columns (one-off and per-frame seconds) and its break-even against
// the path tracer's series of the same sweep (core/eval/break_even.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "core/eval/error_metrics_json.h"
#include "core/pipeline/sweep.h"

namespace rrf {

namespace {

/// A CSV field: quoted when it holds a comma (grid "4,4,4", hidden "20,10") or a quote (RFC 4180).
std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char ch : text) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return quoted + "\"";
}

std::string num(double v) {
    if (!std::isfinite(v)) return "nan";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

/// A noise figure, time or break-even in CSV: empty when unknown (NaN), so a reader sees a missing
/// value, never 0.
std::string optionalField(double v) { return std::isnan(v) ? std::string() : num(v); }

nlohmann::json optionalJson(double v) { return noiseFigureJson(v); }

bool isModelRow(const SweepRow& row) { return !std::isnan(row.oneOffSeconds); }

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

std::string sweepBreakEvenText(const SweepRow& row) {
    return breakEvenText(row.breakEven, comparableError(row.overall), !std::isnan(row.overall.relativeRmseCorrected),
                         row.frameSeconds, row.glslFrameSeconds);
}

std::string sweepCsv(const Scene& scene, const SweepResult& r) {
    std::ostringstream out;
    std::vector<std::string> stages;
    for (const std::vector<SweepRow>* rows : {&r.rows, &r.pathTracer})
        for (const SweepRow& row : *rows)
            for (const auto& s : row.stageSeconds)
                if (std::find(stages.begin(), stages.end(), s.first) == stages.end()) stages.push_back(s.first);
    out << "what,setting";
    for (const std::string& s : stages) out << "," << s << "_seconds";
    out << ",pixels,rmse,rmse_noise_floor,rmse_corrected,relative_rmse,relative_rmse_noise_floor,relative_rmse_corrected,"
           "mae,max_error";
    for (const Object& o : scene.objects)
        out << "," << o.name << "_rmse," << o.name << "_relative_rmse," << o.name << "_relative_rmse_noise_floor," << o.name
            << "_relative_rmse_corrected";
    out << ",spp,one_off_seconds,frame_seconds,glsl_frame_seconds,breakeven_spp,breakeven_seconds,breakeven_extrapolated,"
           "parameters,model_bytes\n";
    // A model row's size (parameters incl. encoding tables, float64 payload bytes); empty for the path tracer.
    auto count = [](const SweepRow& row, const char* key) {
        return row.extra.contains(key) && row.extra[key].is_number_integer() ? std::to_string(row.extra[key].get<int64_t>())
                                                                              : std::string();
    };
    auto line = [&](const std::string& what, const SweepRow& row) {
        out << what << "," << csvField(row.setting);
        for (const std::string& s : stages) {
            double v = std::numeric_limits<double>::quiet_NaN();
            for (const auto& kv : row.stageSeconds)
                if (kv.first == s) v = kv.second;
            out << "," << num(v);
        }
        const ErrorStats& e = row.overall;
        out << "," << e.pixels << "," << num(e.rmse) << "," << optionalField(e.rmseNoiseFloor) << ","
            << optionalField(e.rmseCorrected) << "," << num(e.relativeRmse) << "," << optionalField(e.relativeRmseNoiseFloor)
            << "," << optionalField(e.relativeRmseCorrected) << "," << num(e.mae) << "," << num(e.maxError);
        for (size_t id = 0; id < scene.objects.size(); ++id) {
            const bool seen = id < row.perObject.size() && row.perObject[id].pixels > 0;
            const ErrorStats& o = seen ? row.perObject[id] : ErrorStats{};
            out << "," << (seen ? num(o.rmse) : "") << "," << (seen ? num(o.relativeRmse) : "") << ","
                << optionalField(o.relativeRmseNoiseFloor) << "," << optionalField(o.relativeRmseCorrected);
        }
        const bool model = isModelRow(row), known = model && row.breakEven.known;
        out << "," << (row.spp > 0 ? std::to_string(row.spp) : "") << "," << optionalField(row.oneOffSeconds) << ","
            << optionalField(row.frameSeconds) << "," << optionalField(row.glslFrameSeconds) << ","
            << (known ? num(row.breakEven.spp) : "") << "," << (known ? num(row.breakEven.seconds) : "") << ","
            << (known ? (row.breakEven.extrapolated ? "1" : "0") : "") << "," << count(row, "parameters") << ","
            << count(row, "model_bytes") << "\n";
    };
    for (const SweepRow& row : r.rows) line(r.what, row);
    for (const SweepRow& row : r.pathTracer) line("path_tracer", row);
    return out.str();
}

std::string sweepCurveCsv(const SweepResult& r) {
    std::ostringstream out;
    bool any = false;
    for (const SweepRow& row : r.rows) {
        if (!row.extra.contains("curve")) continue;
        if (!any) out << "trainer,object,target,epoch,seconds,train_loss,validation_loss\n";
        any = true;
        for (const nlohmann::json& p : row.extra["curve"]) {
            const double val = p["validation_loss"].is_number() ? p["validation_loss"].get<double>() : std::nan("");
            out << csvField(row.setting) << "," << p["object"].get<int>() << "," << p["target"].get<std::string>() << ","
                << p["epoch"].get<int>() << "," << num(p["seconds"].get<double>()) << ","
                << num(p["train_loss"].get<double>()) << "," << num(val) << "\n";
        }
    }
    return out.str();
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
                                {"objects", objects}, {"extra", row.extra}};
            if (row.spp > 0) j["spp"] = row.spp;
            if (isModelRow(row)) {
                j["one_off_seconds"] = row.oneOffSeconds;
                j["frame_seconds"] = optionalJson(row.frameSeconds);
                j["glsl_frame_seconds"] = optionalJson(row.glslFrameSeconds);
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
             {{"spp", r.referenceSpp}, {"seconds", r.referenceSeconds}, {"relative_rmse_noise_floor", optionalJson(r.relativeNoiseFloor)}}},
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
            {"extra", r.extra},
            {"rows", rowsJson(r.rows)},
            {"path_tracer", rowsJson(r.pathTracer)}};
}

std::string sweepTable(const SweepResult& r) {
    std::ostringstream out;
    char line[640];
    auto rowsTable = [&](const std::string& what, const std::vector<SweepRow>& rows) {
        const std::string rule10(12, '-'), rule11(13, '-');
        std::snprintf(line, sizeof line,
                      "| %-10s | %-58s | %10s | %11s | %10s | %10s | %11s | %10s | %10s |\n|%s|%s|%s|%s|%s|%s|%s|%s|%s|\n",
                      what.c_str(), "wall time per stage", "RMSE", "noise floor", "corrected", "rel.RMSE", "noise floor",
                      "corrected", "MAE", rule10.c_str(), std::string(60, '-').c_str(), rule10.c_str(), rule11.c_str(),
                      rule10.c_str(), rule10.c_str(), rule11.c_str(), rule10.c_str(), rule10.c_str());
        out << line;
        for (const SweepRow& row : rows) {
            std::string stages;
            for (const auto& kv : row.stageSeconds) {
                std::snprintf(line, sizeof line, "%s %.3f s  ", kv.first.c_str(), kv.second);
                stages += line;
            }
            const ErrorStats& e = row.overall;
            std::snprintf(line, sizeof line, "| %-10s | %-58s | %10.4g | %11s | %10s | %10.4g | %11s | %10s | %10.4g |\n",
                          row.setting.c_str(), stages.c_str(), e.rmse, noiseFigureText(e.rmseNoiseFloor).c_str(),
                          noiseFigureText(e.rmseCorrected).c_str(), e.relativeRmse,
                          noiseFigureText(e.relativeRmseNoiseFloor).c_str(), noiseFigureText(e.relativeRmseCorrected).c_str(),
                          e.mae);
            out << line;
        }
    };
    rowsTable(r.what, r.rows);
    if (!r.pathTracer.empty()) {
        out << "\nthe path tracer against the same reference (another seed):\n";
        rowsTable("spp", r.pathTracer);
    }
    out << "noise floor: the error the reference's own noise gives; corrected: the error with that noise subtracted\n";
    std::snprintf(line, sizeof line, "all points: %dx%d, against one reference (%d spp, relative RMSE noise floor %s), global term\n",
                  r.width, r.height, r.referenceSpp, noiseFigureText(r.relativeNoiseFloor).c_str());
    out << line;
    if (r.extra.contains("loglog_slope_rmse")) {
        const auto slope = [&](const char* key) {
            return r.extra.contains(key) && r.extra[key].is_number() ? r.extra[key].get<double>() : std::nan("");
        };
        std::snprintf(line, sizeof line, "log-log slope of RMSE vs spp: %.3f raw, %s corrected (Monte Carlo: -0.5)\n",
                      slope("loglog_slope_rmse"), noiseFigureText(slope("loglog_slope_rmse_corrected")).c_str());
        out << line;
    }
    bool header = false;
    for (const SweepRow& row : r.rows) {
        if (!isModelRow(row)) continue;
        if (!header) out << "break-even (what the model's error costs the path tracer):\n";
        header = true;
        const auto size = [&](const char* key) {
            return row.extra.contains(key) && row.extra[key].is_number() ? row.extra[key].get<double>() : std::nan("");
        };
        std::snprintf(line, sizeof line, "  %s %s: %.0f parameters, %.3g MB; one-off %.3g s (data + training); ", r.what.c_str(),
                      row.setting.c_str(), size("parameters"), size("model_bytes") / 1e6, row.oneOffSeconds);
        out << line << sweepBreakEvenText(row) << "\n";
    }
    return out.str();
}

}  // namespace rrf
