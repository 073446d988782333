// Leaves panel: the kd-trees of the loaded models (core/nn/partition_tree.h, Ren et al. 2013): per
// object and target the number of leaves, and per leaf its depth, training records and the
// validation relative RMSE of its network against the project's error goal. Clicking a row selects
// the object (the views highlight it); the Views "leaves" checkbox tints the prediction by leaf.
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "panels/figure_text.h"
#include "panels/panels.h"

namespace rrf::panels {

LeavesInfo leavesOf(const ModelSet& models) {
    LeavesInfo info;
    for (const ObjectNetworks& o : models.objects)
        for (const auto& [target, m] : o.byTarget) {
            const std::vector<int> nodes = m.tree.leafNodes();
            // Depth of every node: children follow their parent, so one forward pass suffices.
            std::vector<int> depth(m.tree.nodes.size(), 0);
            for (size_t i = 0; i < m.tree.nodes.size(); ++i) {
                const PartitionNode& n = m.tree.nodes[i];
                if (!n.isLeaf()) depth[size_t(n.left)] = depth[size_t(n.right)] = depth[i] + 1;
            }
            for (int l = 0; l < m.leafCount(); ++l) {
                const PartitionNode& n = m.tree.nodes[size_t(nodes[size_t(l)])];
                info.rows.push_back({o.objectId, o.name, target, l, m.leafCount(), depth[size_t(nodes[size_t(l)])],
                                     n.records, n.error});
            }
        }
    return info;
}

void drawLeavesPanel(const LeavesPanelView& panel) {
    const LeavesInfo& info = panel.leaves;
    if (info.rows.empty()) {
        ImGui::TextDisabled("No models loaded: train, or open a project with a training run.");
        return;
    }
    const double goal = panel.project.networkOrDefault().options.partition.goal;
    int models = 0, above = 0;
    for (const LeafRow& r : info.rows) {
        models += r.leaf == 0;
        above += r.error > goal;
    }
    figureText("%zu leaves in %d models; %d above the goal %.3g (validation relative RMSE)", info.rows.size(), models,
                above, goal);
    ImGui::SameLine();
    ImGui::Checkbox("tint view by leaf", &panel.view.leafOverlay);
    const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_Borders | ImGuiTableFlags_ScrollY |
                                  ImGuiTableFlags_SizingFixedFit;
    if (!ImGui::BeginTable("##leaves", 6, flags)) return;
    ImGui::TableSetupScrollFreeze(0, 1);
    for (const char* h : {"object", "target", "leaf", "depth", "records", "rel. error"}) ImGui::TableSetupColumn(h);
    ImGui::TableHeadersRow();
    for (size_t i = 0; i < info.rows.size(); ++i) {
        const LeafRow& r = info.rows[i];
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        char label[160];
        std::snprintf(label, sizeof label, "%d %s##leaf%zu", r.objectId, r.object.c_str(), i);
        if (ImGui::Selectable(label, panel.view.selectedObject == r.objectId, ImGuiSelectableFlags_SpanAllColumns))
            panel.view.selectedObject = r.objectId;
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(r.target.c_str());
        ImGui::TableNextColumn();
        figureText("%d/%d", r.leaf + 1, r.leafCount);
        ImGui::TableNextColumn();
        figureText("%d", r.depth);
        ImGui::TableNextColumn();
        figureText("%lld", (long long)r.records);
        ImGui::TableNextColumn();
        if (std::isnan(r.error)) ImGui::TextDisabled("n/a");
        else if (r.error > goal) figureTextColored(ImVec4(1.f, 0.45f, 0.35f, 1.f), "%.4f", r.error);
        else figureText("%.4f", r.error);
    }
    ImGui::EndTable();
}

}  // namespace rrf::panels
