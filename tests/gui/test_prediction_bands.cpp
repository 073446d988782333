// Full-quality GLSL frames in bands (app/gui/prediction_bands.h, issue 29): a frame of unknown cost
// starts with a small band, never the whole frame; bands shrink when one took longer than the
// budget and grow (at most doubling) when well below it, so a slow driver spreads a frame over many
// UI frames and a fast one converges to whole frames in a few.
#include <gtest/gtest.h>

#include "app/gui/prediction_bands.h"

namespace rrf::test::test_prediction_bands {

TEST(PredictionBands, FirstBandOfUnknownCostIsASmallShare) {
    EXPECT_EQ(firstBandRows(256, 0.0), 256 / kFirstBandDivisor);
    EXPECT_EQ(firstBandRows(8, 0.0), 1);
    // Known cost: what fits 80 % of the budget, within 1 … height.
    EXPECT_EQ(firstBandRows(256, kBandBudgetSeconds / 10), 8);
    EXPECT_EQ(firstBandRows(256, 10.0), 1);
    EXPECT_EQ(firstBandRows(256, 1e-9), 256);
}

TEST(PredictionBands, BandsFollowTheBudget) {
    // 11 s for a 256-row frame (llvmpipe, 40-10 networks): a row costs 43 ms, one row per band.
    const double perRow = 11.0 / 256;
    int rows = firstBandRows(256, 0.0);
    for (int i = 0; i < 8; ++i) rows = nextBandRows(rows, rows * perRow, 256);
    EXPECT_EQ(rows, 1);
    // A GPU (a row in 10 µs): doubling from one row, the whole frame within 9 bands.
    rows = 1;
    int bands = 0;
    while (rows < 256 && bands < 20) rows = nextBandRows(rows, rows * 1e-5, 256), ++bands;
    EXPECT_EQ(rows, 256);
    EXPECT_LE(bands, 9);
    // A band over the budget shrinks the next in proportion.
    EXPECT_EQ(nextBandRows(32, 4 * kBandBudgetSeconds, 256), int(32 * 0.8 / 4));
    // Unknown time (a timer that gave nothing) grows carefully, never beyond the frame.
    EXPECT_EQ(nextBandRows(200, 0.0, 256), 256);
}

}  // namespace rrf::test::test_prediction_bands
