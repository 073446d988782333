// Objects panel: the last evaluation's error per object for the term the views show (RMSE, relative
// RMSE, MAE, max, pixels, training samples and time), sortable by any column; clicking a row selects
// the object, which the views highlight (ViewState::selectedObject, as the Scene panel does).
// The figures are core's ErrorStats from rrf::evaluate (core/eval/error_metrics.h, per channel), the
// same numbers `rrf evaluate` reports; the panel only sorts and shows them.
#include <algorithm>
#include <cstdio>

#include <imgui.h>

#include "panels/panels.h"

namespace rrf::panels {

namespace {
const char* const kColumnNames[] = {"object", "RMSE", "rel. RMSE", "MAE", "max", "pixels", "samples", "train s"};

double key(const ObjectErrorRow& r, ObjectColumn c) {
    switch (c) {
        case ObjectColumn::Rmse: return r.stats.rmse;
        case ObjectColumn::RelativeRmse: return r.stats.relativeRmse;
        case ObjectColumn::Mae: return r.stats.mae;
        case ObjectColumn::Max: return r.stats.maxError;
        case ObjectColumn::Pixels: return double(r.stats.pixels);
        case ObjectColumn::Samples: return double(r.samples);
        case ObjectColumn::TrainSeconds: return r.trainSeconds;
        default: return double(r.objectId);
    }
}

std::string csvQuote(const std::string& s) {
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

void drawHeader(WorkbenchState& state) {
    const EvaluationInfo& e = state.evaluation;
    ImGui::BeginDisabled(e.running || state.training.modelsDir.empty());
    if (ImGui::Button("Evaluate")) state.request(Command::Evaluate);
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
        ImGui::SetTooltip("compares the prediction of the trained models with the ground truth (CPU predictor)");
    ImGui::SameLine();
    ImGui::BeginDisabled(!e.valid);
    if (ImGui::Button("Export CSV...")) state.request(Command::ExportObjectsCsv);
    ImGui::EndDisabled();
    ImGui::SameLine();
    if (e.running) ImGui::TextUnformatted("evaluating...");
    else if (e.valid)
        ImGui::Text("%s term, light (%.3g, %.3g, %.3g), ground truth %d spp", termName(state.view.term), e.lightPosition.x,
                    e.lightPosition.y, e.lightPosition.z, e.referenceSpp);
    else ImGui::TextDisabled("No evaluation yet: train, then Evaluate.");
}
}  // namespace

std::vector<ObjectErrorRow> sortedObjectRows(const std::vector<ObjectErrorRow>& rows, ObjectColumn column, bool ascending) {
    std::vector<ObjectErrorRow> out = rows;
    std::stable_sort(out.begin(), out.end(), [&](const ObjectErrorRow& a, const ObjectErrorRow& b) {
        if (column == ObjectColumn::Object) return ascending ? a.name < b.name : b.name < a.name;
        return ascending ? key(a, column) < key(b, column) : key(b, column) < key(a, column);
    });
    return out;
}

std::string objectRowsCsv(const std::vector<ObjectErrorRow>& rows, const char* term) {
    std::string csv = "term,object_id,object,rmse,relative_rmse,mae,max,pixels,samples,train_seconds\n";
    char buf[256];
    for (const ObjectErrorRow& r : rows) {
        std::snprintf(buf, sizeof buf, ",%.9g,%.9g,%.9g,%.9g,%llu,%llu,%.6g\n", r.stats.rmse, r.stats.relativeRmse,
                      r.stats.mae, r.stats.maxError, (unsigned long long)r.stats.pixels, (unsigned long long)r.samples,
                      r.trainSeconds);
        csv += std::string(term) + "," + std::to_string(r.objectId) + "," + csvQuote(r.name) + buf;
    }
    return csv;
}

void drawObjectsPanel(WorkbenchState& state) {
    drawHeader(state);
    const EvaluationInfo& e = state.evaluation;
    const int t = int(state.view.term);
    if (!e.valid) return;
    if (!e.available[t]) {
        ImGui::TextDisabled("The networks do not predict the %s term (see the Network panel's targets).",
                           termName(state.view.term));
        return;
    }
    const ImGuiTableFlags flags = ImGuiTableFlags_Sortable | ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg |
                                  ImGuiTableFlags_ScrollY | ImGuiTableFlags_Resizable | ImGuiTableFlags_SizingStretchProp;
    if (!ImGui::BeginTable("##objects", int(ObjectColumn::Count), flags)) return;
    ImGui::TableSetupScrollFreeze(0, 1);
    for (int c = 0; c < int(ObjectColumn::Count); ++c)
        ImGui::TableSetupColumn(kColumnNames[c], c == 0 ? ImGuiTableColumnFlags_DefaultSort : 0, 0.f, ImGuiID(c));
    ImGui::TableHeadersRow();
    ObjectsView& v = state.objectsView;
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
        const bool selected = state.view.selectedObject == r.objectId;
        char label[96];
        std::snprintf(label, sizeof label, "#%d %s", r.objectId, r.name.c_str());
        if (ImGui::Selectable(label, selected, ImGuiSelectableFlags_SpanAllColumns))
            state.view.selectedObject = selected ? -1 : r.objectId;  // click again to clear the highlight
        ImGui::PopID();
        for (double value : {r.stats.rmse, r.stats.relativeRmse, r.stats.mae, r.stats.maxError}) {
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
    for (double value : {o.rmse, o.relativeRmse, o.mae, o.maxError}) {
        ImGui::TableNextColumn();
        ImGui::TextDisabled("%.4g", value);
    }
    ImGui::TableNextColumn();
    ImGui::TextDisabled("%llu", (unsigned long long)o.pixels);
    ImGui::EndTable();
}

}  // namespace rrf::panels
