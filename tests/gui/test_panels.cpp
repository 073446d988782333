// Panel logic in a bare ImGui context: every panel draws without a crash, idle frames change
// nothing, and simulated input changes exactly the state it should.
#include <cmath>

#include <algorithm>
#include <set>

#include "app/gui/shortcuts.h"
#include "panels/layout.h"
#include "panels/panels.h"
#include "panels/project_io.h"
#include "tests/gui/imgui_fixture.h"

namespace rrf::test::test_panels {

using namespace rrf::panels;

namespace {
const std::string kCornell = RRF_SOURCE_DIR "/projects/cornell-box/project.json";

void drawAll(WorkbenchState& s) {
    drawWorkspace(s.project.layout, [&](const std::string& name) { drawPanel(s, name); }, s.focusTab);
}

void fillGroundTruth(WorkbenchState& s) {
    s.groundTruth.global = Image(256, 256, Vec3(0.5f));
    s.groundTruth.direct = Image(256, 256, Vec3(0.3f));
    s.groundTruth.indirect = Image(256, 256, Vec3(0.2f));
    ++s.groundTruth.revision;
}
}  // namespace

using PanelTest = ImGuiFixture;

TEST_F(PanelTest, AllPanelsDrawWithoutProjectAndWithout) {
    WorkbenchState s;
    for (int i = 0; i < 3; ++i) frame([&] { drawAll(s); });
    EXPECT_TRUE(s.requests.empty());
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, kCornell, error)) << error;
    fillGroundTruth(s);
    s.compare = s.groundTruth;
    for (int i = 0; i < 5; ++i) frame([&] { drawAll(s); });
    // Tabs other than each pane's first are not drawn by drawAll; draw each panel on its own too.
    for (int i = 0; i < 2; ++i)
        for (const std::string& name : PaneLayout::panels()) frame([&] { drawPanel(s, name); });
    EXPECT_TRUE(s.requests.empty()) << "idle frames must not ask for anything";
    EXPECT_FALSE(s.dirty) << "idle frames must not edit the project";
    EXPECT_FALSE(s.project.sampling.has_value()) << "drawing must not write a default sampling section";
    EXPECT_TRUE(s.project.overrides.empty()) << "drawing must not record scene overrides";
}

TEST_F(PanelTest, SplitterDragResizesTheLeftColumn) {
    WorkbenchState s;
    const float before = s.project.layout.root.fraction;
    const float x = before * 1600.f + 2.f;  // on the 5-pixel splitter right of the left column
    mouse(x, 500, false);
    frame([&] { drawAll(s); });
    mouse(x, 500, true);
    frame([&] { drawAll(s); });
    for (int i = 1; i <= 10; ++i) {
        mouse(x + 16.f * float(i), 500, true);
        frame([&] { drawAll(s); });
    }
    mouse(x + 160.f, 500, false);
    frame([&] { drawAll(s); });
    EXPECT_NEAR(s.project.layout.root.fraction, before + 160.f / 1600.f, 2.f / 1600.f);
    EXPECT_FLOAT_EQ(s.project.layout.root.children[1].fraction, 1.f - PaneLayout::kDefaultBottom)
        << "the other splitter must not move";
}

TEST_F(PanelTest, SplitterCannotCollapseAPane) {
    WorkbenchState s;
    const float x = s.project.layout.root.fraction * 1600.f + 2.f;
    mouse(x, 500, false);
    frame([&] { drawAll(s); });
    for (int i = 0; i < 20; ++i) {
        mouse(x - 100.f * float(i), 500, true);
        frame([&] { drawAll(s); });
    }
    mouse(0, 500, false);
    frame([&] { drawAll(s); });
    EXPECT_GE(s.project.layout.root.fraction, PaneLayout::kMinFraction - 1e-4f);
}

TEST_F(PanelTest, RenderButtonClickRequestsOneRender) {
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, kCornell, error)) << error;
    // The views panel alone at (0, 0): its first widget is the Render button.
    mouse(10, 8, false);
    frame([&] { drawViewsPanel(viewsPanelView(s)); });
    mouse(10, 8, true);
    frame([&] { drawViewsPanel(viewsPanelView(s)); });
    mouse(10, 8, false);
    frame([&] { drawViewsPanel(viewsPanelView(s)); });
    ASSERT_EQ(s.requests.size(), 1u);
    EXPECT_EQ(s.requests[0].command, Command::StartRender);

    s.requests.clear();
    s.render.running = true;  // now the same place holds "Stop render"
    mouse(10, 8, true);
    frame([&] { drawViewsPanel(viewsPanelView(s)); });
    mouse(10, 8, false);
    frame([&] { drawViewsPanel(viewsPanelView(s)); });
    ASSERT_EQ(s.requests.size(), 1u);
    EXPECT_EQ(s.requests[0].command, Command::CancelRender);
}

