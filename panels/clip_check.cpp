#include "panels/clip_check.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include <imgui.h>
#include <imgui_internal.h>

namespace rrf::panels {

namespace clip_check_detail {
namespace {
/// What the fitted widgets reported in the frame `frame` (the UI thread's only; cleared per frame).
struct FrameReports {
    int frame = -1;
    std::vector<ClippedContent> items;
};

FrameReports& reports() {
    static FrameReports r;
    return r;
}

void report(ClippedContent c) {
    FrameReports& r = reports();
    if (r.frame != ImGui::GetFrameCount()) {
        r.frame = ImGui::GetFrameCount();
        r.items.clear();
    }
    r.items.push_back(std::move(c));
}

/// One pixel of slack: item widths are rounded, clip rectangles are not.
constexpr float kSlack = 1.f;
}  // namespace
}  // namespace clip_check_detail

std::string ClippedContent::describe() const {
    char buf[96];
    std::snprintf(buf, sizeof buf, ": needs %.0f px, has %.0f px", double(needed), double(available));
    return where + buf;
}

std::vector<ClippedContent> findClippedContent() {
    const ImGuiContext& g = *GImGui;
    std::vector<ClippedContent> found;
    const ImGuiWindowFlags grows = ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_Tooltip |
                                   ImGuiWindowFlags_HorizontalScrollbar | ImGuiWindowFlags_AlwaysHorizontalScrollbar;
    ImGuiContext& mg = *GImGui;
    // A table that scrolls sideways declares its columns' full width to the window around it (ImGui
    // lets that window grow to fit it), although the table shows all of it by scrolling.
    auto scrollingTableReaches = [&](const ImGuiWindow* w, float right) {
        for (int i = 0; i < mg.Tables.GetMapSize(); ++i) {
            const ImGuiTable* t = mg.Tables.TryGetMapData(i);
            if (t && t->LastFrameActive == g.FrameCount && t->OuterWindow == w && (t->Flags & ImGuiTableFlags_ScrollX) &&
                t->OuterRect.Min.x + t->ColumnsAutoFitWidth >= right - clip_check_detail::kSlack)
                return true;
        }
        return false;
    };
    for (const ImGuiWindow* w : g.Windows) {
        // Windows that grow with their content or scroll sideways show all of it.
        if (!w->Active || w->Hidden || (w->Flags & grows) || w->ScrollbarX) continue;
        const float right = w->DC.CursorMaxPos.x, limit = w->InnerClipRect.Max.x;
        if (right > limit + clip_check_detail::kSlack && !scrollingTableReaches(w, right))
            found.push_back({std::string("window ") + w->Name, right - w->WorkRect.Min.x, limit - w->WorkRect.Min.x});
    }
    // Tables are ImGui's persistent pool; only those drawn in this frame count.
    for (int i = 0; i < mg.Tables.GetMapSize(); ++i) {
        const ImGuiTable* t = mg.Tables.TryGetMapData(i);
        if (!t || t->LastFrameActive != g.FrameCount) continue;
        for (int c = 0; c < t->ColumnsCount; ++c) {
            const ImGuiTableColumn& col = t->Columns[c];
            if (!col.IsEnabled || !col.IsVisibleX || (col.Flags & ImGuiTableColumnFlags_NoClip)) continue;
            const float content = std::max({col.ContentMaxXFrozen, col.ContentMaxXUnfrozen, col.ContentMaxXHeadersIdeal});
            // Against the column's own edge, not its clip rectangle: in a table that scrolls sideways
            // a column partly scrolled out of view is clipped by the view, not cut.
            if (content > col.MaxX + clip_check_detail::kSlack)
                found.push_back({std::string("table in ") + (t->OuterWindow ? t->OuterWindow->Name : "?") + ", column '" +
                                     ImGui::TableGetColumnName(t, c) + "'",
                                 content - col.MinX, col.MaxX - col.MinX});
        }
    }
    const clip_check_detail::FrameReports& r = clip_check_detail::reports();
    if (r.frame == g.FrameCount) found.insert(found.end(), r.items.begin(), r.items.end());
    return found;
}

float fittedComboWidth(const char* items) {
    float widest = 0.f;
    for (const char* p = items; *p; p += std::strlen(p) + 1) widest = std::max(widest, ImGui::CalcTextSize(p).x);
    return widest + ImGui::GetFrameHeight() + 2 * ImGui::GetStyle().FramePadding.x;
}

void fittedProgressBar(float fraction, float width, const char* overlay) {
    const float needed = ImGui::CalcTextSize(overlay).x + 2 * ImGui::GetStyle().FramePadding.x;
    const float avail = ImGui::GetContentRegionAvail().x;
    const float w = std::max(1.f, std::min(std::max(width, needed), avail));
    if (needed > w + clip_check_detail::kSlack)
        clip_check_detail::report({std::string("progress bar text '") + overlay + "'", needed, w});
    ImGui::ProgressBar(fraction, ImVec2(w, 0), overlay);
}

}  // namespace rrf::panels
