// Help window (F1, Help > Shortcuts and help): the keyboard shortcuts from the application's one
// table (app/gui/shortcuts.h), the mouse gestures of the views, plots and panes, and where each
// stage of the method is driven from. A floating window over the panes, closed by F1 again, its
// close button or Escape.
#include <imgui.h>

#include "panels/panels.h"

namespace rrf::panels {

namespace help_window_detail {
namespace {
struct Gesture {
    const char* where;
    const char* how;
    const char* what;
};

// The gestures the panels implement (views_panel.cpp, plot.cpp, layout.cpp, ImGui's own fields).
const Gesture kGestures[] = {
    {"Views", "mouse wheel", "zoom all three views together"},
    {"Views", "left drag", "pan all three views together"},
    {"Views", "drag the light's handle", "move the light (Shift: keep its height), within its region"},
    {"Views", "right drag", "draw a region of interest (its error figures below); right click clears it"},
    {"Views", "hover", "read out the pixel's values in every view"},
    {"Plots", "mouse wheel / left drag", "zoom / pan (Training loss, Cost)"},
    {"Plots", "double click", "fit the data again"},
    {"Plots", "click a legend entry", "hide or show that series"},
    {"Numeric fields", "click", "type a value; drag to change it"},
    {"Tabs", "drag a tab", "onto a pane's centre or tab bar to join it, onto its edge to split (View > Reset layout)"},
    {"Tabs", "right click a tab", "split its pane, move it, or float it in a window of its own (Dock puts it back)"},
    {"Runs table", "tick A and B", "compare two training runs' predictions side by side"},
};

const char* const kTour[] = {
    "The pipeline bar (top): one click renders the ground truth, generates training records, trains "
    "and evaluates; hovering its choice says what accuracy and time to expect.",
    "Scene and Sampling: the light's position and materials; the viewpoint grid, directions and "
    "paths per record the training data is made with.",
    "Network and Training: layers, encoding, trainer; Train shows the loss live and evaluates after.",
    "Views: ground truth | prediction | error, with FLIP and the ensemble's spread; Objects: the "
    "error per object; Cost: what accuracy costs in time; Project: the runs table; Log: everything.",
};
}  // namespace
}  // namespace help_window_detail

void drawHelpWindow(const std::vector<ShortcutInfo>& shortcuts, bool* open, std::vector<std::string>* linesShown) {
    if (!*open) return;
    if (linesShown) linesShown->clear();
    auto line = [&](const std::string& text) {
        if (linesShown) linesShown->push_back(text);
    };
    const float font = ImGui::GetFontSize();
    ImGui::SetNextWindowSize(ImVec2(font * 40, font * 30), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Help", open, ImGuiWindowFlags_NoCollapse)) {
        ImGui::End();
        return;
    }
    if (ImGui::IsWindowFocused(ImGuiFocusedFlags_RootAndChildWindows) && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
        *open = false;
    ImGui::TextUnformatted("Keyboard");
    if (ImGui::BeginTable("##keys", 2, ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_RowBg)) {
        for (const ShortcutInfo& s : shortcuts) {
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(s.keys.c_str());
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(s.what.c_str());
            line(s.keys + ": " + s.what);
        }
        ImGui::EndTable();
    }
    ImGui::Spacing();
    ImGui::TextUnformatted("Mouse");
    if (ImGui::BeginTable("##mouse", 3, ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_RowBg)) {
        for (const help_window_detail::Gesture& g : help_window_detail::kGestures) {
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(g.where);
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(g.how);
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(g.what);
            line(std::string(g.where) + ", " + g.how + ": " + g.what);
        }
        ImGui::EndTable();
    }
    ImGui::Spacing();
    ImGui::TextUnformatted("Where things are");
    ImGui::PushTextWrapPos(0.f);
    for (const char* t : help_window_detail::kTour) {
        ImGui::Bullet();
        ImGui::TextUnformatted(t);
        line(t);
    }
    ImGui::PopTextWrapPos();
    ImGui::End();
}

}  // namespace rrf::panels
