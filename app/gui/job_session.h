#pragma once
/// One kind of background job as the workbench's UI thread drives it (render, generate, train,
/// evaluate, predict, sweep). A session starts a worker function on the JobRunner, refuses with a
/// logged reason while a conflicting job runs, forwards the worker's log lines every frame, and hands
/// the worker's result to the UI thread exactly once, after the job has ended. drop() forgets the
/// job (a project was closed): it is cancelled and whatever it still produces never arrives.
/// Cancelling sets the flag the worker polls (and fires its onCancel hook, e.g. Renderer::cancel), so
/// a worker that checks it at least once a second stops within a second.
///
/// The worker gets the runner's JobContext (progress, status, post() for log lines, cancelled())
/// and returns std::optional<Result>: nothing when it was cancelled or had nothing to deliver
/// (JobSession<void>: a worker that returns nothing). It
/// never touches ImGui, GL or the workbench state; what the UI shows while it runs (render
/// snapshots, loss curves) it publishes through its own shared object, which the UI thread copies.

#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include "app/gui/job_runner.h"
#include "panels/log.h"

namespace rrf {

/// The part of a session that does not depend on the result type.
class JobSessionBase {
public:
    JobSessionBase(JobRunner& runner, JobKind kind, panels::Log& log) : runner_(runner), kind_(kind), log_(log) {}
    virtual ~JobSessionBase() = default;
    JobSessionBase(const JobSessionBase&) = delete;
    JobSessionBase& operator=(const JobSessionBase&) = delete;

    /// True while this session's job runs.
    bool running() const { return id_ != 0 && runner_.running(id_); }
    /// Fraction done of the running job (0 when none runs).
    double progress() const;
    /// Asks the running job to stop; it stops at its next check of JobContext::cancelled().
    void cancel();
    /// Cancels the job and forgets what it still produces: its messages and result are discarded.
    /// running() stays true until the cancelled worker has returned.
    void drop();

protected:
    /// Starts `work`. A refusal goes to `why` when given, else to the log as an error.
    bool launch(const std::string& name, std::function<void(JobContext&)> work, std::string* why);
    /// Moves the job's posted lines into the log ("<kind>: <line>").
    void forwardMessages();
    /// Drops the typed result slot (drop()).
    virtual void forgetResult() = 0;

    JobRunner& runner_;
    const JobKind kind_;
    panels::Log& log_;
    int id_ = 0;
    std::shared_ptr<JobContext> context_;  ///< the current job's, kept for its messages
};

template <class Result>
class JobSession : public JobSessionBase {
public:
    using Work = std::function<std::optional<Result>(JobContext&)>;
    using JobSessionBase::JobSessionBase;

    /// Starts `work` on a worker thread (see launch() for refusals). A previous job's undelivered
    /// result is discarded: the new job replaces it.
    bool start(const std::string& name, Work work, std::string* why = nullptr) {
        auto slot = std::make_shared<Slot>();
        const bool started = launch(name, [slot, work = std::move(work)](JobContext& ctx) {
            std::optional<Result> result = work(ctx);
            std::lock_guard<std::mutex> lock(slot->mutex);
            slot->result = std::move(result);
        }, why);
        if (started) slot_ = std::move(slot);
        return started;
    }

    /// UI thread, every frame: forwards log lines; once the job has ended, calls `onResult` with its
    /// result (if it delivered one: not when it failed, was cancelled without one, or was dropped).
    /// Each result is delivered once. Returns true when no job is in flight after the call: a caller
    /// that must act once the job has ended asks this, not running() again, since the job may end
    /// between the two reads with its result still waiting for the next frame.
    template <class OnResult>
    bool poll(OnResult&& onResult) {
        forwardMessages();
        if (running()) return false;
        if (!slot_) return true;
        std::optional<Result> result;
        {
            std::lock_guard<std::mutex> lock(slot_->mutex);
            result = std::move(slot_->result);
        }
        slot_.reset();
        if (result) onResult(*result);
        return true;
    }

private:
    /// Shared with the worker, which writes the result as its last act.
    struct Slot {
        std::mutex mutex;
        std::optional<Result> result;
    };
    void forgetResult() override { slot_.reset(); }

    std::shared_ptr<Slot> slot_;
};

/// A job whose output is published while it runs (the ground-truth render's snapshots), so nothing
/// is handed over when it ends: the worker returns nothing and poll() only forwards its log lines.
template <>
class JobSession<void> : public JobSessionBase {
public:
    using Work = std::function<void(JobContext&)>;
    using JobSessionBase::JobSessionBase;

    /// Starts `work` on a worker thread (see launch() for refusals).
    bool start(const std::string& name, Work work, std::string* why = nullptr) { return launch(name, std::move(work), why); }
    /// UI thread, every frame: forwards the job's log lines.
    void poll() { forwardMessages(); }

private:
    void forgetResult() override {}
};

}  // namespace rrf
