#include "app/gui/worker_priority.h"

#include <cerrno>

#include <tbb/task_arena.h>
#include <tbb/task_scheduler_observer.h>

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace rrf {

bool lowerCurrentThreadPriority() {
#if defined(__linux__)
    // On Linux the nice value is per thread (setpriority on a thread id); a thread may always
    // lower its own priority. Never raise it: a thread already nicer than this stays so.
    const id_t tid = id_t(syscall(SYS_gettid));
    errno = 0;
    const int current = getpriority(PRIO_PROCESS, tid);
    if (errno != 0) return false;
    if (current >= kWorkerNice) return true;
    return setpriority(PRIO_PROCESS, tid, kWorkerNice) == 0;
#else
    return false;
#endif
}

namespace {
/// Lowers each thread as it enters the observed arena (workers and the job thread alike). A worker
/// stays lowered afterwards: the UI thread itself never runs parallel loops (workbench rule), so
/// the only cost is that a lowered worker also serves other jobs' loops at the same low priority.
struct LowerOnEntry : tbb::task_scheduler_observer {
    explicit LowerOnEntry(tbb::task_arena& arena) : tbb::task_scheduler_observer(arena) { observe(true); }
    ~LowerOnEntry() override { observe(false); }
    void on_scheduler_entry(bool) override { lowerCurrentThreadPriority(); }
};
}  // namespace

void runAtBackgroundPriority(const std::function<void()>& work) {
    lowerCurrentThreadPriority();
    tbb::task_arena arena;
    arena.initialize();
    LowerOnEntry observer(arena);
    arena.execute(work);
}

}  // namespace rrf