// The Help window (F1) lists the application's key table itself, so every shortcut that works is
// listed and every listed one has a key; the menus take their labels from the same table.
TEST_F(PanelTest, HelpWindowListsEveryShortcutOfTheKeyTable) {
    bool open = true;
    std::vector<std::string> lines;
    frame([&] { drawHelpWindow(shortcutInfos(), &open, &lines); });
    ASSERT_FALSE(shortcuts().empty());
    std::set<std::string> labels;
    for (const Shortcut& s : shortcuts()) {
        const std::string entry = std::string(s.keys) + ": " + s.what;
        EXPECT_NE(std::find(lines.begin(), lines.end(), entry), lines.end()) << entry;
        EXPECT_TRUE(labels.insert(s.keys).second) << s.keys << " is bound twice";
    }
    for (ShortcutAction a : {ShortcutAction::Open, ShortcutAction::Save, ShortcutAction::Quit, ShortcutAction::FrameOverlay,
                             ShortcutAction::Help})
        EXPECT_NE(shortcutKeys(a), nullptr) << "an action the menus advertise has no key";
    EXPECT_STREQ(shortcutKeys(ShortcutAction::Help), "F1");
    EXPECT_GT(lines.size(), shortcuts().size()) << "the mouse gestures and the tour follow the keys";
    EXPECT_TRUE(open);
}

TEST_F(PanelTest, WheelZoomsAboutTheCursorInAllViews) {
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, kCornell, error)) << error;
    fillGroundTruth(s);
    // Hover the first view (below the two toolbar rows), then scroll one notch.
    mouse(150, 250, false);
    frame([&] { drawViewsPanel(viewsPanelView(s)); });
    frame([&] { drawViewsPanel(viewsPanelView(s)); });  // hovering needs a frame for ImGui to find the window
    EXPECT_GE(s.view.hoverX, 0);
    EXPECT_GE(s.view.hoverY, 0);
    const int hx = s.view.hoverX, hy = s.view.hoverY;
    mouse(150, 250, false, 1.f);
    frame([&] { drawViewsPanel(viewsPanelView(s)); });
    mouse(150, 250, false, 0.f);
    frame([&] { drawViewsPanel(viewsPanelView(s)); });
    EXPECT_NEAR(s.view.zoom, 1.2f, 1e-5f);
    // The pixel under the cursor stays under the cursor (within a pixel of rounding).
    EXPECT_NEAR(s.view.hoverX, hx, 1);
    EXPECT_NEAR(s.view.hoverY, hy, 1);
    EXPECT_TRUE(s.view.panX != 0.f || s.view.panY != 0.f);
}

TEST_F(PanelTest, DragPansTheViews) {
    WorkbenchState s;
    fillGroundTruth(s);
    s.hasProject = true;
    mouse(150, 250, false);
    frame([&] { drawViewsPanel(viewsPanelView(s)); });
    mouse(150, 250, true);
    frame([&] { drawViewsPanel(viewsPanelView(s)); });
    for (int i = 1; i <= 5; ++i) {
        mouse(150.f + 10.f * float(i), 250, true);
        frame([&] { drawViewsPanel(viewsPanelView(s)); });
    }
    mouse(200, 250, false);
    frame([&] { drawViewsPanel(viewsPanelView(s)); });
    EXPECT_LT(s.view.panX, 0.f) << "dragging right moves the image right (the view centre left)";
    EXPECT_FLOAT_EQ(s.view.panY, 0.f);
}

// Issue 29 item 10: the light's handle in a view drags the light (in the plane facing the camera,
// within the light region), where it projects under the pointer; the view does not pan.
TEST_F(PanelTest, DraggingTheLightHandleMovesTheLight) {
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, kCornell, error)) << error;
    fillGroundTruth(s);
    const Vec3 before = s.project.scene.lightPosition();
    mouse(5, 5, false);
    frame([&] { drawViewsPanel(viewsPanelView(s)); });
    frame([&] { drawViewsPanel(viewsPanelView(s)); });
    const ImVec2 h = s.view.lightHandle[0];
    ASSERT_FALSE(std::isnan(h.x)) << "the ground-truth view draws the handle";
    mouse(h.x, h.y, false);
    frame([&] { drawViewsPanel(viewsPanelView(s)); });
    mouse(h.x, h.y, true);
    frame([&] { drawViewsPanel(viewsPanelView(s)); });
    for (int i = 1; i <= 6; ++i) {
        mouse(h.x + 4.f * float(i), h.y + 3.f * float(i), true);
        frame([&] { drawViewsPanel(viewsPanelView(s)); });
    }
    mouse(h.x + 24.f, h.y + 18.f, false);
    frame([&] { drawViewsPanel(viewsPanelView(s)); });
    frame([&] { drawViewsPanel(viewsPanelView(s)); });
    const Vec3 after = s.project.scene.lightPosition();
    EXPECT_GT(after.x, before.x) << "right in the image is +x for this camera";
    EXPECT_LT(after.y, before.y) << "down in the image is lower";
    EXPECT_FLOAT_EQ(after.z, before.z) << "the plane facing the camera";
    EXPECT_TRUE(s.project.scene.lightRegion.contains(after));
    EXPECT_NEAR(s.view.lightHandle[0].x, h.x + 24.f, 1.f) << "the handle is under the pointer";
    EXPECT_NEAR(s.view.lightHandle[0].y, h.y + 18.f, 1.f);
    EXPECT_FLOAT_EQ(s.view.panX, 0.f) << "a drag on the handle does not pan";
    EXPECT_FLOAT_EQ(s.view.panY, 0.f);
    EXPECT_TRUE(s.dirty);
    EXPECT_TRUE(std::any_of(s.requests.begin(), s.requests.end(),
                            [](const Request& r) { return r.command == Command::SceneChanged; }));
}

