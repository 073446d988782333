// The pane tree of the workbench's layout (issue 14 item 7): tabs move between panes, panes split
// and collapse, every panel stays in exactly one pane, and the tree survives a JSON round trip;
// damaged files fall back with warnings, old files load as the fixed three-pane arrangement.
#include <algorithm>
#include <limits>

#include <gtest/gtest.h>

#include "core/project/pane_layout.h"
#include "core/project/pane_layout_json.h"

namespace rrf::test::test_pane_layout {

using nlohmann::json;

namespace {
/// Every panel exactly once over all panes and floating windows.
bool holdsEveryPanelOnce(const PaneLayout& l) {
    std::vector<std::string> all;
    for (const PaneNode* p : l.panes()) all.insert(all.end(), p->tabs.begin(), p->tabs.end());
    for (const FloatingPanel& f : l.floating) all.push_back(f.tab);
    std::vector<std::string> want = PaneLayout::panels();
    std::sort(all.begin(), all.end());
    std::sort(want.begin(), want.end());
    return all == want;
}

PaneLayout read(const json& j, std::vector<std::string>& warnings) {
    return paneLayoutFromJson(JsonReader(j, "p.json", "/layout"), warnings);
}
}  // namespace

TEST(PaneLayout, DefaultIsThreePanes) {
    const PaneLayout l;
    ASSERT_EQ(l.panes().size(), 3u);
    EXPECT_EQ(l.panes()[0]->tabs, (std::vector<std::string>{"Project", "Scene", "Sampling", "Network"}));
    EXPECT_EQ(l.panes()[1]->tabs, (std::vector<std::string>{"Views"}));
    EXPECT_EQ(l.panes()[2]->tabs, (std::vector<std::string>{"Training", "Objects", "Cost", "Leaves", "Light region", "Log"}));
    EXPECT_EQ(l.root.split, PaneSplit::Row);
    EXPECT_FLOAT_EQ(l.root.fraction, 0.27f);
    EXPECT_EQ(l.root.children[1].split, PaneSplit::Column);
    EXPECT_FLOAT_EQ(l.root.children[1].fraction, 0.68f);
    EXPECT_TRUE(holdsEveryPanelOnce(l));
}

TEST(PaneLayout, MoveTabIntoAnotherPaneShowsIt) {
    PaneLayout l;
    ASSERT_TRUE(l.moveTab("Objects", "Views", DropSide::Centre));
    const PaneNode* views = l.paneOf("Views");
    ASSERT_NE(views, nullptr);
    EXPECT_EQ(views->tabs, (std::vector<std::string>{"Views", "Objects"}));
    EXPECT_EQ(views->active, "Objects");
    EXPECT_EQ(l.paneOf("Training")->tabs, (std::vector<std::string>{"Training", "Cost", "Leaves", "Light region", "Log"}));
    EXPECT_EQ(l.panes().size(), 3u);
    EXPECT_TRUE(holdsEveryPanelOnce(l));
    EXPECT_FALSE(l.moveTab("Objects", "Views", DropSide::Centre)) << "already there";
    EXPECT_FALSE(l.moveTab("Nope", "Views", DropSide::Centre));
}

TEST(PaneLayout, SplitPutsTheTabBesideItsPane) {
    PaneLayout l;
    // Sampling next to Network: its own pane to the right of the left column's pane.
    ASSERT_TRUE(l.moveTab("Sampling", "Network", DropSide::Right));
    const PaneNode& left = l.root.children[0];
    ASSERT_EQ(left.split, PaneSplit::Row);
    EXPECT_FLOAT_EQ(left.fraction, 0.5f);
    EXPECT_EQ(left.children[0].tabs, (std::vector<std::string>{"Project", "Scene", "Network"}));
    EXPECT_EQ(left.children[1].tabs, (std::vector<std::string>{"Sampling"}));
    EXPECT_NE(l.paneOf("Sampling"), l.paneOf("Network"));
    // Objects above Training: the bottom pane splits into a column, Objects first.
    ASSERT_TRUE(l.moveTab("Objects", "Training", DropSide::Top));
    const PaneNode& bottom = l.root.children[1].children[1];
    ASSERT_EQ(bottom.split, PaneSplit::Column);
    EXPECT_EQ(bottom.children[0].tabs, (std::vector<std::string>{"Objects"}));
    EXPECT_EQ(l.panes().size(), 5u);
    EXPECT_TRUE(holdsEveryPanelOnce(l));
    // A pane's only tab cannot split its own pane.
    EXPECT_FALSE(l.moveTab("Objects", "Objects", DropSide::Left));
}

TEST(PaneLayout, EmptiedPaneCollapsesIntoItsSibling) {
    PaneLayout l;
    // The Views pane's only tab joins the bottom pane: the centre/bottom split disappears.
    ASSERT_TRUE(l.moveTab("Views", "Log", DropSide::Centre));
    ASSERT_EQ(l.panes().size(), 2u);
    EXPECT_EQ(l.root.split, PaneSplit::Row);
    EXPECT_TRUE(l.root.children[1].isLeaf());
    EXPECT_EQ(l.root.children[1].tabs.back(), "Views");
    // Moving every tab into the left pane leaves one pane: the root itself.
    for (const std::string& t : std::vector<std::string>(l.root.children[1].tabs))
        ASSERT_TRUE(l.moveTab(t, "Project", DropSide::Centre)) << t;
    EXPECT_TRUE(l.root.isLeaf());
    EXPECT_EQ(l.root.tabs.size(), PaneLayout::panels().size());
    EXPECT_TRUE(holdsEveryPanelOnce(l));
}

TEST(PaneLayout, ReorderAndShow) {
    PaneLayout l;
    EXPECT_TRUE(l.reorderPane({"Scene", "Project", "Sampling", "Network"}));
    EXPECT_EQ(l.root.children[0].tabs.front(), "Scene");
    EXPECT_FALSE(l.reorderPane({"Scene", "Project", "Sampling"})) << "not all of the pane's tabs";
    EXPECT_FALSE(l.reorderPane({"Scene", "Project", "Sampling", "Views"})) << "a tab of another pane";
    EXPECT_TRUE(l.showTab("Cost"));
    EXPECT_EQ(l.paneOf("Cost")->active, "Cost");
    EXPECT_FALSE(l.showTab("Cost"));
}

TEST(PaneLayout, JsonRoundTripKeepsTheTree) {
    PaneLayout l;
    ASSERT_TRUE(l.moveTab("Sampling", "Network", DropSide::Bottom));
    ASSERT_TRUE(l.moveTab("Log", "Views", DropSide::Centre));
    l.root.children[0].fraction = 0.4f;
    ASSERT_TRUE(l.showTab("Cost"));
    const json j = toJson(l);
    EXPECT_EQ(j["root"]["split"], "row");
    EXPECT_EQ(j["root"]["panes"][0]["split"], "column");
    EXPECT_EQ(j["root"]["panes"][0]["panes"][1]["tabs"], json::array({"Sampling"}));
    std::vector<std::string> warnings;
    const PaneLayout back = read(j, warnings);
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    EXPECT_EQ(back, l);
    EXPECT_EQ(back.paneOf("Cost")->active, "Cost");
}

TEST(PaneLayout, OldFormatLoadsAsTheFixedPanes) {
    std::vector<std::string> warnings;
    const PaneLayout l = read(json{{"left", 0.3}, {"bottom", 0.25}}, warnings);
    EXPECT_TRUE(warnings.empty());
    EXPECT_EQ(l.panes().size(), 3u);
    EXPECT_FLOAT_EQ(l.root.fraction, 0.3f);
    EXPECT_FLOAT_EQ(l.root.children[1].fraction, 0.75f);
    EXPECT_EQ(l.panes()[1]->tabs, (std::vector<std::string>{"Views"}));
}

TEST(PaneLayout, DamagedTreeFallsBackWithAWarning) {
    std::vector<std::string> warnings;
    // A split with one pane: structural damage, the default arrangement is used.
    const PaneLayout a = read(json{{"root", {{"split", "row"}, {"panes", json::array({{{"tabs", {"Log"}}}})}}}}, warnings);
    EXPECT_EQ(a, PaneLayout());
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("p.json: /layout/root/panes: expected an array of 2 panes"), std::string::npos)
        << warnings[0];
    EXPECT_NE(warnings[0].find("the default layout is used"), std::string::npos) << warnings[0];

