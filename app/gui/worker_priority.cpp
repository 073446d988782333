#include "app/gui/worker_priority.h"

#include <cerrno>

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

/// TBB calls on_scheduler_entry on each thread that joins the global arena; workers are lowered,
/// a thread that merely calls into TBB (the UI thread, if it ever did) is not.
struct BackgroundWorkerPriority::Observer : tbb::task_scheduler_observer {
    Observer() { observe(true); }
    ~Observer() override { observe(false); }
    void on_scheduler_entry(bool isWorker) override {
        if (isWorker) lowerCurrentThreadPriority();
    }
};

BackgroundWorkerPriority::BackgroundWorkerPriority() : observer_(new Observer) {}
BackgroundWorkerPriority::~BackgroundWorkerPriority() { delete observer_; }

}  // namespace rrf