// Issue 30 item 6: a right-button drag in a view marks a region (the pixels between the press and the
// mouse, both included), without panning; a right click without a drag clears it.
TEST_F(PanelTest, RightDragMarksARegionAndARightClickClearsIt) {
    WorkbenchState s;
    fillGroundTruth(s);
    s.hasProject = true;
    auto right = [&](float x, float y, bool down) {
        mouse(x, y, false);
        ImGui::GetIO().MouseDown[1] = down;
        frame([&] { drawViewsPanel(viewsPanelView(s)); });
    };
    right(150, 250, false);
    right(150, 250, false);  // hovering needs a frame
    const int ax = s.view.hoverX, ay = s.view.hoverY;
    ASSERT_GE(ax, 0);
    right(150, 250, true);
    for (int i = 1; i <= 5; ++i) right(150.f + 8.f * float(i), 250.f + 4.f * float(i), true);
    const int bx = s.view.hoverX, by = s.view.hoverY;
    right(190, 270, false);
    EXPECT_FLOAT_EQ(s.view.panX, 0.f) << "the right button does not pan";
    ASSERT_FALSE(s.view.region.empty());
    EXPECT_EQ(s.view.region.x0, ax);
    EXPECT_EQ(s.view.region.y0, ay);
    EXPECT_EQ(s.view.region.x1, bx + 1);
    EXPECT_EQ(s.view.region.y1, by + 1);
    right(150, 250, true);
    right(150, 250, false);
    EXPECT_TRUE(s.view.region.empty()) << "a right click without a drag clears the region";
}

TEST_F(PanelTest, LogCollectsMessagesAndCopiesThem) {
    WorkbenchState s;
    s.log.info("first");
    s.log.error("second");
    frame([&] { drawLogPanel(logPanelView(s)); });
    EXPECT_EQ(s.log.errorCount(), 1u);
    const std::string text = s.log.text();
    EXPECT_NE(text.find("info: first"), std::string::npos);
    EXPECT_NE(text.find("error: second"), std::string::npos);
}

}  // namespace rrf::test::test_panels

namespace rrf::test::test_panels {

TEST_F(PanelTest, LightRegionCellClickMovesTheLightToItsGridPosition) {
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, kCornell, error)) << error;
    s.training.modelsDir = "models";  // as if models were loaded
    const Bounds3 region = s.project.scene.lightRegion;
    LightGridMap m;
    m.grid = LightGridSpec::parse("2x1x3", "test", "grid");
    m.region = region;
    m.lights = m.grid.positions(region);
    m.global = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6};
    m.globalRaw = m.global;
    m.globalNoiseFloor.assign(6, 0.01);
    m.objects.assign(s.project.scene.objects.size(), m.global);
    m.marksWhy = "test";
    s.lightRegion.map = m;
    // The slice is the item before the panel's last line: its bottom-left cell is (x lo, z hi).
    ImVec2 lastLine;
    frame([&] {
        drawLightRegionPanel(lightRegionPanelView(s));
        lastLine = ImGui::GetItemRectMin();
    });
    EXPECT_TRUE(s.requests.empty());
    const float x = lastLine.x + 6, y = lastLine.y - ImGui::GetStyle().ItemSpacing.y - 6;
    mouse(x, y, false);
    frame([&] { drawLightRegionPanel(lightRegionPanelView(s)); });
    mouse(x, y, true);
    frame([&] { drawLightRegionPanel(lightRegionPanelView(s)); });
    mouse(x, y, false);
    frame([&] { drawLightRegionPanel(lightRegionPanelView(s)); });
    ASSERT_EQ(s.requests.size(), 1u);
    EXPECT_EQ(s.requests[0].command, Command::SceneChanged);
    EXPECT_TRUE(s.dirty);
    const Vec3 moved = s.project.scene.lightPosition();
    const Vec3 want = m.lights[m.grid.index(0, 0, 2)];
    EXPECT_FLOAT_EQ(moved.x, want.x);
    EXPECT_FLOAT_EQ(moved.y, want.y);
    EXPECT_FLOAT_EQ(moved.z, want.z);
    EXPECT_FLOAT_EQ(want.x, region.lo.x);
    EXPECT_FLOAT_EQ(want.z, region.hi.z);
}

}  // namespace rrf::test::test_panels