    // Unknown, repeated and missing panels: repaired pane by pane, every panel still reachable.
    warnings.clear();
    const json tree = {{"split", "column"},
                       {"fraction", 3.0},
                       {"panes", json::array({{{"tabs", {"Views", "Bogus", "Log"}}, {"active", "Bogus"}},
                                              {{"tabs", {"Log"}}}})}};
    const PaneLayout b = read(json{{"root", tree}}, warnings);
    EXPECT_TRUE(holdsEveryPanelOnce(b));
    EXPECT_TRUE(b.root.isLeaf()) << "the second pane lost its only (repeated) tab and collapsed";
    EXPECT_EQ(b.root.active, "Views") << "the shown tab is one of the pane's";
    auto has = [&](const std::string& text) {
        return std::any_of(warnings.begin(), warnings.end(), [&](const std::string& w) { return w.find(text) != w.npos; });
    };
    EXPECT_TRUE(has("p.json: /layout/root/fraction: expected a number in [0.08, 0.92]; 0.92 is used"));
    EXPECT_TRUE(has("unknown panel 'Bogus' dropped"));
    EXPECT_TRUE(has("panel 'Log' is in two panes"));
    EXPECT_TRUE(has("panel 'Project' is in no pane"));

    // Nesting beyond the limit (a hostile file) is refused without deep recursion.
    json deep = {{"tabs", {"Log"}}};
    for (int i = 0; i < 40; ++i) deep = {{"split", "row"}, {"panes", json::array({deep, {{"tabs", {"Views"}}}})}};
    warnings.clear();
    EXPECT_EQ(read(json{{"root", deep}}, warnings), PaneLayout());
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("nested deeper than 12 levels"), std::string::npos) << warnings[0];
}

