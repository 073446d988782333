#include "panels/frame_overlay.h"

#include <algorithm>

namespace rrf::panels {

ImVec2 frameOverlayCorner(const ViewState& v, ImVec2 fallback) {
    if (v.drawnFrame != ImGui::GetFrameCount()) return fallback;
    // The top-right corner of the block of views (a row, a grid or one view): image pixels only.
    bool any = false;
    ImVec2 corner(0, 0);
    for (int i = 0; i < 3; ++i) {
        if (v.viewMax[i].x <= v.viewMin[i].x || v.viewMax[i].y <= v.viewMin[i].y) continue;
        corner = any ? ImVec2(std::max(corner.x, v.viewMax[i].x), std::min(corner.y, v.viewMin[i].y))
                     : ImVec2(v.viewMax[i].x, v.viewMin[i].y);
        any = true;
    }
    if (!any) return fallback;
    // Below the toolbar in any case (a view cannot start above it, but a corner never goes there).
    const float inset = ImGui::GetStyle().ItemSpacing.y;
    return ImVec2(corner.x - inset, std::max(corner.y, v.toolbarMax.y) + inset);
}

std::pair<ImVec2, ImVec2> drawFrameOverlay(const std::vector<std::string>& lines, const ViewState& view, ImVec2 fallback) {
    ImGui::SetNextWindowPos(frameOverlayCorner(view, fallback), ImGuiCond_Always, ImVec2(1, 0));
    ImGui::SetNextWindowBgAlpha(0.7f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                   ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs;
    std::pair<ImVec2, ImVec2> rect;
    if (ImGui::Begin("##frame-time", nullptr, flags)) {
        for (size_t i = 0; i < lines.size(); ++i) {
            if (i + 1 < lines.size()) ImGui::TextUnformatted(lines[i].c_str());
            else ImGui::TextDisabled("%s", lines[i].c_str());
        }
    }
    const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    rect = {pos, ImVec2(pos.x + size.x, pos.y + size.y)};
    ImGui::End();
    return rect;
}

}  // namespace rrf::panels
