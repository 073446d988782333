// The Views use the space they have (issue 14 item 6): three views in a row when the pane is wide,
// two over two (the figures in the fourth cell) when that shows the image larger; the image keeps
// its aspect inside each view.
#include <gtest/gtest.h>

#include "panels/view_model.h"

namespace rrf::test::test_views_layout {

using namespace rrf::panels;

TEST(ViewsLayout, AWidePaneGetsARowOfThree) {
    // Row: (1200 - 2·8) / 3 = 394.67 wide, 600 - 7.5·17 = 472.5 high → 394.67 shown.
    // Grid: (1200 - 8) / 2 = 596 wide, (600 - 4) / 2 - 17 = 281 high → 281 shown.
    const ViewsLayout l = viewsLayout(ImVec2(1200, 600), ImVec2(8, 4), 17.f, Image(256, 256));
    EXPECT_FALSE(l.grid);
    EXPECT_FLOAT_EQ(l.view.x, 1184.f / 3.f);
    EXPECT_FLOAT_EQ(l.view.y, 1184.f / 3.f);
}

TEST(ViewsLayout, ATallPaneGetsTwoOverTwo) {
    // Row: 784 / 3 = 261.3 shown; grid: 396 wide, 996 / 2 - 17 = 481 high → 396 shown.
    const ViewsLayout l = viewsLayout(ImVec2(800, 1000), ImVec2(8, 4), 17.f, Image(256, 256));
    EXPECT_TRUE(l.grid);
    EXPECT_FLOAT_EQ(l.view.x, 396.f);
    EXPECT_FLOAT_EQ(l.view.y, 396.f);
}

TEST(ViewsLayout, TheImageKeepsItsAspect) {
    // A 2:1 image in the tall pane: row shows 784 / 3 / 2 = 130.7 high, grid 396 / 2 = 198.
    const ViewsLayout l = viewsLayout(ImVec2(800, 1000), ImVec2(8, 4), 17.f, Image(512, 256));
    EXPECT_TRUE(l.grid);
    EXPECT_FLOAT_EQ(l.view.x, 396.f);
    EXPECT_FLOAT_EQ(l.view.y, 198.f);
    // Nothing shown yet: square.
    EXPECT_FLOAT_EQ(viewsLayout(ImVec2(1200, 600), ImVec2(8, 4), 17.f, Image()).view.y, 1184.f / 3.f);
}

}  // namespace rrf::test::test_views_layout
