// Scene panel: objects by name with their materials (select to highlight; OBJ groups with vertex
// normals marked "smooth"), materials (editable, kd + ks ≤ 1 enforced), lights (rect, triangle, point),
// the movable light's position bounded by the light region, and the effects derived from the scene.
#include <cstdio>
#include <string>

#include <imgui.h>

#include "core/scene/effects.h"
#include "core/scene/scene_summary.h"
#include "panels/figure_text.h"
#include "panels/panels.h"
#include "core/project/scene_edits.h"

namespace rrf::panels {

namespace scene_panel_detail {
namespace {
void drawObjects(const ScenePanelView& panel) {
    const Scene& scene = panel.project.scene;
    const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit;
    if (!ImGui::BeginTable("##objects", 5, flags)) return;
    // Columns fitted to their content: wrapping their text at the column's edge would keep them narrow.
    ImGui::PushTextWrapPos(-1.f);
    ImGui::TableSetupColumn("id");
    ImGui::TableSetupColumn("name", ImGuiTableColumnFlags_WidthStretch);
    ImGui::TableSetupColumn("kind");
    ImGui::TableSetupColumn("prims");
    ImGui::TableSetupColumn("material");
    ImGui::TableHeadersRow();
    for (const Object& o : scene.objects) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        char id[16];
        std::snprintf(id, sizeof id, "%d", o.id);
        const bool selected = panel.selectedObject == o.id;
        if (ImGui::Selectable(id, selected, ImGuiSelectableFlags_SpanAllColumns))
            panel.selectedObject = selected ? -1 : o.id;  // click again to clear the highlight
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(o.name.c_str());
        ImGui::TableNextColumn();
        figureText("%s%s", objectKindName(o.kind), o.normals.empty() ? "" : ", smooth");
        ImGui::TableNextColumn();
        figureText("%zu", o.primitiveCount());
        ImGui::TableNextColumn();
        const bool validMaterial = o.material >= 0 && o.material < int(scene.materials.size());
        ImGui::TextUnformatted(validMaterial ? scene.materials[size_t(o.material)].name.c_str() : "?");
    }
    ImGui::PopTextWrapPos();
    ImGui::EndTable();
}

void drawMaterials(const ScenePanelView& panel) {
    const Scene& scene = panel.project.scene;
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        Material m = scene.materials[i];  // edited as a copy: editMaterial applies and records it
        ImGui::PushID(int(i));
        if (ImGui::TreeNode("##mat", "%s (%s)", m.name.c_str(), m.type == Material::Type::Phong ? "Phong" : "Lambert")) {
            const bool kd = ImGui::ColorEdit3("kd (diffuse)", &m.kd.x, ImGuiColorEditFlags_Float);
            const bool ks = ImGui::ColorEdit3("ks (specular)", &m.ks.x, ImGuiColorEditFlags_Float);
            bool ex = false;
            if (m.type == Material::Type::Phong || ks)
                ex = ImGui::DragFloat("exponent", &m.exponent, 1.f, 0.f, 1e6f, "%.1f", ImGuiSliderFlags_Logarithmic);
            if (kd || ks || ex) {
                if (editMaterial(panel.project, int(i), m, kd)) ImGui::SetTooltip("kd + ks limited to 1 per channel");
                panel.actions.markDirty();
                panel.actions.request(Command::SceneChanged);
            }
            ImGui::TreePop();
        }
        ImGui::PopID();
    }
}

void drawLights(const ScenePanelView& panel) {
    const Scene& scene = panel.project.scene;
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        const Vec3 c = l.center();
        const bool movable = int(i) == scene.movableLight;
        // Bullet + Text rather than BulletText, which does not wrap at the pane's edge.
        ImGui::Bullet();
        if (l.isArea())
            figureText("%s: %s, area %.4g, radiance (%.3g, %.3g, %.3g)%s", l.name.c_str(), lightTypeName(l.type),
                        l.area(), l.radiance.x, l.radiance.y, l.radiance.z, movable ? ", movable" : "");
        else
            figureText("%s: point at (%.3g, %.3g, %.3g)%s", l.name.c_str(), c.x, c.y, c.z, movable ? ", movable" : "");
    }
    if (scene.lights.empty()) {
        ImGui::TextDisabled("The scene has no light.");
        return;
    }
    const Bounds3& region = scene.lightRegion;
    Vec3 p = scene.lightPosition();
    if (region.empty()) {
        ImGui::TextDisabled("No light region: the light does not move (set \"light_region\" in the scene).");
        return;
    }
    ImGui::TextUnformatted("Light position (within the light region)");
    bool moved = false;
    const char* axes[3] = {"x", "y", "z"};
    float* comp[3] = {&p.x, &p.y, &p.z};
    const float lo[3] = {region.lo.x, region.lo.y, region.lo.z};
    const float hi[3] = {region.hi.x, region.hi.y, region.hi.z};
    for (int a = 0; a < 3; ++a) {
        if (lo[a] == hi[a]) {
            figureText("%s = %.3f (fixed by the region)", axes[a], lo[a]);
            continue;
        }
        moved |= ImGui::SliderFloat(axes[a], comp[a], lo[a], hi[a], "%.3f", ImGuiSliderFlags_AlwaysClamp);
    }
    if (ImGui::Button("Centre of region")) {
        p = region.center();
        moved = true;
    }
    if (moved) {
        moveLight(panel.project, p);
        panel.actions.markDirty();
        panel.actions.request(Command::SceneChanged);
    }
}
}  // namespace
}  // namespace scene_panel_detail

void drawScenePanel(const ScenePanelView& panel) {
    if (!panel.hasProject) {
        ImGui::TextDisabled("No project is open.");
        return;
    }
    const Scene& scene = panel.project.scene;
    figureTextDisabled("%s", scene.sourcePath.empty() ? "(embedded scene)" : scene.sourcePath.c_str());
    figureText("%zu objects, %zu materials, %zu lights, camera %dx%d", scene.objects.size(), scene.materials.size(),
                scene.lights.size(), scene.camera.width, scene.camera.height);
    if (ImGui::CollapsingHeader("Objects", ImGuiTreeNodeFlags_DefaultOpen)) scene_panel_detail::drawObjects(panel);
    if (ImGui::CollapsingHeader("Materials", ImGuiTreeNodeFlags_DefaultOpen)) scene_panel_detail::drawMaterials(panel);
    if (ImGui::CollapsingHeader("Lights", ImGuiTreeNodeFlags_DefaultOpen)) scene_panel_detail::drawLights(panel);
    if (ImGui::CollapsingHeader("Effects", ImGuiTreeNodeFlags_DefaultOpen)) {
        for (const std::string& line : Effects::derive(scene).describe()) {
            ImGui::Bullet();
            ImGui::TextUnformatted(line.c_str());
        }
    }
    if (!scene.warnings.empty() && ImGui::CollapsingHeader("Loader warnings")) {
        for (const std::string& w : scene.warnings) {
            ImGui::Bullet();
            ImGui::TextUnformatted(w.c_str());
        }
    }
}

}  // namespace rrf::panels
