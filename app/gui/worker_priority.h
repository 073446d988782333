#pragma once
/// Background work yields the CPU to the UI thread (issue 14, item 10).
///
/// On the 2-core machines this workbench targets, a render or training job keeps every core busy;
/// at equal priority the UI thread (and Mesa llvmpipe's rasteriser threads, which draw its frames)
/// gets about a third of the CPU, and frames stretch to 100 ms. Job threads and TBB's worker threads
/// therefore run at a lower scheduling priority (nice +kWorkerNice on Linux): the scheduler gives
/// the UI thread the CPU when it needs it and the jobs everything else, so job throughput is
/// unchanged while the UI is idle. Results do not depend on it (every number comes from a
/// counter-based stream, never from timing). The CLI does not lower anything.

namespace rrf {

/// Nice value added to background threads: +10 weighs a thread about 10× lighter in Linux's CFS.
constexpr int kWorkerNice = 10;

/// Lowers the calling thread's priority to kWorkerNice (no-op where unsupported; never raises it).
/// Returns false if the system refused.
bool lowerCurrentThreadPriority();

/// While alive, every TBB worker thread that joins the scheduler lowers its own priority (the
/// threads that run the jobs' parallel loops). Create one in the workbench's main().
class BackgroundWorkerPriority {
public:
    BackgroundWorkerPriority();
    ~BackgroundWorkerPriority();
    BackgroundWorkerPriority(const BackgroundWorkerPriority&) = delete;
    BackgroundWorkerPriority& operator=(const BackgroundWorkerPriority&) = delete;

private:
    struct Observer;
    Observer* observer_;
};

}  // namespace rrf
