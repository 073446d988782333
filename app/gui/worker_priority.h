#pragma once
/// Background work yields the CPU to the UI thread (issue 14, item 10).
///
/// On the 2-core machines this workbench targets, a render or training job keeps every core busy;
/// at equal priority the UI thread (and Mesa llvmpipe's rasteriser threads, which draw its frames)
/// gets only its share of the CPU among the jobs' threads, and frames stretch. A job's thread and the TBB worker
/// threads of its parallel loops therefore run at a lower scheduling priority (nice +kWorkerNice on
/// Linux): the scheduler gives the UI thread the CPU when it needs it and the jobs everything else,
/// so job throughput is unchanged while the UI is idle. Results do not depend on it (every number
/// comes from a counter-based stream, never from timing). The CLI does not lower anything.

#include <functional>

namespace rrf {

/// Nice value of background threads: +10 weighs a thread about 10× lighter in Linux's CFS.
constexpr int kWorkerNice = 10;

/// Lowers the calling thread's priority to kWorkerNice (no-op where unsupported; never raises it).
/// Returns false if the system refused.
bool lowerCurrentThreadPriority();

/// Runs `work` on the calling thread at background priority: lowers this thread, then runs `work`
/// inside a TBB task arena of its own whose observer lowers every worker thread that joins it.
/// (A task_scheduler_observer sees only its own arena: one created on the UI thread never sees the
/// parallel loops a job thread starts, which run in that thread's implicit arena.) Exceptions from
/// `work` propagate to the caller.
void runAtBackgroundPriority(const std::function<void()>& work);

}  // namespace rrf
