// Objects panel: the last evaluation's error per object for the term the views show (RMSE and
// relative RMSE, each with the ground truth's noise floor and the corrected (noise subtracted) figure,
// MAE, max, pixels, training samples and time), sortable by any column; clicking a row selects the
// object, which the views highlight (ViewState::selectedObject, as the Scene panel does).
// The figures are core's ErrorStats from rrf::evaluate (core/eval/error_metrics.h, per channel, over
// the footprint mask's pixels), the same numbers `rrf evaluate` reports; the panel only sorts and
// shows them. An unknown noise floor (a ground truth without its variance) reads "unknown", never 0.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include <imgui.h>

#include "core/eval/evaluation.h"
#include "panels/figure_text.h"
#include "panels/panels.h"

namespace rrf::panels {

namespace objects_panel_detail {
namespace {
const char* const kColumnNames[] = {"object",         "RMSE",    "RMSE noise floor",   "RMSE corrected", "rel. RMSE",
                                    "rel. noise floor", "rel. corrected", "bias", "relMSE", "relMSE corrected",
                                    "SMAPE",          "FLIP",    "MAE",     "max",              "pixels",         "samples",
                                    "train s"};
static_assert(sizeof kColumnNames / sizeof kColumnNames[0] == size_t(ObjectColumn::Count), "one name per column");

double key(const ObjectErrorRow& r, ObjectColumn c) {
    switch (c) {
        case ObjectColumn::Rmse: return r.stats.rmse;
        case ObjectColumn::RmseNoiseFloor: return r.stats.rmseNoiseFloor;
        case ObjectColumn::RmseCorrected: return r.stats.rmseCorrected;
        case ObjectColumn::RelativeRmse: return r.stats.relativeRmse;
        case ObjectColumn::RelativeNoiseFloor: return r.stats.relativeRmseNoiseFloor;
        case ObjectColumn::RelativeCorrected: return r.stats.relativeRmseCorrected;
        case ObjectColumn::Bias: return r.stats.signedRelativeMean;
        case ObjectColumn::RelMse: return r.stats.relMse;
        case ObjectColumn::RelMseCorrected: return r.stats.relMseCorrected;
        case ObjectColumn::Smape: return r.stats.smape;
        case ObjectColumn::Flip: return r.flip;
        case ObjectColumn::Mae: return r.stats.mae;
        case ObjectColumn::Max: return r.stats.maxError;
        case ObjectColumn::Pixels: return double(r.stats.pixels);
        case ObjectColumn::Samples: return double(r.samples);
        case ObjectColumn::TrainSeconds: return r.trainSeconds;
        default: return double(r.objectId);
    }
}

/// The figures from RMSE to SMAPE in column order (unknown noise figures read "unknown").
std::array<double, 10> rmseFigures(const ErrorStats& s) {
    return {s.rmse,   s.rmseNoiseFloor, s.rmseCorrected,     s.relativeRmse, s.relativeRmseNoiseFloor, s.relativeRmseCorrected,
            s.signedRelativeMean, s.relMse, s.relMseCorrected, s.smape};
}

/// The FLIP cell: the figure, or "-" where there is none (a term other than global, or an
/// evaluation without FLIP figures).
std::string flipText(double v) {
    if (std::isnan(v)) return "-";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

/// An optional figure in CSV: empty when unknown, so a reader sees a missing value, never 0.
std::string csvNumber(double v) {
    if (std::isnan(v)) return "";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

std::string csvQuote(const std::string& s) {
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

/// The buttons and the evaluation's summary above the table: `e` for term `term`; Evaluate needs
/// loaded models (`modelsLoaded`); the buttons' requests go to `requests`.
void drawHeader(const EvaluationInfo& e, Term term, bool modelsLoaded, std::vector<Request>& requests) {
    ImGui::BeginDisabled(e.running || !modelsLoaded);
    if (ImGui::Button("Evaluate")) requests.push_back({Command::Evaluate, {}, -1});
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
        ImGui::SetTooltip("compares the prediction of the trained models with the ground truth (CPU predictor)");
    ImGui::SameLine();
    ImGui::BeginDisabled(!e.valid);
    if (ImGui::Button("Export CSV...")) requests.push_back({Command::ExportObjectsCsv, {}, -1});
    ImGui::EndDisabled();
    ImGui::SameLine();
    if (e.running) ImGui::TextUnformatted("evaluating...");
    else if (e.valid)
        figureText("%s term, light (%.3g, %.3g, %.3g), ground truth %d spp, noise %s", termName(term),
                    e.lightPosition.x, e.lightPosition.y, e.lightPosition.z, e.referenceSpp,
                    e.referenceNoiseKnown ? "known" : "unknown (no variance)");
    else figureTextDisabled("No evaluation yet: train, then Evaluate.");
    if (e.valid) {
        figureTextDisabled("noise floor: the error the ground truth's own noise gives; corrected (noise subtracted): "
                            "the error against the noise-free truth");
        figureTextDisabled("%s", e.footprint.describe().c_str());
        if (!std::isnan(e.flipHdr))
            figureTextDisabled("FLIP (global term): HDR-FLIP %.4g (noise floor %s), LDR-FLIP %.4g", e.flipHdr,
                                noiseFigureText(e.flipNoiseFloor).c_str(), e.flipLdr);
        if (!std::isnan(e.spreadSpearman)) {
            std::string per;
            for (const auto& [name, rho] : e.spreadSpearmanPerObject) per += "  " + name + " " + noiseFigureText(rho);
            figureTextDisabled("Uncertainty (ensemble members' spread, global term): mean relative spread %.4g, rank "
                                "correlation with the error %.3f;%s",
                                e.spreadRelative, e.spreadSpearman, per.c_str());
        }
    }
}
}  // namespace
}  // namespace objects_panel_detail

EvaluationInfo evaluationInfo(const Evaluation& e, const Scene& scene, const ModelSet& models) {
    EvaluationInfo info;
    info.valid = true;
    info.lightPosition = e.lightPosition;
    info.referenceSpp = e.referenceSpp;
    info.referenceNoiseKnown = e.referenceNoiseKnown;
    info.footprint = e.footprint.counts;
    std::map<int, std::pair<uint64_t, double>> training;
    for (const ObjectNetworks& o : models.objects)
        for (const auto& [target, m] : o.byTarget) {
            auto& t = training[o.objectId];
            uint64_t records = 0;  // a partitioned model's leaves share out the object's records
            for (const NetworkModel& leaf : m.leaves) {
                const TrainResult& r = leaf.training;
                records += uint64_t(r.trainSamples + r.validationSamples + r.testSamples);
                t.second += r.seconds;
            }
            t.first = std::max<uint64_t>(t.first, records);
        }
    const FlipEvaluation& f = e.flip;
    if (f.available && f.hdr.pixels) {
        info.flipHdr = f.hdr.mean;
        info.flipNoiseFloor = f.hdrNoiseFloor;
        info.flipLdr = f.ldr.mean;
    }
    if (e.uncertainty.available && e.uncertainty.overall.pixels) {
        info.spreadSpearman = e.uncertainty.overall.spearman;
        info.spreadRelative = e.uncertainty.overall.meanRelativeSpread;
        for (size_t id = 0; id < e.uncertainty.perObject.size() && id < scene.objects.size(); ++id)
            if (e.uncertainty.perObject[id].pixels)
                info.spreadSpearmanPerObject.emplace_back(scene.objects[id].name, e.uncertainty.perObject[id].spearman);
    }
    for (Term t : kTerms) {
        const TermErrors& te = e.term(t);
        info.available[int(t)] = te.available;
        info.overall[int(t)] = te.overall;
        for (size_t id = 0; id < te.perObject.size() && id < scene.objects.size(); ++id) {
            if (te.perObject[id].pixels == 0 && !training.count(int(id))) continue;  // out of view, untrained
            ObjectErrorRow row;
            row.objectId = int(id);
            row.name = scene.objects[id].name;
            row.stats = te.perObject[id];
            if (t == Term::Global && f.available && id < f.hdrPerObject.size() && f.hdrPerObject[id].pixels)
                row.flip = f.hdrPerObject[id].mean;
            if (training.count(int(id))) row.samples = training[int(id)].first, row.trainSeconds = training[int(id)].second;
            info.rows[int(t)].push_back(row);
        }
    }
    return info;
}

std::vector<ObjectErrorRow> sortedObjectRows(const std::vector<ObjectErrorRow>& rows, ObjectColumn column, bool ascending) {
    std::vector<ObjectErrorRow> out = rows;
    std::stable_sort(out.begin(), out.end(), [&](const ObjectErrorRow& a, const ObjectErrorRow& b) {
        if (column == ObjectColumn::Object) return ascending ? a.name < b.name : b.name < a.name;
        const double ka = objects_panel_detail::key(a, column), kb = objects_panel_detail::key(b, column);
        // Unknown figures (NaN) go last in either direction, which keeps the order strict and weak.
        if (std::isnan(ka) || std::isnan(kb)) return !std::isnan(ka) && std::isnan(kb);
        return ascending ? ka < kb : kb < ka;
    });
    return out;
}

std::string objectRowsCsv(const std::vector<ObjectErrorRow>& rows, const char* term) {
    // The noise columns follow the older ones, so readers of the earlier layout keep their columns.
    std::string csv = "term,object_id,object,rmse,relative_rmse,mae,max,pixels,samples,train_seconds,rmse_noise_floor,"
                      "rmse_corrected,relative_rmse_noise_floor,relative_rmse_corrected,signed_relative_mean,relmse,"
                      "relmse_noise_floor,relmse_corrected,smape,flip\n";
    char buf[256];
    for (const ObjectErrorRow& r : rows) {
        std::snprintf(buf, sizeof buf, ",%.9g,%.9g,%.9g,%.9g,%llu,%llu,%.6g", r.stats.rmse, r.stats.relativeRmse,
                      r.stats.mae, r.stats.maxError, (unsigned long long)r.stats.pixels, (unsigned long long)r.samples,
                      r.trainSeconds);
        csv += std::string(term) + "," + std::to_string(r.objectId) + "," + objects_panel_detail::csvQuote(r.name) + buf + "," +
               objects_panel_detail::csvNumber(r.stats.rmseNoiseFloor) + "," +
               objects_panel_detail::csvNumber(r.stats.rmseCorrected) + "," +
               objects_panel_detail::csvNumber(r.stats.relativeRmseNoiseFloor) + "," +
               objects_panel_detail::csvNumber(r.stats.relativeRmseCorrected) + "," +
               objects_panel_detail::csvNumber(r.stats.signedRelativeMean) + "," +
               objects_panel_detail::csvNumber(r.stats.relMse) + "," + objects_panel_detail::csvNumber(r.stats.relMseNoiseFloor) +
               "," + objects_panel_detail::csvNumber(r.stats.relMseCorrected) + "," +
               objects_panel_detail::csvNumber(r.stats.smape) + "," + objects_panel_detail::csvNumber(r.flip) + "\n";
    }
    return csv;
}

std::vector<PairedObjectRow> pairedObjectRows(const EvaluationInfo& a, const EvaluationInfo& b, Term t) {
    std::map<int, PairedObjectRow> rows;
    auto add = [&](const EvaluationInfo& e, bool first) {
        if (!e.valid) return;
        for (const ObjectErrorRow& r : e.rows[int(t)]) {
            PairedObjectRow& p = rows[r.objectId];
            p.objectId = r.objectId;
            p.name = r.name;
            (first ? p.a : p.b) = r.stats.relativeRmse;
            p.noiseFloor = r.stats.relativeRmseNoiseFloor;
        }
    };
    add(a, true);
    add(b, false);
    std::vector<PairedObjectRow> out;
    for (auto& kv : rows) out.push_back(std::move(kv.second));
    return out;
}

std::string objectsTableMismatch(const ObjectsPanelView& panel) {
    const EvaluationInfo& e = panel.evaluation;
    if (panel.view.compareSource == CompareSource::RunPair)
        return "The Views show two runs: their per-object errors are in the table below.";
    if (!e.valid) return {};
    // "runs/x/models/" and "runs/x/models" are one directory.
    auto normal = [](const std::string& dir) {
        std::filesystem::path p = std::filesystem::path(dir).lexically_normal();
        return p.has_filename() ? p : p.parent_path();
    };
    // Models live in runs/<run id>/models: the run id names them.
    auto runOf = [&](const std::string& modelsDir) { return normal(modelsDir).parent_path().filename().string(); };
    if (panel.modelsDir.empty())
        return "This table judged the models of " + runOf(e.modelsDir) + "; no models are loaded now.";
    if (!e.modelsDir.empty() && normal(e.modelsDir) != normal(panel.modelsDir))
        return "This table judged the models of " + runOf(e.modelsDir) + "; the prediction shows " +
               runOf(panel.modelsDir) + ". Press Evaluate for the models shown.";
    if (panel.view.compareSource == CompareSource::Run)
        return "This table judged the prediction; the Views compare a saved run instead.";
    return {};
}

namespace objects_panel_detail {
namespace {
/// The per-object errors of the two runs `p` compares, for term `term`.
void drawPairTable(const RunPair& p, Term term) {
    if (!p.errorsA.valid && !p.errorsB.valid) {
        figureTextDisabled("No per-object errors: render a ground truth, then compare the runs again.");
        return;
    }
    // Columns as wide as their content, scrolling sideways in a narrow pane (nothing cut off). Not
    // resizable: ImGui stops fitting a resizable column to its content after the first frames, so
    // figures that arrive later would be cut.
    const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY |
                                  ImGuiTableFlags_ScrollX | ImGuiTableFlags_SizingFixedFit;
    if (!ImGui::BeginTable("##pair", 5, flags)) return;
    ImGui::TableSetupScrollFreeze(1, 1);
    const std::string a = "A " + p.nameA + " rel. RMSE", b = "B " + p.nameB + " rel. RMSE";
    ImGui::TableSetupColumn("object");
    ImGui::TableSetupColumn(a.c_str());
    ImGui::TableSetupColumn(b.c_str());
    ImGui::TableSetupColumn("B - A");
    ImGui::TableSetupColumn("noise floor");
    ImGui::TableHeadersRow();
    for (const PairedObjectRow& r : pairedObjectRows(p.errorsA, p.errorsB, term)) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::Text("#%d %s", r.objectId, r.name.c_str());
        for (double v : {r.a, r.b, r.b - r.a, r.noiseFloor}) {
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(noiseFigureText(v).c_str());
        }
    }
    ImGui::EndTable();
}
}  // namespace
}  // namespace objects_panel_detail

void drawObjectsPanel(const ObjectsPanelView& panel) {
    objects_panel_detail::drawHeader(panel.evaluation, panel.view.term, !panel.modelsDir.empty(), panel.actions.requests);
    const std::string mismatch = objectsTableMismatch(panel);
    if (!mismatch.empty()) figureTextColored(ImVec4(1.f, 0.8f, 0.3f, 1.f), "%s", mismatch.c_str());
    if (panel.view.compareSource == CompareSource::RunPair) {
        objects_panel_detail::drawPairTable(panel.runPair, panel.view.term);
        return;
    }
    const EvaluationInfo& e = panel.evaluation;
    const int t = int(panel.view.term);
    if (!e.valid) return;
    if (!e.available[t]) {
        figureTextDisabled("The networks do not predict the %s term (see the Network panel's targets).",
                           termName(panel.view.term));
        return;
    }
    // Columns as wide as their content, the object column frozen while the figures scroll sideways
    // in a narrow pane (nothing cut off); not resizable, as in the pair table above.
    const ImGuiTableFlags flags = ImGuiTableFlags_Sortable | ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg |
                                  ImGuiTableFlags_ScrollY | ImGuiTableFlags_ScrollX | ImGuiTableFlags_SizingFixedFit;
    if (!ImGui::BeginTable("##objects", int(ObjectColumn::Count), flags)) return;
    ImGui::TableSetupScrollFreeze(1, 1);
    for (int c = 0; c < int(ObjectColumn::Count); ++c)
        ImGui::TableSetupColumn(objects_panel_detail::kColumnNames[c], c == 0 ? ImGuiTableColumnFlags_DefaultSort : 0, 0.f,
                                ImGuiID(c));
    ImGui::TableHeadersRow();
    for (int c = 0; c < int(ObjectColumn::Count); ++c)
        if (ImGui::TableGetColumnFlags(c) & ImGuiTableColumnFlags_IsHovered) {
            const ObjectColumn col = ObjectColumn(c);
            if (col == ObjectColumn::RmseNoiseFloor || col == ObjectColumn::RelativeNoiseFloor)
                ImGui::SetTooltip("noise floor: the error the ground truth's own Monte Carlo noise gives\n(a perfect prediction's expected error); unknown without its variance");
            else if (col == ObjectColumn::RmseCorrected || col == ObjectColumn::RelativeCorrected)
                ImGui::SetTooltip("corrected (noise subtracted): sqrt(max(0, mean(d^2 - Var(ref))))\nan estimate of the error against the noise-free truth");
            else if (col == ObjectColumn::Bias)
                ImGui::SetTooltip("bias: mean d / (|ref| + 0.01), signed (> 0: the prediction is above the ground truth);\nthe RMSE is the spread, this is the offset");
            else if (col == ObjectColumn::RelMse || col == ObjectColumn::RelMseCorrected)
                ImGui::SetTooltip("relMSE: mean d^2 / (ref^2 + 0.01), tev's relative squared error (no root);\ncorrected: the ground truth's variance subtracted");
            else if (col == ObjectColumn::Smape)
                ImGui::SetTooltip("SMAPE: mean |d| / (|pred| + |ref| + 0.01), in [0, 1]; not noise-corrected");
            else if (col == ObjectColumn::Flip)
                ImGui::SetTooltip("FLIP: mean HDR-FLIP (Andersson et al.), the perceived difference in [0, 1], over the\n"
                                  "reference's exposure range; global term only (\"-\" for the others)");
        }
    ObjectsView& v = panel.objectsView;
    if (ImGuiTableSortSpecs* specs = ImGui::TableGetSortSpecs()) {
        if (specs->SpecsDirty && specs->SpecsCount > 0) {
            v.sortColumn = ObjectColumn(specs->Specs[0].ColumnUserID);
            v.ascending = specs->Specs[0].SortDirection != ImGuiSortDirection_Descending;
        }
        specs->SpecsDirty = false;
    }
    for (const ObjectErrorRow& r : sortedObjectRows(e.rows[t], v.sortColumn, v.ascending)) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::PushID(r.objectId);
        const bool selected = panel.view.selectedObject == r.objectId;
        char label[96];
        std::snprintf(label, sizeof label, "#%d %s", r.objectId, r.name.c_str());
        if (ImGui::Selectable(label, selected, ImGuiSelectableFlags_SpanAllColumns))
            panel.view.selectedObject = selected ? -1 : r.objectId;  // click again to clear the highlight
        ImGui::PopID();
        for (double value : objects_panel_detail::rmseFigures(r.stats)) {
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(noiseFigureText(value).c_str());
        }
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(objects_panel_detail::flipText(r.flip).c_str());
        for (double value : {r.stats.mae, r.stats.maxError}) {
            ImGui::TableNextColumn();
            ImGui::Text("%.4g", value);
        }
        ImGui::TableNextColumn();
        ImGui::Text("%llu", (unsigned long long)r.stats.pixels);
        ImGui::TableNextColumn();
        ImGui::Text("%llu", (unsigned long long)r.samples);
        ImGui::TableNextColumn();
        ImGui::Text("%.2f", r.trainSeconds);
    }
    const ErrorStats& o = e.overall[t];
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextDisabled("all objects");
    for (double value : objects_panel_detail::rmseFigures(o)) {
        ImGui::TableNextColumn();
        ImGui::TextDisabled("%s", noiseFigureText(value).c_str());
    }
    ImGui::TableNextColumn();
    ImGui::TextDisabled("%s", objects_panel_detail::flipText(panel.view.term == Term::Global ? e.flipHdr : std::nan("")).c_str());
    for (double value : {o.mae, o.maxError}) {
        ImGui::TableNextColumn();
        ImGui::TextDisabled("%.4g", value);
    }
    ImGui::TableNextColumn();
    ImGui::TextDisabled("%llu", (unsigned long long)o.pixels);
    ImGui::EndTable();
}

}  // namespace rrf::panels
