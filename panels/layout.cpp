#include "panels/layout.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include <imgui.h>
#include <imgui_internal.h>

#include "panels/panels.h"

namespace rrf::panels {

namespace layout_detail {
namespace {

/// A change the user asked for while the tree was drawn; applied after the walk.
struct PendingMove {
    std::string tab, target;
    DropSide side = DropSide::Centre;
};

struct WorkspaceDraw {
    PaneLayout& layout;
    const std::function<void(const std::string&)>& drawPanel;
    std::string& focusTab;
    float thickness = 10.f;  ///< the gap between panes: splitterWidth()
    std::optional<PendingMove> move;
    std::vector<std::string> reorder;  ///< a pane's tabs in the order its bar now shows them
    std::string undock, dock;          ///< a tab to float in a window of its own / to dock back
    bool floatingMoved = false;        ///< a floating window was moved or resized
};

/// One splitter between two panes along `axis`; `first` is the size of the pane before it. The whole
/// gap between the panes (`thickness`, at least 10 px) takes the mouse, while only a thin line is
/// drawn in its middle, wider and brighter under the mouse or while dragged. The hit zone does not
/// reach into the panes: the workspace is a child window, so ImGui would not let a splitter take the
/// mouse over the panes' own child windows anyway, and their scrollbars lie right at its edges.
void splitter(ImGuiID id, ImGuiAxis axis, const ImVec2& origin, float total, float cross, float thickness, float& first) {
    float second = total - first - thickness;
    const float minSize = total * PaneLayout::kMinFraction;
    ImRect bb;
    if (axis == ImGuiAxis_X)
        bb = ImRect(ImVec2(origin.x + first, origin.y), ImVec2(origin.x + first + thickness, origin.y + cross));
    else
        bb = ImRect(ImVec2(origin.x, origin.y + first), ImVec2(origin.x + cross, origin.y + first + thickness));
    // ImGui fills the whole zone in the separator colours: make that fill invisible and draw the line.
    ImGui::PushStyleColor(ImGuiCol_Separator, 0u);
    ImGui::PushStyleColor(ImGuiCol_SeparatorHovered, 0u);
    ImGui::PushStyleColor(ImGuiCol_SeparatorActive, 0u);
    ImGui::SplitterBehavior(bb, id, axis, &first, &second, minSize, minSize, 0.f, 0.f);
    ImGui::PopStyleColor(3);
    const bool active = ImGui::IsItemActive(), hovered = ImGui::IsItemHovered();
    if (hovered || active) ImGui::SetMouseCursor(axis == ImGuiAxis_X ? ImGuiMouseCursor_ResizeEW : ImGuiMouseCursor_ResizeNS);
    // The line follows a drag in this frame: drawn where the splitter now is.
    const float line = (hovered || active) ? 4.f : 2.f;
    const float mid = first + 0.5f * thickness;
    const ImRect l = axis == ImGuiAxis_X ? ImRect(ImVec2(origin.x + mid - 0.5f * line, origin.y),
                                                  ImVec2(origin.x + mid + 0.5f * line, origin.y + cross))
                                         : ImRect(ImVec2(origin.x, origin.y + mid - 0.5f * line),
                                                  ImVec2(origin.x + cross, origin.y + mid + 0.5f * line));
    ImGui::GetWindowDrawList()->AddRectFilled(
        l.Min, l.Max, ImGui::GetColorU32(active ? ImGuiCol_SeparatorActive : hovered ? ImGuiCol_SeparatorHovered : ImGuiCol_Separator));
}

std::string joined(const std::vector<std::string>& tabs) {
    std::string s;
    for (const std::string& t : tabs) s += (s.empty() ? "" : ", ") + t;
    return s;
}

/// The part of `r` a drop on `side` would give the dropped tab (the whole pane for Centre).
ImRect zoneRect(const ImRect& r, DropSide side) {
    const ImVec2 c = r.GetCenter();
    switch (side) {
        case DropSide::Left: return ImRect(r.Min, ImVec2(c.x, r.Max.y));
        case DropSide::Right: return ImRect(ImVec2(c.x, r.Min.y), r.Max);
        case DropSide::Top: return ImRect(r.Min, ImVec2(r.Max.x, c.y));
        case DropSide::Bottom: return ImRect(ImVec2(r.Min.x, c.y), r.Max);
        case DropSide::Centre: break;
    }
    return r;
}

/// Right-click menu of a tab: split its pane, or move the tab to another pane.
void tabMenu(WorkspaceDraw& w, const PaneNode& pane, const std::string& tab) {
    if (!ImGui::BeginPopupContextItem()) return;
    const bool alone = pane.tabs.size() == 1;
    if (ImGui::MenuItem("Split right", nullptr, false, !alone)) w.move = PendingMove{tab, tab, DropSide::Right};
    if (ImGui::MenuItem("Split below", nullptr, false, !alone)) w.move = PendingMove{tab, tab, DropSide::Bottom};
    if (ImGui::MenuItem("Float in a window", nullptr, false, w.layout.panes().size() > 1 || !alone)) w.undock = tab;
    if (ImGui::BeginMenu("Move to pane", w.layout.panes().size() > 1)) {
        for (const PaneNode* other : w.layout.panes())
            if (other != &pane && ImGui::MenuItem(joined(other->tabs).c_str()))
                w.move = PendingMove{tab, other->tabs.front(), DropSide::Centre};
        ImGui::EndMenu();
    }
    ImGui::EndPopup();
}

/// The tab bar of one pane and its shown panel; returns the bar's rectangle (empty when not drawn).
ImRect drawPaneTabs(WorkspaceDraw& w, PaneNode& pane) {
    ImRect barRect;
    // The bar's ID follows the pane's tabs in model order: when the model changes them (a move, a
    // reorder, a reset, a loaded project) ImGui sees a bar it has not shown in the last frame.
    ImGui::PushID(joined(pane.tabs).c_str());
    if (ImGui::BeginTabBar("##tabs", ImGuiTabBarFlags_Reorderable | ImGuiTabBarFlags_FittingPolicyScroll)) {
        ImGuiTabBar* bar = GImGui->CurrentTabBar;
        barRect = bar->BarRect;
        const bool fresh = bar->PrevFrameVisible != ImGui::GetFrameCount() - 1;
        // A reorderable bar keeps its own tab order from the last time it was shown; a bar that
        // (re)appears starts from the model's order instead.
        if (fresh) bar->Tabs.clear();
        for (const std::string& tab : pane.tabs) {
            const bool select = w.focusTab == tab || (fresh && tab == pane.active);
            const bool open = ImGui::BeginTabItem(tab.c_str(), nullptr, select ? ImGuiTabItemFlags_SetSelected : 0);
            if (w.focusTab == tab) w.focusTab.clear();
            // Dragging along the bar reorders (ImGui); a drag that leaves the bar carries the tab
            // to another pane. Once it carries the tab, the source must be submitted every frame.
            const ImVec2 m = ImGui::GetIO().MousePos;
            const bool leftBar = m.y < bar->BarRect.Min.y || m.y > bar->BarRect.Max.y;
            const bool carrying = GImGui->DragDropActive && GImGui->DragDropPayload.SourceId == ImGui::GetItemID();
            if ((leftBar || carrying) && ImGui::BeginDragDropSource()) {
                ImGui::SetDragDropPayload(kTabPayload, tab.c_str(), tab.size() + 1);
                ImGui::Text("Move '%s': drop on a pane (its edge splits it)", tab.c_str());
                ImGui::EndDragDropSource();
            }
            tabMenu(w, pane, tab);
            if (open) {
                // On a bar's first frame ImGui shows its first tab before the selection lands.
                if (!fresh) pane.active = tab;
                // Text wraps at the pane's edge instead of running past it (tables that size their
                // columns to their content scroll in their own child window, which does not wrap).
                ImGui::PushTextWrapPos(0.f);
                w.drawPanel(tab);
                ImGui::PopTextWrapPos();
                ImGui::EndTabItem();
            }
        }
        // Tabs reordered by dragging: the bar's order becomes the model's once the mouse is up.
        if (!fresh && !ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
            std::vector<std::string> shown;
            for (const ImGuiTabItem& t : bar->Tabs)
                if (t.LastFrameVisible == ImGui::GetFrameCount() && t.NameOffset >= 0) shown.push_back(bar->GetTabName(&t));
            if (shown.size() == pane.tabs.size() && shown != pane.tabs) w.reorder = shown;
        }
        ImGui::EndTabBar();
    }
    ImGui::PopID();
    return barRect;
}

/// A pane as a drop target: the zone under the pointer is highlighted while a tab is dragged over it.
/// A drop on the pane's tab bar joins the pane, as it does in every docking UI, whatever edge zone
/// the bar lies in.
void paneDropTarget(WorkspaceDraw& w, const PaneNode& pane, const ImRect& r, const ImRect& bar) {
    if (!ImGui::BeginDragDropTargetCustom(r, ImGui::GetID(("##drop" + joined(pane.tabs)).c_str()))) return;
    const ImVec2 m = ImGui::GetIO().MousePos;
    const DropSide side = bar.Contains(m) ? DropSide::Centre
                                          : dropSideAt((m.x - r.Min.x) / std::max(1.f, r.GetWidth()),
                                                       (m.y - r.Min.y) / std::max(1.f, r.GetHeight()));
    if (const ImGuiPayload* p = ImGui::AcceptDragDropPayload(
            kTabPayload, ImGuiDragDropFlags_AcceptBeforeDelivery | ImGuiDragDropFlags_AcceptNoDrawDefaultRect)) {
        const ImRect z = zoneRect(r, side);
        ImGui::GetForegroundDrawList()->AddRectFilled(z.Min, z.Max, ImGui::GetColorU32(ImGuiCol_DragDropTarget, 0.25f));
        ImGui::GetForegroundDrawList()->AddRect(z.Min, z.Max, ImGui::GetColorU32(ImGuiCol_DragDropTarget), 0.f, 0, 2.f);
        if (p->IsDelivery())
            w.move = PendingMove{std::string(static_cast<const char*>(p->Data)), pane.tabs.front(), side};
    }
    ImGui::EndDragDropTarget();
}

/// A panel floating in a window of its own: a Dock button and a handle that carries it onto a pane
/// (as a tab's drag does) above the panel; closing the window docks it too, so no panel is lost.
/// The window's position and size go back into the layout when the user has moved or sized it.
void drawFloating(WorkspaceDraw& w, FloatingPanel& f) {
    ImGui::SetNextWindowPos(ImVec2(f.x, f.y), ImGuiCond_Appearing);
    ImGui::SetNextWindowSize(ImVec2(f.width, f.height), ImGuiCond_Appearing);
    bool open = true;
    const std::string title = f.tab + "###floating " + f.tab;
    if (w.focusTab == f.tab) {
        ImGui::SetNextWindowFocus();
        w.focusTab.clear();
    }
    if (ImGui::Begin(title.c_str(), &open, ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings)) {
        if (ImGui::SmallButton("Dock")) w.dock = f.tab;
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("Back into the pane it came from");
        ImGui::SameLine();
        ImGui::SmallButton("Drag to a pane");
        if (ImGui::BeginDragDropSource()) {
            ImGui::SetDragDropPayload(kTabPayload, f.tab.c_str(), f.tab.size() + 1);
            ImGui::Text("Move '%s': drop on a pane (its edge splits it)", f.tab.c_str());
            ImGui::EndDragDropSource();
        }
        ImGui::Separator();
        ImGui::PushTextWrapPos(0.f);
        w.drawPanel(f.tab);
        ImGui::PopTextWrapPos();
        const ImVec2 p = ImGui::GetWindowPos(), s = ImGui::GetWindowSize();
        if (!ImGui::IsMouseDown(ImGuiMouseButton_Left) && (p.x != f.x || p.y != f.y || s.x != f.width || s.y != f.height)) {
            f.x = p.x, f.y = p.y, f.width = s.x, f.height = s.y;
            w.floatingMoved = true;
        }
    }
    ImGui::End();
    if (!open) w.dock = f.tab;
}

void drawNode(WorkspaceDraw& w, PaneNode& node, const ImVec2& origin, const ImVec2& size, int depth) {
    if (node.isLeaf()) {
        if (node.tabs.empty()) return;  // only an empty tree has an empty pane (PaneLayout collapses them)
        ImGui::SetCursorScreenPos(origin);
        ImRect bar;
        if (ImGui::BeginChild(("##pane" + joined(node.tabs)).c_str(), size, true)) bar = drawPaneTabs(w, node);
        ImGui::EndChild();
        paneDropTarget(w, node, ImRect(origin, ImVec2(origin.x + size.x, origin.y + size.y)), bar);
        return;
    }
    const bool row = node.split == PaneSplit::Row;
    const float total = row ? size.x : size.y;
    const float t = w.thickness;
    node.fraction = PaneLayout::clampFraction(node.fraction, 0.5f);
    float first = std::round(node.fraction * (total - t));
    ImGui::PushID(depth);
    const PaneNode* firstPane = &node;  // names the splitter: stable while panes elsewhere change
    while (!firstPane->isLeaf()) firstPane = &firstPane->children[0];
    ImGui::PushID(joined(firstPane->tabs).c_str());
    const float placed = first;
    splitter(ImGui::GetID("##split"), row ? ImGuiAxis_X : ImGuiAxis_Y, origin, total, row ? size.y : size.x, t, first);
    ImGui::PopID();
    ImGui::PopID();
    // Only a drag changes the fraction: storing the rounded pixel position back every frame would
    // let the fraction creep.
    if (first != placed) {
        node.fraction = PaneLayout::clampFraction(first / std::max(1.f, total - t), node.fraction);
        first = std::round(node.fraction * (total - t));
    }
    const float second = total - first - t;
    if (row) {
        drawNode(w, node.children[0], origin, ImVec2(first, size.y), depth + 1);
        drawNode(w, node.children[1], ImVec2(origin.x + first + t, origin.y), ImVec2(second, size.y), depth + 1);
    } else {
        drawNode(w, node.children[0], origin, ImVec2(size.x, first), depth + 1);
        drawNode(w, node.children[1], ImVec2(origin.x, origin.y + first + t), ImVec2(size.x, second), depth + 1);
    }
}

}  // namespace
}  // namespace layout_detail

float splitterWidth() { return std::max(10.f, std::round(ImGui::GetFontSize() * 0.7f)); }

DropSide dropSideAt(float u, float v) {
    constexpr float edge = 0.25f;
    const float d[4] = {u, 1.f - u, v, 1.f - v};  // distance to left, right, top, bottom
    const DropSide sides[4] = {DropSide::Left, DropSide::Right, DropSide::Top, DropSide::Bottom};
    const int nearest = int(std::min_element(d, d + 4) - d);
    return d[nearest] < edge ? sides[nearest] : DropSide::Centre;
}

bool drawWorkspace(PaneLayout& layout, const std::function<void(const std::string&)>& drawPanel,
                   std::string& focusTab) {
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    layout_detail::WorkspaceDraw w{layout, drawPanel, focusTab, splitterWidth(), {}, {}, {}, {}, false};
    if (avail.x < 4 * w.thickness || avail.y < 4 * w.thickness) return false;  // minimised window
    layout_detail::drawNode(w, layout.root, origin, avail, 0);
    // The panes' child windows were placed by hand: claim their area so the parent's layout knows it.
    ImGui::SetCursorScreenPos(origin);
    ImGui::Dummy(avail);
    for (FloatingPanel& f : layout.floating) layout_detail::drawFloating(w, f);
    bool changed = w.floatingMoved;
    if (w.move) changed |= layout.moveTab(w.move->tab, w.move->target, w.move->side);
    else if (!w.reorder.empty()) changed |= layout.reorderPane(w.reorder);
    else if (!w.dock.empty()) changed |= layout.dockTab(w.dock);
    else if (!w.undock.empty()) {
        // The new window opens under the pointer, a third of the workspace in size.
        const ImVec2 m = ImGui::GetIO().MousePos;
        changed |= layout.floatTab(w.undock, std::round(m.x), std::round(m.y), std::round(std::max(320.f, avail.x / 3)),
                                   std::round(std::max(240.f, avail.y / 3)));
    }
    return changed;
}

void drawPanel(WorkbenchState& state, const std::string& name) {
    // Each panel gets the view of what it draws (panels/panel_views.h), never the whole state.
    using Draw = void (*)(WorkbenchState&);
    static const std::pair<const char*, Draw> kPanels[] = {
        {"Project", [](WorkbenchState& s) { drawProjectPanel(projectPanelView(s)); }},
        {"Scene", [](WorkbenchState& s) { drawScenePanel(scenePanelView(s)); }},
        {"Sampling", [](WorkbenchState& s) { drawSamplingPanel(samplingPanelView(s)); }},
        {"Network", [](WorkbenchState& s) { drawNetworkPanel(networkPanelView(s)); }},
        {"Views", [](WorkbenchState& s) { drawViewsPanel(viewsPanelView(s)); }},
        {"Training", [](WorkbenchState& s) { drawTrainingPanel(trainingPanelView(s)); }},
        {"Objects", [](WorkbenchState& s) { drawObjectsPanel(objectsPanelView(s)); }},
        {"Cost", [](WorkbenchState& s) { drawCostPanel(costPanelView(s)); }},
        {"Leaves", [](WorkbenchState& s) { drawLeavesPanel(leavesPanelView(s)); }},
        {"Light region", [](WorkbenchState& s) { drawLightRegionPanel(lightRegionPanelView(s)); }},
        {"Log", [](WorkbenchState& s) { drawLogPanel(logPanelView(s)); }},
    };
    for (const auto& [panel, draw] : kPanels)
        if (name == panel) draw(state);
}

void sameLineIfFits(float width) {
    const float right = ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + width;
    if (right <= ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x) ImGui::SameLine();
}

float labelledWidth(float frameWidth, const char* label) {
    const float text = ImGui::CalcTextSize(label, nullptr, true).x;
    return text > 0.f ? frameWidth + ImGui::GetStyle().ItemInnerSpacing.x + text : frameWidth;
}

float fieldWidth(float preferred, const char* label) {
    const float room = ImGui::GetContentRegionAvail().x - (labelledWidth(0.f, label));
    return std::max(ImGui::GetFontSize() * 4, std::min(preferred, room));
}

}  // namespace rrf::panels
