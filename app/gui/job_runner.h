#pragma once
/// Background jobs of the workbench (render, generate, train, evaluate, predict, sweep), each on its
/// own worker thread. A job reports progress, ETA, a status line and log lines through its
/// JobContext; the UI thread polls JobRunner::jobs() every frame and logs finished jobs via
/// takeFinished(). Workers never touch ImGui or GL: what they produce they publish as snapshots that
/// the UI thread copies. The workbench drives each kind of job through a JobSession (job_session.h).
///
/// Starting a job whose kind conflicts with a running one is refused (with the reason), never
/// queued silently: the user decides what to stop.

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/pipeline/stage_observer.h"

namespace rrf {

/// Predict: the CPU fallback of the live prediction; Sweep: a cost-of-accuracy series (core/pipeline/sweep.h).
/// Compare: two runs' models predicted (and judged) side by side; it loads its own models and copies
/// the ground truth, so it conflicts only with another comparison. Overlay: the Views' leaf overlay
/// (a leaf lookup per pixel of the loaded models), reading shared models only.
/// ReadBack: a project's stored results read back when it opens (its sweeps): it writes nothing and
/// conflicts with no job, not even the read-back of the project opened before it (dropped).
enum class JobKind { Render, Generate, Train, Evaluate, Predict, Sweep, Compare, Overlay, LightGrid, Spread, ReadBack };
const char* jobKindName(JobKind kind);
/// True when jobs of kinds a and b must not run at the same time (one needs what the other makes,
/// or both write the same outputs).
bool jobsConflict(JobKind a, JobKind b);

/// Handed to the job's function on its worker thread. All members are thread-safe.
class JobContext {
public:
    /// Fraction done in [0, 1]; the ETA is extrapolated from it.
    void setProgress(double fraction);
    void setStatus(const std::string& status);
    bool cancelled() const { return cancel_.load(std::memory_order_relaxed); }
    const std::atomic<bool>& cancelFlag() const { return cancel_; }
    /// Called (on the UI thread) when the job is cancelled, e.g. to forward to Renderer::cancel().
    void onCancel(std::function<void()> hook);
    /// A line for the workbench log (worker side); the UI thread collects them with takeMessages().
    void post(const std::string& line);
    /// The lines posted since the last call, oldest first.
    std::vector<std::string> takeMessages();
    /// An observer for a core/pipeline stage run by this job: its cancel flag, progress, status and
    /// notes are this context's (the caller may add the epoch callback).
    StageObserver stageObserver();

private:
    friend class JobRunner;
    mutable std::mutex mutex_;
    std::atomic<bool> cancel_{false};
    double progress_ = 0.0;
    std::string status_;
    std::string error_;  ///< set by the runner when the job's function threw
    std::function<void()> cancelHook_;
    std::vector<std::string> messages_;
};

/// A copy of one job's state for display.
struct JobInfo {
    int id = 0;
    JobKind kind = JobKind::Render;
    std::string name, status;
    double progress = 0.0;
    double seconds = 0.0;
    double etaSeconds = -1.0;  ///< -1 while unknown
    bool running = true, cancelled = false, failed = false;
    std::string error;         ///< what the job threw, if it failed
};

class JobRunner {
public:
    JobRunner() = default;
    /// Cancels every job and joins the workers.
    ~JobRunner();
    JobRunner(const JobRunner&) = delete;
    JobRunner& operator=(const JobRunner&) = delete;

    /// Starts `work` on a new thread. Returns the job id, or 0 when refused because a conflicting
    /// job is running (`why` then says which). Exceptions thrown by `work` mark the job failed.
    int start(JobKind kind, const std::string& name, std::function<void(JobContext&)> work, std::string* why = nullptr);
    /// Asks a job to stop (its function sees cancelled() and returns at its next check).
    void cancel(int id);
    void cancelAll();
    /// Running jobs, oldest first.
    std::vector<JobInfo> jobs() const;
    /// True while job `id` runs (false for 0, finished or unknown ids).
    bool running(int id) const;
    /// The state of job `id` while it runs (null otherwise).
    std::optional<JobInfo> info(int id) const;
    /// The context of job `id` (null for an unknown id); it outlives the job for whoever holds it.
    std::shared_ptr<JobContext> context(int id) const;
    bool idle() const;
    /// True when no job runs and every ended job has been taken (takeFinished), so its result has
    /// been handed to the UI in the same frame: what a script waits for between steps (a job that
    /// ends after the frame's polls is idle() but its result is still on its way).
    bool drained() const;
    /// Jobs that finished since the last call (each reported once), joined.
    std::vector<JobInfo> takeFinished();
    /// Blocks until every job has finished (used on exit after cancelAll()).
    void waitAll();

private:
    struct Entry {
        JobInfo info;
        std::shared_ptr<JobContext> context;
        std::chrono::steady_clock::time_point start;
        std::atomic<bool> done{false};
        std::thread thread;
    };
    JobInfo snapshot(const Entry& e) const;

    mutable std::mutex mutex_;
    std::vector<std::unique_ptr<Entry>> entries_;
    int nextId_ = 1;
};

}  // namespace rrf
