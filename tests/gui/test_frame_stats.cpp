// Frame-time statistics of the workbench (app/gui/frame_stats.h): nearest-rank median and 95th
// percentile, the overlay's window and the measured stretches of bench/bench_frames.sh.
#include <gtest/gtest.h>

#include "app/gui/frame_stats.h"

namespace rrf::test_frame_stats {

TEST(FrameStats, NearestRankMedianAndPercentile) {
    std::vector<double> t;
    for (int i = 20; i >= 1; --i) t.push_back(i * 0.001);  // 1..20 ms, unsorted
    const FrameTimeSummary s = summarizeFrameTimes(t);
    EXPECT_EQ(s.frames, 20u);
    EXPECT_DOUBLE_EQ(s.median, 0.010) << "rank ceil(0.5 * 20) = 10";
    EXPECT_DOUBLE_EQ(s.p95, 0.019) << "rank ceil(0.95 * 20) = 19";
    EXPECT_DOUBLE_EQ(s.max, 0.020);
    EXPECT_EQ(summarizeFrameTimes({}).frames, 0u);
    EXPECT_DOUBLE_EQ(summarizeFrameTimes({0.004}).p95, 0.004);
}

TEST(FrameStats, WindowKeepsTheLastFramesAndRecordingTakesAStretch) {
    FrameStats f(3);
    f.add(1);
    f.startRecording();
    for (double x : {2.0, 3.0, 4.0, 5.0}) f.add(x);
    EXPECT_EQ(f.recent(), (std::vector<double>{3, 4, 5}));
    EXPECT_DOUBLE_EQ(f.last(), 5);
    EXPECT_EQ(f.takeRecording(), (std::vector<double>{2, 3, 4, 5})) << "every frame since the start, beyond the window";
    EXPECT_FALSE(f.recording());
    f.add(6);
    EXPECT_TRUE(f.takeRecording().empty());
}

TEST(FrameStats, LongestAfterTheFirstFrameOutlivesTheWindow) {
    FrameStats f(2);
    EXPECT_DOUBLE_EQ(f.longestAfterFirst(), 0);
    f.add(9);  // the window's start: not a stall of anything on screen
    EXPECT_DOUBLE_EQ(f.longestAfterFirst(), 0);
    for (double x : {0.5, 2.0, 0.25, 0.5, 0.75}) f.add(x);
    EXPECT_DOUBLE_EQ(f.longestAfterFirst(), 2.0) << "kept after the frame left the window";
}

}  // namespace rrf::test_frame_stats
