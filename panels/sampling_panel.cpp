// Sampling panel: the data generator's settings (Project::sampling), what a run will
// cost before it starts, and how many records each object got after it ran.
#include <algorithm>
#include <cstdio>

#include <imgui.h>

#include "core/data/record_layout.h"
#include "core/data/sampling_settings.h"
#include "panels/figure_text.h"
#include "panels/panels.h"
#include "panels/pipeline_controls.h"
#include "panels/status_text.h"

namespace rrf::panels {

namespace sampling_panel_detail {
namespace {
void drawEstimate(const Scene& scene, const SamplingSettings& s) {
    // Upper bounds: cells inside closed objects are dropped and escaping rays store nothing.
    const double records = double(s.cellCount()) * double(s.directions);
    const int floats = RecordLayout::forScene(scene).floatsPerRecord();
    const double bytes = records * floats * 4.0;
    figureText("at most %.3g records, %.3g MB (%d floats per record)", records, bytes / 1e6, floats);
}

void drawCoverage(const DatasetInfo& d) {
    if (d.path.empty()) {
        ImGui::TextDisabled("No dataset generated in this session.");
        return;
    }
    const GeneratorStats& g = d.generator;
    figureText("%s (%.1f s)", d.path.c_str(), d.seconds);
    figureText("%llu records from %llu of %llu viewpoints (%llu inside objects, %llu outside the scene, %llu behind a "
                "surface)",
                (unsigned long long)g.records, (unsigned long long)g.keptCells(), (unsigned long long)g.cells(),
                (unsigned long long)g.cellsDroppedInsideObject, (unsigned long long)g.cellsDroppedOutsideScene,
                (unsigned long long)g.cellsDroppedBehindSurface);
    figureText("rays without a record: %llu escaped, %llu hit a light, %llu without a finite sample",
                (unsigned long long)g.raysEscaped, (unsigned long long)g.raysHitEmitter,
                (unsigned long long)g.recordsWithoutFiniteSample);
    figureText("paths: %llu (%.1f per record); records at the path cap with noise above the target: %llu",
                (unsigned long long)g.paths, g.records ? double(g.paths) / double(g.records) : 0.0,
                (unsigned long long)g.recordsAtSppCap);
    // Columns share the width in proportion to their content (headers included), so none is cut.
    if (!ImGui::BeginTable("##coverage", 4, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp))
        return;
    ImGui::TableSetupColumn("object");
    ImGui::TableSetupColumn("records");
    // Relative standard error of the targets (core/data/record_noise.h): what the trainers' goal
    // competes with.
    ImGui::TableSetupColumn("noise median");
    ImGui::TableSetupColumn("noise p90");
    ImGui::TableHeadersRow();
    for (size_t i = 0; i < g.recordsPerObject.size(); ++i) {
        const uint64_t count = g.recordsPerObject[i];
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(i < d.objectNames.size() ? d.objectNames[i].c_str() : "?");
        ImGui::TableNextColumn();
        figureText("%llu%s", (unsigned long long)count, count == 0 ? "  (no data: cannot train)" : "");
        const NoiseSummary* n = i < g.noisePerObject.size() ? &g.noisePerObject[i] : nullptr;
        ImGui::TableNextColumn();
        if (n && n->known > 0) figureText("%.2f %%", 100.0 * n->median);
        else ImGui::TextDisabled("unknown");
        ImGui::TableNextColumn();
        if (n && n->known > 0) figureText("%.2f %%", 100.0 * n->p90);
        else ImGui::TextDisabled("unknown");
    }
    ImGui::EndTable();
}
}  // namespace
}  // namespace sampling_panel_detail

void drawSamplingPanel(const SamplingPanelView& panel) {
    if (!panel.hasProject) {
        ImGui::TextDisabled("No project is open.");
        return;
    }
    drawSamplingPresets(panel);
    // Edits a copy: a project without a sampling section keeps none until the user changes something.
    SamplingSettings s = panel.project.samplingOrDefault();
    bool changed = false;
    const float w = fieldWidth(ImGui::GetFontSize() * 10, "paths per record (first round)");  // the longest label
    int grid[3] = {s.nx, s.ny, s.nz};
    ImGui::SetNextItemWidth(w);
    if (ImGui::DragInt3("jitter grid", grid, 0.2f, 1, kMaxGridCells)) {
        s.nx = grid[0];
        s.ny = grid[1];
        s.nz = grid[2];
        changed = true;
    }
    ImGui::SetNextItemWidth(w);
    changed |= ImGui::DragInt("directions (N_dir)", &s.directions, 10.f, 1, kMaxDirections);
    ImGui::SetNextItemWidth(w);
    changed |= ImGui::DragInt("paths per record (first round)", &s.spp, 1.f, 1, kMaxSamplesPerRecord);
    ImGui::SetNextItemWidth(w);
    changed |= ImGui::DragInt("max paths per record", &s.maxSpp, 4.f, 1, kMaxSamplesPerRecord);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("adaptive sampling: a record doubles its paths until its relative noise is at most the\n"
                          "noise target or it has this many paths; at most the first round = fixed paths per record");
    ImGui::SetNextItemWidth(w);
    float target = float(s.noiseTarget * 100.0);
    if (ImGui::DragFloat("noise target (%)", &target, 0.05f, 0.1f, 100.f, "%.2f")) {
        s.noiseTarget = double(std::max(target, 0.1f)) / 100.0;
        changed = true;
    }
    int seed = int(s.seed & 0x7fffffff);
    ImGui::SetNextItemWidth(w);
    if (ImGui::InputInt("seed##sampling", &seed)) {
        s.seed = uint64_t(seed < 0 ? 0 : seed);
        changed = true;
    }
    changed |= ImGui::Checkbox("fixed light (ignore the light region)", &s.fixedLight);
    if (changed) {
        // A typed value outside a field's range is kept at the bound, and the Sampling panel says so.
        const char* tab = "Sampling";
        s.nx = clampWithNotice(panel.actions, tab, "the grid's cells per axis", s.nx, 1, kMaxGridCells);
        s.ny = clampWithNotice(panel.actions, tab, "the grid's cells per axis", s.ny, 1, kMaxGridCells);
        s.nz = clampWithNotice(panel.actions, tab, "the grid's cells per axis", s.nz, 1, kMaxGridCells);
        s.directions = clampWithNotice(panel.actions, tab, "directions", s.directions, 1, kMaxDirections);
        s.spp = clampWithNotice(panel.actions, tab, "paths per record (first round)", s.spp, 1, kMaxSamplesPerRecord);
        s.maxSpp = clampWithNotice(panel.actions, tab, "max paths per record", s.maxSpp, 1, kMaxSamplesPerRecord);
        panel.project.sampling = s;
        panel.actions.markDirty();
    }
    const Bounds3& r = panel.project.scene.lightRegion;
    if (!r.empty())
        figureTextDisabled("light region (%.2f, %.2f, %.2f) .. (%.2f, %.2f, %.2f)", r.lo.x, r.lo.y, r.lo.z, r.hi.x, r.hi.y,
                            r.hi.z);
    sampling_panel_detail::drawEstimate(panel.project.scene, s);

    if (!panel.dataset.running) {
        // Refused at the button, before any work: the reason stays in sight while the settings change.
        const std::string refusal = generateRefusal(panel.estimates, s);
        ImGui::BeginDisabled(!refusal.empty());
        if (ImGui::Button("Generate dataset")) panel.actions.request(Command::Generate);
        ImGui::EndDisabled();
        if (!refusal.empty()) {
            ImGui::PushTextWrapPos(0.f);
            figureTextColored(ImVec4(1.f, 0.45f, 0.4f, 1.f), "Cannot generate: %s", refusal.c_str());
            ImGui::PopTextWrapPos();
        }
    } else {
        if (ImGui::Button("Stop generating")) panel.actions.request(Command::CancelGenerate);
        ImGui::SameLine();
        ImGui::ProgressBar(float(panel.dataset.progress), ImVec2(ImGui::GetFontSize() * 10, 0));
    }
    if (panel.actions.notice && panel.actions.notice->panel == "Sampling") drawNotice(panel.actions.notice);
    if (ImGui::CollapsingHeader("Coverage per object", ImGuiTreeNodeFlags_DefaultOpen)) {
        const std::string stale = datasetStaleReason(panel.dataset, panel.project);
        if (!stale.empty()) figureTextColored(ImVec4(1.f, 0.8f, 0.3f, 1.f), "%s", stale.c_str());
        sampling_panel_detail::drawCoverage(panel.dataset);
    }
}

}  // namespace rrf::panels
