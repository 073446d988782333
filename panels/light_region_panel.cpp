// Light region panel: where in the light region the loaded models fail. The models are judged at a
// grid of light positions spanning the region, edges included (core/eval/light_grid.h, the job in
// app/gui/evaluation_light_grid.cpp); the panel shows one map per height (y) of the grid, x across and
// z down, all on one colour scale, with the training records' light positions of that height band as
// dots. Hovering a cell gives its figures; clicking it moves the light there, so the views show that
// light's ground truth and prediction.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "core/project/scene_edits.h"
#include "panels/figure_text.h"
#include "panels/layout.h"
#include "panels/panels.h"

namespace rrf::panels {

namespace light_region_panel_detail {
namespace {

ImU32 viridisColour(double v, double scale) {
    if (!std::isfinite(v)) return IM_COL32(255, 0, 255, 255);  // no figure: magenta, as in the error maps
    const Vec3 c = viridis(float(scale > 0 ? v / scale : 0.0));
    return ImGui::ColorConvertFloat4ToU32(ImVec4(linearToSrgb(c.x), linearToSrgb(c.y), linearToSrgb(c.z), 1.f));
}

std::string figure(double v) {
    if (!std::isfinite(v)) return "unknown";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4f", v);
    return buf;
}

/// The controls: grid counts, the Evaluate / Stop button, progress.
void drawControls(const LightRegionPanelView& panel, bool modelsLoaded) {
    LightRegionInfo& lr = panel.lightRegion;
    ImGui::SetNextItemWidth(fieldWidth(ImGui::GetFontSize() * 9, "grid x, y, z"));
    if (ImGui::InputInt3("grid x, y, z", lr.counts))
        for (int& c : lr.counts) c = std::clamp(c, 1, LightRegionInfo::kMaxCount);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("light positions along each axis of the light region, edges included (1 to %d each)",
                          LightRegionInfo::kMaxCount);
    const int points = lr.counts[0] * lr.counts[1] * lr.counts[2];
    sameLineIfFits(ImGui::GetFontSize() * 10);
    figureTextDisabled("%d references", points);
    if (lr.running) {
        if (ImGui::Button("Stop")) panel.actions.request(Command::CancelLightRegion);
        ImGui::SameLine();
        ImGui::ProgressBar(float(lr.progress), ImVec2(-1, 0));
        return;
    }
    const char* why = !panel.hasProject                    ? "no project is open"
                      : !modelsLoaded                      ? "no models are loaded: train first"
                      : panel.project.scene.lightRegion.empty() ? "the scene's light does not move (no light region)"
                                                                : nullptr;
    ImGui::BeginDisabled(why != nullptr);
    if (ImGui::Button("Evaluate over the light region")) panel.actions.request(Command::EvaluateLightRegion);
    ImGui::EndDisabled();
    if (why) {
        ImGui::SameLine();
        figureTextDisabled("(%s)", why);
    } else if (ImGui::IsItemHovered()) {
        ImGui::SetTooltip("judges the loaded models at every grid position against references of the project's "
                          "store at 64x64 (converged to its noise target, reused once rendered)");
    }
}

/// One slice: cells coloured by figure, marks as dots; hover read-out, click moves the light.
void drawSlice(const LightRegionPanelView& panel, const LightGridMap& m, const std::vector<double>& values, int j, double scale,
               float side) {
    const int nx = m.grid.counts[0], nz = m.grid.counts[2];
    const float cell = side / float(std::max(nx, nz));
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    ImGui::InvisibleButton(("##slice" + std::to_string(j)).c_str(), ImVec2(cell * float(nx), cell * float(nz)));
    const bool hovered = ImGui::IsItemHovered(), clicked = ImGui::IsItemClicked(ImGuiMouseButton_Left);
    for (int k = 0; k < nz; ++k)
        for (int i = 0; i < nx; ++i) {
            const ImVec2 a(origin.x + cell * float(i), origin.y + cell * float(k));
            dl->AddRectFilled(a, ImVec2(a.x + cell, a.y + cell), viridisColour(values[m.grid.index(i, j, k)], scale));
        }
    // Marks of this slice's height band, placed as in the slice images.
    for (const Vec3& p : m.marks)
        if (m.inSlice(p, j))
            dl->AddCircleFilled(ImVec2(origin.x + m.cellCoordinate(p, 0) * cell, origin.y + m.cellCoordinate(p, 2) * cell),
                                std::max(1.5f, cell * 0.025f), IM_COL32(255, 255, 255, 150));
    if (!hovered) return;
    const ImVec2 mouse = ImGui::GetIO().MousePos;
    const int i = std::clamp(int((mouse.x - origin.x) / cell), 0, nx - 1);
    const int k = std::clamp(int((mouse.y - origin.y) / cell), 0, nz - 1);
    const size_t n = m.grid.index(i, j, k);
    const Vec3& l = m.lights[n];
    ImGui::BeginTooltip();
    figureText("light (%.3f, %.3f, %.3f)", l.x, l.y, l.z);
    figureText("relative RMSE %s", figure(values[n]).c_str());
    if (panel.lightRegion.object < 0)
        figureText("raw %s, reference noise floor %s", figure(m.globalRaw[n]).c_str(), figure(m.globalNoiseFloor[n]).c_str());
    ImGui::TextDisabled("click: move the light here");
    ImGui::EndTooltip();
    if (clicked) {
        moveLight(panel.project, l);
        panel.actions.markDirty();
        panel.actions.request(Command::SceneChanged);
    }
}

}  // namespace
}  // namespace light_region_panel_detail

void drawLightRegionPanel(const LightRegionPanelView& panel) {
    LightRegionInfo& lr = panel.lightRegion;
    light_region_panel_detail::drawControls(panel, !panel.modelsDir.empty());
    if (!lr.map) {
        ImGui::TextDisabled("No evaluation over the light region yet.");
        return;
    }
    const LightGridMap& m = *lr.map;
    // What is shown: the global figure or one object's.
    const auto& objects = panel.project.scene.objects;
    if (lr.object >= int(std::min(m.objects.size(), objects.size()))) lr.object = -1;
    const std::string shown = lr.object < 0 ? "all objects" : objects[size_t(lr.object)].name;
    ImGui::SetNextItemWidth(fieldWidth(ImGui::GetFontSize() * 10, "show"));
    if (ImGui::BeginCombo("show", shown.c_str())) {
        if (ImGui::Selectable("all objects", lr.object < 0)) lr.object = -1;
        for (size_t id = 0; id < m.objects.size() && id < objects.size(); ++id)
            if (ImGui::Selectable(objects[id].name.c_str(), lr.object == int(id))) lr.object = int(id);
        ImGui::EndCombo();
    }
    const std::vector<double>& values = lr.object < 0 ? m.global : m.objects[size_t(lr.object)];
    const double scale = LightGridMap::scaleOf(values);
    figureText(
        "Relative RMSE of the global term (noise-corrected where the reference's noise is known), %dx%d "
        "references; colour 0 (dark) to %s (yellow), magenta: not visible. Dots: training records' lights%s.",
        lr.width, lr.height, light_region_panel_detail::figure(scale).c_str(),
        m.marks.empty() ? (" (none: " + m.marksWhy + ")").c_str() : "");
    // The slices side by side where they fit, each labelled with its height.
    const int ny = m.grid.counts[1];
    // Square slices as large as the pane allows beside each other (up to three in a row) and below the
    // text, never smaller than six lines of text.
    const ImVec2 room = ImGui::GetContentRegionAvail();
    const float line = ImGui::GetTextLineHeightWithSpacing();
    const float side = std::clamp(std::min(room.x / float(std::min(ny, 3)) - ImGui::GetStyle().ItemSpacing.x, room.y - 2.5f * line),
                                  ImGui::GetFontSize() * 6, ImGui::GetFontSize() * 16);
    for (int j = 0; j < ny; ++j) {
        if (j > 0) sameLineIfFits(side);
        ImGui::BeginGroup();
        figureText("y = %.3f", m.lights[m.grid.index(0, j, 0)].y);
        light_region_panel_detail::drawSlice(panel, m, values, j, scale, side);
        ImGui::EndGroup();
    }
    figureTextDisabled("x to the right, z downwards; models %s; files in %s", lr.modelsDir.c_str(), lr.outDir.c_str());
}

}  // namespace rrf::panels