TEST(PaneLayout, FloatingPanelsLeaveThePanesAndDockBack) {
    PaneLayout l;
    ASSERT_TRUE(l.floatTab("Log", 900, 80, 480, 360));
    EXPECT_EQ(l.paneOf("Log"), nullptr);
    ASSERT_NE(l.floatingPanel("Log"), nullptr);
    EXPECT_EQ(l.floatingPanel("Log")->home, "Light region");
    EXPECT_TRUE(holdsEveryPanelOnce(l));
    EXPECT_FALSE(l.floatTab("Log", 0, 0, 10, 10)) << "it floats already";
    ASSERT_TRUE(l.dockTab("Log"));
    EXPECT_EQ(l.paneOf("Log"), l.paneOf("Training"));
    EXPECT_EQ(l.paneOf("Log")->active, "Log");
    EXPECT_TRUE(l.floating.empty());
    EXPECT_FALSE(l.dockTab("Log")) << "it is docked";

    // A pane's only panel floats: the pane collapses; docked by a drag onto another pane's edge.
    ASSERT_TRUE(l.floatTab("Views", 10, 10, 300, 200));
    EXPECT_EQ(l.panes().size(), 2u);
    ASSERT_TRUE(l.moveTab("Views", "Cost", DropSide::Top));
    EXPECT_EQ(l.panes().size(), 3u);
    EXPECT_EQ(l.paneOf("Views")->tabs, (std::vector<std::string>{"Views"}));
    EXPECT_TRUE(holdsEveryPanelOnce(l));

    // The last panel left in the panes stays there.
    PaneLayout m;
    const std::vector<std::string>& all = PaneLayout::panels();
    for (size_t i = 0; i + 1 < all.size(); ++i) ASSERT_TRUE(m.floatTab(all[i], 0, 0, 100, 100)) << all[i];
    EXPECT_FALSE(m.floatTab(all.back(), 0, 0, 100, 100));
    EXPECT_TRUE(holdsEveryPanelOnce(m));
    // Their homes floated away: docking falls back to the first pane.
    ASSERT_TRUE(m.dockTab(all.front()));
    EXPECT_EQ(m.paneOf(all.front()), m.paneOf(all.back()));
}

TEST(PaneLayout, FloatingPanelsSurviveJsonAndDamageIsRepaired) {
    PaneLayout l;
    ASSERT_TRUE(l.floatTab("Objects", 700.5f, 90, 420, 300));
    const json j = toJson(l);
    EXPECT_EQ(j["floating"][0]["rect"], json::array({700.5, 90.0, 420.0, 300.0}));
    std::vector<std::string> warnings;
    EXPECT_EQ(read(j, warnings), l);
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    EXPECT_FALSE(toJson(PaneLayout()).contains("floating")) << "layouts without floating panels are written as before";

    json bad = toJson(PaneLayout());
    bad["floating"] = json::array({{{"tab", "Bogus"}, {"rect", {0, 0, 10, 10}}},
                                   {{"tab", "Log"}, {"rect", {0, 0, 10}}},
                                   {{"tab", "Views"}, {"rect", {0, 0, 10, 10}}}});
    const PaneLayout b = read(bad, warnings);
    EXPECT_TRUE(holdsEveryPanelOnce(b));
    EXPECT_TRUE(b.floating.empty());
    auto has = [&](const std::string& text) {
        return std::any_of(warnings.begin(), warnings.end(), [&](const std::string& w) { return w.find(text) != w.npos; });
    };
    EXPECT_TRUE(has("unknown floating panel 'Bogus' dropped"));
    EXPECT_TRUE(has("p.json: /layout/floating/1/rect: expected [x, y, width, height]"));
    EXPECT_TRUE(has("panel 'Views' floats but is also in a pane"));
}

TEST(PaneLayout, ClampFraction) {
    EXPECT_FLOAT_EQ(PaneLayout::clampFraction(0.5f, 0.3f), 0.5f);
    EXPECT_FLOAT_EQ(PaneLayout::clampFraction(0.f, 0.3f), PaneLayout::kMinFraction);
    EXPECT_FLOAT_EQ(PaneLayout::clampFraction(2.f, 0.3f), PaneLayout::kMaxFraction);
    EXPECT_FLOAT_EQ(PaneLayout::clampFraction(std::numeric_limits<float>::quiet_NaN(), 0.3f), 0.3f);
}

}  // namespace rrf::test::test_pane_layout
