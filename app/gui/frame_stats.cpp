#include "app/gui/frame_stats.h"

#include <algorithm>
#include <cmath>

namespace rrf {

FrameTimeSummary summarizeFrameTimes(std::vector<double> seconds) {
    FrameTimeSummary s;
    if (seconds.empty()) return s;
    std::sort(seconds.begin(), seconds.end());
    // Nearest rank: the smallest value with at least p·n values at or below it.
    auto rank = [&](double p) { return seconds[size_t(std::max(1.0, std::ceil(p * double(seconds.size())))) - 1]; };
    s.frames = seconds.size();
    s.median = rank(0.5);
    s.p95 = rank(0.95);
    s.max = seconds.back();
    return s;
}

void FrameStats::add(double seconds) {
    if (frames_++ > 0) longestAfterFirst_ = std::max(longestAfterFirst_, seconds);
    recent_.push_back(seconds);
    if (recent_.size() > window_) recent_.erase(recent_.begin(), recent_.begin() + std::ptrdiff_t(recent_.size() - window_));
    if (recording_) recorded_.push_back(seconds);
}

void FrameStats::startRecording() {
    recorded_.clear();
    recording_ = true;
}

std::vector<double> FrameStats::takeRecording() {
    recording_ = false;
    std::vector<double> r;
    r.swap(recorded_);
    return r;
}

}  // namespace rrf
