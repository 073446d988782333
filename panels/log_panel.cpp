// Log panel: every message the workbench and its jobs reported, filterable, copyable.
#include <algorithm>
#include <string>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "panels/layout.h"
#include "panels/panels.h"

namespace rrf::panels {

namespace log_panel_detail {
namespace {
struct LogView {
    bool showInfo = true, showWarnings = true, showErrors = true;
    bool autoScroll = true;
    std::string filter;
    uint64_t seenRevision = 0;
};

ImVec4 levelColour(LogLevel level) {
    switch (level) {
        case LogLevel::Warning: return ImVec4(1.f, 0.8f, 0.3f, 1.f);
        case LogLevel::Error: return ImVec4(1.f, 0.4f, 0.4f, 1.f);
        default: return ImGui::GetStyleColorVec4(ImGuiCol_Text);
    }
}

bool shown(const LogView& v, const LogEntry& e) {
    if (e.level == LogLevel::Info && !v.showInfo) return false;
    if (e.level == LogLevel::Warning && !v.showWarnings) return false;
    if (e.level == LogLevel::Error && !v.showErrors) return false;
    return v.filter.empty() || e.text.find(v.filter) != std::string::npos;
}
}  // namespace
}  // namespace log_panel_detail

void drawLogPanel(const LogPanelView& panel) {
    // One log view per ImGui context; the view settings are UI state, not project state.
    static log_panel_detail::LogView view;
    // The toolbar wraps in a narrow pane (each item goes on the line when it fits, else starts the
    // next one), and the filter field shrinks to the room left, down to a few characters: nothing
    // is cut off at the pane's edge.
    auto button = [](const char* label) { return ImGui::CalcTextSize(label, nullptr, true).x + 2 * ImGui::GetStyle().FramePadding.x; };
    const float box = ImGui::GetFrameHeight();  // a checkbox's square
    if (ImGui::Button("Copy all")) ImGui::SetClipboardText(panel.log.text().c_str());
    sameLineIfFits(button("Clear"));
    if (ImGui::Button("Clear")) panel.log.clear();
    sameLineIfFits(labelledWidth(box, "info"));
    ImGui::Checkbox("info", &view.showInfo);
    sameLineIfFits(labelledWidth(box, "warnings"));
    ImGui::Checkbox("warnings", &view.showWarnings);
    sameLineIfFits(labelledWidth(box, "errors"));
    ImGui::Checkbox("errors", &view.showErrors);
    sameLineIfFits(labelledWidth(box, "follow"));
    ImGui::Checkbox("follow", &view.autoScroll);
    const float filterMin = ImGui::GetFontSize() * 6, filterWanted = ImGui::GetFontSize() * 12;
    sameLineIfFits(filterMin);
    ImGui::SetNextItemWidth(std::max(filterMin, std::min(filterWanted, ImGui::GetContentRegionAvail().x)));
    ImGui::InputTextWithHint("##filter", "filter", &view.filter);

    if (ImGui::BeginChild("##log-lines", ImVec2(0, 0), false, ImGuiWindowFlags_HorizontalScrollbar)) {
        const std::vector<LogEntry> entries = panel.log.entries();
        int n = 0;
        for (const LogEntry& e : entries) {
            if (!log_panel_detail::shown(view, e)) continue;
            ImGui::PushID(n++);
            ImGui::TextDisabled("%8.2f", e.time);
            ImGui::SameLine();
            ImGui::PushStyleColor(ImGuiCol_Text, log_panel_detail::levelColour(e.level));
            ImGui::TextUnformatted(e.text.c_str());
            ImGui::PopStyleColor();
            // Right-click a line to copy just that message.
            if (ImGui::BeginPopupContextItem("##line")) {
                if (ImGui::MenuItem("Copy line")) ImGui::SetClipboardText(e.text.c_str());
                ImGui::EndPopup();
            }
            ImGui::PopID();
        }
        const uint64_t rev = panel.log.revision();
        if (view.autoScroll && rev != view.seenRevision) ImGui::SetScrollHereY(1.f);
        view.seenRevision = rev;
    }
    ImGui::EndChild();
}

}  // namespace rrf::panels
