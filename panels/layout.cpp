#include "panels/layout.h"

#include <algorithm>
#include <cmath>

#include <imgui.h>
#include <imgui_internal.h>

namespace rrf::panels {

namespace {
/// One splitter between two panes along `axis`; `first` is the size of the pane before it.
void splitter(const char* id, ImGuiAxis axis, const ImVec2& origin, float total, float cross, float thickness,
              float& first) {
    float second = total - first - thickness;
    const float minSize = total * PaneLayout::kMinFraction;
    ImRect bb;
    if (axis == ImGuiAxis_X)
        bb = ImRect(ImVec2(origin.x + first, origin.y), ImVec2(origin.x + first + thickness, origin.y + cross));
    else
        bb = ImRect(ImVec2(origin.x, origin.y + first), ImVec2(origin.x + cross, origin.y + first + thickness));
    ImGui::SplitterBehavior(bb, ImGui::GetID(id), axis, &first, &second, minSize, minSize, 4.f, 0.f);
}
}  // namespace

void drawWorkspace(PaneLayout& layout, const std::function<void()>& left, const std::function<void()>& centre,
                   const std::function<void()>& bottom) {
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const float t = std::max(4.f, std::round(ImGui::GetFontSize() * 0.35f));
    if (avail.x < 4 * t || avail.y < 4 * t) return;  // minimised window: nothing sensible to draw

    layout.left = PaneLayout::clampFraction(layout.left, PaneLayout::kDefaultLeft);
    layout.bottom = PaneLayout::clampFraction(layout.bottom, PaneLayout::kDefaultBottom);

    // Left column | right side.
    float leftW = std::round(layout.left * avail.x);
    splitter("##split-left", ImGuiAxis_X, origin, avail.x, avail.y, t, leftW);
    layout.left = PaneLayout::clampFraction(leftW / avail.x, PaneLayout::kDefaultLeft);
    leftW = std::round(layout.left * avail.x);
    const float rightW = avail.x - leftW - t;

    // Centre above bottom, inside the right side.
    const ImVec2 rightOrigin(origin.x + leftW + t, origin.y);
    float centreH = avail.y - std::round(layout.bottom * avail.y) - t;
    splitter("##split-bottom", ImGuiAxis_Y, rightOrigin, avail.y, rightW, t, centreH);
    layout.bottom = PaneLayout::clampFraction((avail.y - centreH - t) / avail.y, PaneLayout::kDefaultBottom);
    centreH = avail.y - std::round(layout.bottom * avail.y) - t;
    const float bottomH = avail.y - centreH - t;

    ImGui::SetCursorScreenPos(origin);
    if (ImGui::BeginChild("##left", ImVec2(leftW, avail.y), true)) left();
    ImGui::EndChild();

    ImGui::SetCursorScreenPos(rightOrigin);
    if (ImGui::BeginChild("##centre", ImVec2(rightW, centreH), true)) centre();
    ImGui::EndChild();

    ImGui::SetCursorScreenPos(ImVec2(rightOrigin.x, rightOrigin.y + centreH + t));
    if (ImGui::BeginChild("##bottom", ImVec2(rightW, bottomH), true)) bottom();
    ImGui::EndChild();
}

void sameLineIfFits(float width) {
    const float right = ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + width;
    if (right <= ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x) ImGui::SameLine();
}

float labelledWidth(float frameWidth, const char* label) {
    const float text = ImGui::CalcTextSize(label, nullptr, true).x;
    return text > 0.f ? frameWidth + ImGui::GetStyle().ItemInnerSpacing.x + text : frameWidth;
}

}  // namespace rrf::panels
