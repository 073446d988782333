// Docking without the docking branch (issue 14 item 7) driven with the mouse in a bare ImGui context,
// and the clipped-text check of item 6 (panels/clip_check.h) on content that does and does not fit.
#include <string>

#include <imgui_internal.h>

#include "panels/clip_check.h"
#include "panels/layout.h"
#include "panels/panels.h"
#include "tests/gui/imgui_fixture.h"

namespace rrf::test::test_pane_docking {

using namespace rrf::panels;

namespace {
/// The workspace with every pane's panel a plain line of text naming it.
struct Workspace {
    PaneLayout layout;
    std::string focus;
    bool changed = false;
    void draw() {
        changed |= drawWorkspace(layout, [](const std::string& name) { ImGui::TextUnformatted(name.c_str()); }, focus);
    }
};
}  // namespace

class DockingTest : public ImGuiFixture {
protected:
    /// Presses on the left pane's first tab ("Project", top left), leaves the tab bar downwards, then
    /// carries the tab to (x, y) and lets go there, a frame per step, as a user's drag does.
    void carryProjectTab(Workspace& w, float x, float y) {
        mouse(24, 16, false);
        for (int i = 0; i < 3; ++i) frame([&] { w.draw(); });
        mouse(24, 16, true);
        frame([&] { w.draw(); });
        for (int i = 1; i <= 10; ++i) {
            mouse(24.f, 16.f + 10.f * float(i), true);
            frame([&] { w.draw(); });
        }
        for (int i = 1; i <= 20; ++i) {
            mouse(24.f + (x - 24.f) * float(i) / 20.f, 116.f + (y - 116.f) * float(i) / 20.f, true);
            frame([&] { w.draw(); });
        }
        mouse(x, y, false);
        frame([&] { w.draw(); });
        frame([&] { w.draw(); });
    }
    /// A right click on the "Project" tab: its context menu opens at the pointer.
    void openProjectTabMenu(Workspace& w) {
        mouse(24, 16, false);
        ImGui::GetIO().MouseDown[1] = true;
        frame([&] { w.draw(); });
        ImGui::GetIO().MouseDown[1] = false;
        frame([&] { w.draw(); });
        frame([&] { w.draw(); });
    }
    /// A left click at (x, y): the pointer moves there, presses and lets go, a frame each.
    void clickAt(Workspace& w, float x, float y) {
        mouse(x, y, false);
        frame([&] { w.draw(); });
        mouse(x, y, true);
        frame([&] { w.draw(); });
        mouse(x, y, false);
        frame([&] { w.draw(); });
        frame([&] { w.draw(); });
    }
};

TEST(DropSide, EdgeQuartersSplitTheMiddleJoins) {
    EXPECT_EQ(dropSideAt(0.5f, 0.5f), DropSide::Centre);
    EXPECT_EQ(dropSideAt(0.3f, 0.7f), DropSide::Centre);
    EXPECT_EQ(dropSideAt(0.1f, 0.5f), DropSide::Left);
    EXPECT_EQ(dropSideAt(0.9f, 0.5f), DropSide::Right);
    EXPECT_EQ(dropSideAt(0.5f, 0.2f), DropSide::Top);
    EXPECT_EQ(dropSideAt(0.5f, 0.95f), DropSide::Bottom);
    EXPECT_EQ(dropSideAt(0.9f, 0.99f), DropSide::Bottom) << "the nearer edge wins in a corner";
}

TEST_F(DockingTest, DraggingATabOntoAPaneEdgeSplitsIt) {
    Workspace w;
    // Press on the left pane's first tab ("Project", top left), leave the tab bar downwards, then
    // carry the tab to the right edge of the Views pane (right of x = 0.27 · 1600, upper part).
    carryProjectTab(w, 1540, 300);
    EXPECT_TRUE(w.changed);
    ASSERT_EQ(w.layout.panes().size(), 4u);
    const PaneNode& top = w.layout.root.children[1].children[0];
    ASSERT_EQ(top.split, PaneSplit::Row) << "the Views pane split side by side";
    EXPECT_EQ(top.children[0].tabs, (std::vector<std::string>{"Views"}));
    EXPECT_EQ(top.children[1].tabs, (std::vector<std::string>{"Project"}));
    EXPECT_EQ(w.layout.root.children[0].tabs, (std::vector<std::string>{"Scene", "Sampling", "Network"}));
}

TEST_F(DockingTest, DroppingATabOnAnotherPanesTabBarJoinsThatPane) {
    Workspace w;
    // Carry "Project" as above, then drop it on the Views pane's tab bar (top of the right column,
    // inside the pane's top edge zone, where a drop on the pane body would split it).
    carryProjectTab(w, 1000, 16);
    EXPECT_TRUE(w.changed);
    ASSERT_EQ(w.layout.panes().size(), 3u) << "no pane was split";
    EXPECT_EQ(w.layout.root.children[1].children[0].tabs, (std::vector<std::string>{"Views", "Project"}));
}

TEST_F(DockingTest, DraggingATabAlongItsBarReordersThePane) {
    Workspace w;
    for (int i = 0; i < 3; ++i) frame([&] { w.draw(); });
    // The "Scene" tab follows "Project" (8 px window padding, tabs ItemInnerSpacing apart); drag it
    // to the left along the bar, past "Project".
    const ImGuiStyle& st = ImGui::GetStyle();
    const float sceneX = 8.f + ImGui::CalcTextSize("Project").x + 2 * st.FramePadding.x + st.ItemInnerSpacing.x + 10.f;
    mouse(sceneX, 16, false);
    frame([&] { w.draw(); });
    mouse(sceneX, 16, true);
    frame([&] { w.draw(); });
    for (int i = 1; i <= 10; ++i) {
        mouse(sceneX - (sceneX - 10.f) * float(i) / 10.f, 16, true);
        frame([&] { w.draw(); });
    }
    mouse(10, 16, false);
    for (int i = 0; i < 3; ++i) frame([&] { w.draw(); });
    EXPECT_TRUE(w.changed);
    EXPECT_EQ(w.layout.root.children[0].tabs, (std::vector<std::string>{"Scene", "Project", "Sampling", "Network"}));
    EXPECT_EQ(w.layout.panes().size(), 3u) << "a drag along the bar moves no tab to another pane";
}

TEST_F(DockingTest, ContextMenuSplitsAPane) {
    Workspace w;
    for (int i = 0; i < 3; ++i) frame([&] { w.draw(); });
    // Right click on the "Project" tab opens its menu; its first entry is "Split right".
    openProjectTabMenu(w);
    // The menu opens at the pointer: its first item is just below and right of it.
    const float itemY = 16.f + ImGui::GetStyle().WindowPadding.y + ImGui::GetFontSize() * 0.5f;
    clickAt(w, 40, itemY);
    EXPECT_TRUE(w.changed);
    const PaneNode& left = w.layout.root.children[0];
    ASSERT_EQ(left.split, PaneSplit::Row);
    EXPECT_EQ(left.children[1].tabs, (std::vector<std::string>{"Project"}));
}

TEST_F(DockingTest, ContextMenuFloatsATabAndDockPutsItBack) {
    Workspace w;
    for (int i = 0; i < 3; ++i) frame([&] { w.draw(); });
    // Right click on the "Project" tab; its third entry is "Float in a window".
    openProjectTabMenu(w);
    const ImGuiStyle& style = ImGui::GetStyle();
    // Move the pointer down the open menu until its "Float in a window" item is under it.
    ASSERT_FALSE(GImGui->OpenPopupStack.empty());
    ImGuiWindow* menu = GImGui->OpenPopupStack.back().Window;
    ASSERT_NE(menu, nullptr);
    const ImGuiID item = menu->GetID("Float in a window");
    float itemY = menu->Pos.y;
    for (; itemY < menu->Pos.y + menu->Size.y; itemY += 2.f) {
        mouse(40, itemY, false);
        frame([&] { w.draw(); });
        if (GImGui->HoveredId == item) break;
    }
    ASSERT_EQ(GImGui->HoveredId, item) << "the menu has the item";
    clickAt(w, 40, itemY);
    EXPECT_TRUE(w.changed);
    EXPECT_EQ(w.layout.paneOf("Project"), nullptr);
    const FloatingPanel* f = w.layout.floatingPanel("Project");
    ASSERT_NE(f, nullptr);
    ImGuiWindow* window = ImGui::FindWindowByName("Project###floating Project");
    ASSERT_NE(window, nullptr) << "the panel has a window of its own";
    EXPECT_TRUE(window->Active) << "drawn in the last frame";
    EXPECT_FLOAT_EQ(window->Pos.x, f->x);
    EXPECT_FLOAT_EQ(window->Pos.y, f->y);

    // Its Dock button (first item under the title bar) puts it back where it came from.
    w.changed = false;
    const ImVec2 dock(window->Pos.x + style.WindowPadding.x + 8.f,
                      window->Pos.y + window->TitleBarHeight() + style.WindowPadding.y + ImGui::GetFontSize() * 0.5f);
    clickAt(w, dock.x, dock.y);
    EXPECT_TRUE(w.changed);
    EXPECT_TRUE(w.layout.floating.empty());
    ASSERT_NE(w.layout.paneOf("Project"), nullptr);
    EXPECT_EQ(w.layout.paneOf("Project"), w.layout.paneOf("Scene")) << "back in the pane it came from";
}

TEST_F(DockingTest, FocusTabBringsItToTheFrontOnce) {
    Workspace w;
    for (int i = 0; i < 2; ++i) frame([&] { w.draw(); });
    w.focus = "Log";
    for (int i = 0; i < 3; ++i) frame([&] { w.draw(); });
    EXPECT_TRUE(w.focus.empty());
    EXPECT_EQ(w.layout.paneOf("Log")->active, "Log");
    EXPECT_FALSE(w.changed) << "showing a tab is not a change of the arrangement";
}

TEST_F(DockingTest, ClipCheckFindsTextWiderThanItsWindow) {
    const std::string longText(120, 'x');
    std::vector<ClippedContent> found;
    frame([&] {
        ImGui::BeginChild("##narrow", ImVec2(200, 100), true);
        ImGui::TextUnformatted(longText.c_str());
        ImGui::EndChild();
        ImGui::BeginChild("##wrapped", ImVec2(200, 300), true);
        ImGui::TextWrapped("%s", std::string(60, ' ').append(longText).c_str());
        ImGui::EndChild();
        found = findClippedContent();
    });
    ASSERT_EQ(found.size(), 1u);
    EXPECT_NE(found[0].where.find("##narrow"), std::string::npos) << found[0].describe();
    EXPECT_NEAR(found[0].needed, ImGui::CalcTextSize(longText.c_str()).x, 1.f);
    EXPECT_LT(found[0].available, 200.f);
}

TEST_F(DockingTest, ClipCheckFindsACutTableCellAndProgressText) {
    std::vector<ClippedContent> found;
    // Auto-fit columns take their width from the frame before: look at the third frame.
    for (int i = 0; i < 3; ++i) frame([&] {
        ImGui::BeginChild("##tables", ImVec2(300, 200), false);
        if (ImGui::BeginTable("t", 2, ImGuiTableFlags_SizingFixedFit)) {
            ImGui::TableSetupColumn("short", ImGuiTableColumnFlags_WidthFixed, 40.f);
            ImGui::TableSetupColumn("fits");
            ImGui::TableNextColumn();
            ImGui::TextUnformatted("a cell far wider than forty pixels");
            ImGui::TableNextColumn();
            ImGui::TextUnformatted("ok");
            ImGui::EndTable();
        }
        fittedProgressBar(0.5f, 50.f, "short");  // grows to its text: not clipped
        ImGui::BeginChild("##bar", ImVec2(80, 40), false);
        fittedProgressBar(0.5f, 50.f, "an overlay that cannot fit in eighty pixels");
        ImGui::EndChild();
        ImGui::EndChild();
        found = findClippedContent();
    });
    std::string all;
    for (const ClippedContent& c : found) all += c.describe() + "\n";
    ASSERT_EQ(found.size(), 2u) << all;
    EXPECT_NE(found[0].where.find("column 'short'"), std::string::npos) << found[0].describe();
    EXPECT_NEAR(found[0].available, 40.f, 12.f);
    EXPECT_NE(found[1].where.find("progress bar text 'an overlay"), std::string::npos) << found[1].describe();
    EXPECT_FLOAT_EQ(found[1].available, 80.f);
}

TEST_F(DockingTest, FittedComboIsAsWideAsItsLongestItem) {
    frame([&] {
        const float w = fittedComboWidth("a\0much longer item\0b\0");
        const ImGuiStyle& st = ImGui::GetStyle();
        EXPECT_FLOAT_EQ(w, ImGui::CalcTextSize("much longer item").x + ImGui::GetFrameHeight() + 2 * st.FramePadding.x);
    });
}

TEST_F(DockingTest, FieldWidthLeavesRoomForTheLabel) {
    frame([&] {
        ImGui::BeginChild("##field", ImVec2(300, 100), false);
        const char* label = "a rather long label##id";
        const float labelW = ImGui::CalcTextSize("a rather long label").x + ImGui::GetStyle().ItemInnerSpacing.x;
        EXPECT_FLOAT_EQ(fieldWidth(80.f, label), 80.f) << "room enough: the preferred width";
        EXPECT_FLOAT_EQ(fieldWidth(250.f, label), 300.f - labelW);
        EXPECT_FLOAT_EQ(fieldWidth(250.f, std::string(80, 'w').c_str()), ImGui::GetFontSize() * 4) << "never below 4 em";
        ImGui::EndChild();
    });
}

}  // namespace rrf::test::test_pane_docking
