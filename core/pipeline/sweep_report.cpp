// The reports of a sweep (core/pipeline/sweep.h): CSV, training-curve CSV and the readable table (the
// JSON report is the sweep file, core/pipeline/sweep_file.h).
// Every model row carries its cost columns (one-off and per-frame seconds) and its break-even against
// the path tracer's series of the same sweep (core/eval/break_even.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>

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

/// A model row's size (parameters incl. encoding tables, float64 payload bytes) in CSV; empty for the path tracer.
std::string countField(const std::optional<int64_t>& v) { return v ? std::to_string(*v) : std::string(); }

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
            << (known ? (row.breakEven.extrapolated ? "1" : "0") : "") << "," << countField(row.extra.parameters) << ","
            << countField(row.extra.modelBytes) << "\n";
    };
    for (const SweepRow& row : r.rows) line(r.what, row);
    for (const SweepRow& row : r.pathTracer) line("path_tracer", row);
    return out.str();
}

std::string sweepCurveCsv(const SweepResult& r) {
    std::ostringstream out;
    bool any = false;
    for (const SweepRow& row : r.rows) {
        if (!row.extra.curve) continue;
        if (!any) out << "trainer,object,target,epoch,seconds,train_loss,validation_loss\n";
        any = true;
        for (const SweepCurvePoint& p : *row.extra.curve)
            out << csvField(row.setting) << "," << p.object << "," << p.target << "," << p.epoch << "," << num(p.seconds) << ","
                << num(p.trainLoss) << "," << num(p.validationLoss) << "\n";
    }
    return out.str();
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
    if (r.extra.loglogSlopeRmse) {
        std::snprintf(line, sizeof line, "log-log slope of RMSE vs spp: %.3f raw, %s corrected (Monte Carlo: -0.5)\n",
                      *r.extra.loglogSlopeRmse, noiseFigureText(r.extra.loglogSlopeRmseCorrected.value_or(std::nan(""))).c_str());
        out << line;
    }
    bool header = false;
    for (const SweepRow& row : r.rows) {
        if (!isModelRow(row)) continue;
        if (!header) out << "break-even (what the model's error costs the path tracer):\n";
        header = true;
        const auto size = [](const std::optional<int64_t>& v) { return v ? double(*v) : std::nan(""); };
        std::snprintf(line, sizeof line, "  %s %s: %.0f parameters, %.3g MB; one-off %.3g s (data + training); ", r.what.c_str(),
                      row.setting.c_str(), size(row.extra.parameters), size(row.extra.modelBytes) / 1e6, row.oneOffSeconds);
        out << line << sweepBreakEvenText(row) << "\n";
    }
    return out.str();
}

}  // namespace rrf
