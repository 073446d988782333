#pragma once
/// A read from disk (or a pure computation over the project) that the UI would otherwise wait for,
/// done on a worker and handed to the UI thread when it is complete (issue 29: no UI-thread stall
/// over 100 ms at start, open, train end or reopen). Used for the picking map, the model sets of
/// the live prediction and the images of a compared or re-opened run.
///
/// A ReadBack is a JobSession of JobKind::ReadBack (which conflicts with no job: it writes nothing)
/// plus what to do with the result, which runs on the UI thread in poll(). Starting a new read
/// forgets the one in flight (its worker is cancelled and whatever it still delivers is dropped):
/// the user asked for something newer, and only the latest request may land. drop() forgets it too
/// (another project was opened). Until the result arrives the UI keeps what it showed (the old
/// picking map, the old models) or nothing.
///
/// The worker never touches ImGui, GL or the workbench state: it returns its result, and onArrived
/// publishes it. UI thread only (except the worker function).

#include <functional>
#include <optional>
#include <string>
#include <utility>

#include "app/gui/job_session.h"

namespace rrf {

template <class Result>
class ReadBack {
public:
    using Work = std::function<std::optional<Result>(JobContext&)>;
    using OnArrived = std::function<void(Result&)>;

    ReadBack(JobRunner& runner, panels::Log& log) : job_(runner, JobKind::ReadBack, log) {}

    /// Starts `work` on a worker; `onArrived` gets its result on the UI thread in a later poll().
    /// A read in flight is dropped first. Returns false (with the reason in the log) only when the
    /// runner refuses, which a ReadBack job never is by kind.
    bool start(const std::string& name, Work work, OnArrived onArrived) {
        drop();
        ++generation_;
        if (!job_.start(name, std::move(work))) return false;
        onArrived_ = std::move(onArrived);
        pending_ = true;
        return true;
    }

    /// UI thread, every frame: hands a finished read's result to its onArrived (once). A read that
    /// failed (threw) or returned nothing ends without a call; its job's failure is logged by the
    /// workbench like any job's.
    void poll() {
        if (!pending_) return;
        const unsigned generation = generation_;
        if (!job_.poll([&](Result& r) {
                // Moved out first: onArrived may start the next read of this session.
                OnArrived arrived = std::move(onArrived_);
                pending_ = false;
                if (arrived) arrived(r);
            }))
            return;
        if (generation_ != generation) return;  // onArrived started another read: it is pending
        pending_ = false;
        onArrived_ = nullptr;
    }

    /// True from start() until the result has been handed over (or the read ended without one).
    bool pending() const { return pending_; }
    /// Forgets the read in flight: its worker is cancelled and its result never arrives.
    void drop() {
        job_.drop();
        onArrived_ = nullptr;
        pending_ = false;
    }

private:
    JobSession<Result> job_;
    OnArrived onArrived_;
    bool pending_ = false;
    unsigned generation_ = 0;  ///< reads started, so poll() sees one started by onArrived
};

}  // namespace rrf
