#pragma once
/// The ground truth as a controller: the progressive path-traced render of the current scene and
/// light (a RenderSession on a Render job), the stamp of what its images are of, and the restart a
/// scene edit asks for once the old render has stopped. It publishes state.groundTruth (the
/// snapshots, with their variances and footprint mask) and state.render (panels::RenderProgress).
/// UI thread only.

#include <chrono>
#include <cstdint>
#include <memory>

#include "app/gui/controller_context.h"
#include "app/gui/job_session.h"
#include "app/gui/prediction_draft.h"
#include "app/gui/render_session.h"

namespace rrf {

/// Seconds without a material or light edit after which the ground truth restarts: the rest after
/// which the prediction's draft gives way to the full frame (prediction_draft.h), so both settle together.
inline constexpr double kRestartRestSeconds = kDraftRestSeconds;

class GroundTruthController {
public:
    explicit GroundTruthController(ControllerContext& ctx);

    /// Starts the render of the current scene (refused while one runs). A saved project keeps the
    /// finished image in its store (restored on reopen).
    bool start();
    /// The pipeline's render stage: joins the running render or starts one; `done` is told once
    /// when the render ended with no restart pending (delivered: it reached its target).
    bool startStage(StageDone done);
    bool running() const { return job_.running(); }
    /// The render has ended and its last snapshot is what the views show (a render that ends after
    /// this frame's poll is not running but not shown yet).
    bool shown() const;
    /// The current ground truth is of the current scene and converged (the pipeline keeps it).
    bool converged() const;
    /// Fraction of the target samples per pixel done.
    double progress() const;
    /// Asks the running render (if any) to stop; it stops at its next pass boundary.
    void cancel();
    /// The scene changed: the old render no longer matches it, so it is stopped and a new one starts
    /// once it has stopped (now, when none runs). A replacement the user asked for by editing, not a
    /// queued conflicting job. `afterRest`: an edit of materials or the light, which come many to a
    /// drag: the new render starts once no such edit came for kRestartRestSeconds, so a drag does
    /// not start (and stop) a render with its BVH build every frame beside the UI's own work.
    void restart(bool afterRest = false);
    /// A restart waits for the old render to stop, or for the edits to rest.
    bool restartPending() const { return restart_; }
    /// Each frame: publishes the newest snapshot, notes how the render ended, carries out a restart.
    void poll();
    /// Forgets the render (a project was closed): nothing it still produces arrives.
    void drop();
    /// The current render (its images, options and outputs); null before the first.
    const std::shared_ptr<RenderSession>& session() const { return session_; }

private:
    ControllerContext& ctx_;
    panels::WorkbenchState& state_;  ///< ctx_.state: what the controller publishes into
    std::shared_ptr<RenderSession> session_;
    JobSession<void> job_;
    uint64_t revision_ = 0;       ///< the snapshot revision last published
    panels::ImageStamp stamp_;    ///< what the current render's images are of (light, scene, size)
    bool restart_ = false;        ///< a scene edit asked for a new render, not started yet
    std::chrono::steady_clock::time_point restartAt_{};  ///< not before: the edits' rest
    StageDone done_;              ///< the pipeline's, while its render stage runs
};

}  // namespace rrf
