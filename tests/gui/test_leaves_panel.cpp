// The Leaves panel and the Views leaf overlay in a bare ImGui context: rows per kd-tree leaf with
// depth, records and error from the model set; the tint changes exactly the pixels that have a leaf.
#include <cmath>

#include "core/nn/network_settings_json.h"
#include "panels/panels.h"
#include "panels/project_io.h"
#include "panels/view_model.h"
#include "tests/gui/imgui_fixture.h"

namespace rrf::test::test_leaves_panel {

using namespace rrf::panels;

namespace {
/// A 3-input network (weights irrelevant here: the panel reads the tree, not the outputs).
NetworkModel net(int object) {
    NetworkModel m;
    m.arch.inputs = 9;
    m.arch.hidden = {1};
    m.params = VecX<double>::Zero(m.arch.numParams());
    m.inputScaler = MinMaxScaler::identity(9);
    m.outputScaler = MinMaxScaler::identity(3);
    m.objectId = object;
    m.target = "indirect";
    return m;
}

/// Object 4: root split on hit_x, its right child split on light_x (3 leaves, depths 1, 2, 2);
/// object 1: a plain network (1 leaf).
ModelSet models() {
    PartitionedNetwork t;
    t.tree.nodes.resize(5);
    t.tree.nodes[0] = {0, 0.f, 1, 2, -1, 300, 0.2};
    t.tree.nodes[1] = {-1, 0.f, -1, -1, 0, 100, 0.04};
    t.tree.nodes[2] = {6, 0.1f, 3, 4, -1, 200, 0.09};
    t.tree.nodes[3] = {-1, 0.f, -1, -1, 1, 120, 0.03};
    t.tree.nodes[4] = {-1, 0.f, -1, -1, 2, 80, NAN};
    for (int l = 0; l < 3; ++l) t.leaves.push_back(net(4));
    ModelSet set;
    ObjectNetworks a;
    a.objectId = 4;
    a.name = "short-box";
    a.byTarget["indirect"] = t;
    ObjectNetworks b;
    b.objectId = 1;
    b.name = "ceiling";
    b.byTarget["indirect"] = net(1);
    set.objects = {a, b};
    return set;
}
}  // namespace

using LeavesPanelTest = ImGuiFixture;

TEST_F(LeavesPanelTest, RowsPerLeafFromTheTrees) {
    const LeavesInfo info = leavesOf(models());
    ASSERT_EQ(info.rows.size(), 4u);
    const int depth[3] = {1, 2, 2};
    const int64_t records[3] = {100, 120, 80};
    for (int l = 0; l < 3; ++l) {
        EXPECT_EQ(info.rows[size_t(l)].objectId, 4);
        EXPECT_EQ(info.rows[size_t(l)].leaf, l);
        EXPECT_EQ(info.rows[size_t(l)].leafCount, 3);
        EXPECT_EQ(info.rows[size_t(l)].depth, depth[l]);
        EXPECT_EQ(info.rows[size_t(l)].records, records[l]);
    }
    EXPECT_EQ(info.rows[0].error, 0.04);
    EXPECT_TRUE(std::isnan(info.rows[2].error));
    EXPECT_EQ(info.rows[3].objectId, 1);
    EXPECT_EQ(info.rows[3].leafCount, 1);
    EXPECT_EQ(info.rows[3].depth, 0);

    WorkbenchState s;
    s.leaves = info;
    for (int i = 0; i < 3; ++i) frame([&] { drawLeavesPanel(leavesPanelView(s)); });
    EXPECT_TRUE(s.requests.empty());
    WorkbenchState empty;
    frame([&] { drawLeavesPanel(leavesPanelView(empty)); });
}

TEST(LeafOverlay, TintsOnlyPixelsWithALeaf) {
    const std::vector<int> ids = {-1, 4, 4, 1}, leaf = {-1, 0, 1, -1};
    std::vector<uint8_t> rgba(16, 100), before = rgba;
    tintByLeaf(ids, leaf, rgba);
    for (int c = 0; c < 4; ++c) {
        EXPECT_EQ(rgba[size_t(c)], before[size_t(c)]);        // background
        EXPECT_EQ(rgba[12 + size_t(c)], before[12 + size_t(c)]);  // object without a leaf
    }
    bool differ = false;  // the two leaves of object 4 take different colours
    for (int c = 0; c < 3; ++c) differ |= rgba[4 + size_t(c)] != rgba[8 + size_t(c)];
    EXPECT_TRUE(differ);
    EXPECT_EQ(rgba[7], 100);  // alpha untouched
    std::vector<uint8_t> wrong(8, 100);
    tintByLeaf(ids, leaf, wrong);  // size mismatch: nothing changes
    EXPECT_EQ(wrong, std::vector<uint8_t>(8, 100));
}

TEST_F(LeavesPanelTest, PartitionEditsAreStoredInTheNetworkSection) {
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, RRF_SOURCE_DIR "/projects/cornell-box/project.json", error)) << error;
    for (int i = 0; i < 2; ++i) frame([&] { drawNetworkPanel(networkPanelView(s)); });
    EXPECT_FALSE(s.dirty) << "drawing the partition controls must not edit the project";

    PartitionSettings p = s.project.networkOrDefault().options.partition;
    EXPECT_FALSE(setPartition(networkPanelView(s), p)) << "no change, nothing stored";
    p.maxLeaves = 7;
    p.goal = 0.02;
    p.axes.light = false;
    ASSERT_TRUE(setPartition(networkPanelView(s), p));
    EXPECT_TRUE(s.dirty);
    const NetworkSettings n = s.project.networkOrDefault();
    EXPECT_EQ(n.options.partition.maxLeaves, 7);
    EXPECT_DOUBLE_EQ(n.options.partition.goal, 0.02);
    EXPECT_FALSE(n.options.partition.axes.light);
    EXPECT_EQ(n.options.targets, TargetMode::Indirect) << "the other network settings are kept";
    // What the project file will say: the section written and read back gives the same partition.
    const nlohmann::json section = toJson(n);
    EXPECT_EQ(section.at("partition").at("max_leaves"), 7);
    EXPECT_EQ(section.at("partition").at("split_axes"), nlohmann::json::array({"position"}));
    frame([&] { drawNetworkPanel(networkPanelView(s)); });
    EXPECT_TRUE(s.requests.empty());
}

}  // namespace rrf::test::test_leaves_panel
