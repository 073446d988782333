#pragma once
/// Frame times of the workbench's UI thread: the work of one frame (events handled, jobs polled,
/// panels drawn, GL rendered and swapped), never the idle wait for events before it. The frame-time
/// overlay (View menu, F3) shows them, and the `measure_frames` script step prints their median and
/// 95th percentile over a labelled stretch (bench/bench_frames.sh: idle, rendering, training,
/// dragging the light).

#include <cstddef>
#include <string>
#include <vector>

namespace rrf {

/// Median and 95th percentile of a set of frame times (seconds), by the nearest-rank rule.
struct FrameTimeSummary {
    size_t frames = 0;
    double median = 0, p95 = 0, max = 0;
};
/// The summary of `seconds` (empty: all zero).
FrameTimeSummary summarizeFrameTimes(std::vector<double> seconds);

class FrameStats {
public:
    /// The last `window` frames are kept for the overlay.
    explicit FrameStats(size_t window = 240) : window_(window) {}
    /// Adds one frame's work time (seconds).
    void add(double seconds);
    /// The frames kept (oldest first).
    const std::vector<double>& recent() const { return recent_; }
    double last() const { return recent_.empty() ? 0.0 : recent_.back(); }
    /// The longest frame since the first (seconds; 0 before a second frame). The first frame is
    /// drawn before the window is shown (Window::swap): nothing on screen waits for it.
    double longestAfterFirst() const { return longestAfterFirst_; }
    /// Starts collecting every frame (not only the window) until takeRecording().
    void startRecording();
    bool recording() const { return recording_; }
    /// The frames since startRecording(); stops recording.
    std::vector<double> takeRecording();

private:
    size_t window_;
    std::vector<double> recent_;
    size_t frames_ = 0;
    double longestAfterFirst_ = 0.0;
    bool recording_ = false;
    std::vector<double> recorded_;
};

}  // namespace rrf
