// GroundTruthController (ground_truth_controller.h): the progressive ground-truth render job, its
// snapshots, and the restart scene edits ask for.
#include "app/gui/ground_truth_controller.h"

#include <cstdio>
#include <filesystem>

#include "core/eval/stored_ground_truth_file.h"

namespace rrf {

namespace fs = std::filesystem;

GroundTruthController::GroundTruthController(ControllerContext& ctx)
    : ctx_(ctx), state_(ctx.state), job_(ctx.jobs, JobKind::Render, ctx.state.log) {}

bool GroundTruthController::shown() const {
    if (running() || restart_) return false;
    if (!session_) return true;
    uint64_t revision = 0;
    (void)session_->latest(&revision);
    return revision == revision_ && state_.render.running == false;
}

bool GroundTruthController::converged() const {
    return !running() && !restart_ && !state_.groundTruth.empty() && !state_.render.cancelled &&
           state_.render.spp >= state_.render.targetSpp && state_.render.targetSpp > 0;
}

bool GroundTruthController::startStage(StageDone done) {
    // The render the project started on opening (or an edit restarted) is the stage's own.
    if (!running() && !start()) return false;
    done_ = std::move(done);
    return true;
}

double GroundTruthController::progress() const {
    return state_.render.targetSpp > 0 ? double(state_.render.spp) / state_.render.targetSpp : 0.0;
}

void GroundTruthController::cancel() {
    job_.cancel();
    restart_ = false;
}

void GroundTruthController::drop() {
    job_.drop();
    session_.reset();
    done_ = nullptr;
}

void GroundTruthController::restart(bool afterRest) {
    const auto now = std::chrono::steady_clock::now();
    restartAt_ = afterRest ? now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                       std::chrono::duration<double>(kRestartRestSeconds))
                           : now;
    if (running()) {
        job_.cancel();
        restart_ = true;
    } else if (afterRest) {
        restart_ = true;
    } else {
        start();
    }
}

bool GroundTruthController::start() {
    if (!state_.hasProject) {
        state_.log.error("render: no project is open");
        return false;
    }
    const RenderOptions options = renderOptionsFor(state_.project.scene, state_.project.render, kGuiRenderPasses);
    // A saved project keeps its last finished ground truth beside it (restored on reopen); an
    // untitled one has no place for it yet.
    std::optional<RenderSession::Store> store;
    if (ctx_.savedProject())
        store = RenderSession::Store{(fs::path(ctx_.projectDir()) / kGroundTruthDir).string(),
                                     ReferenceKey::of(state_.project.scene, state_.project.scene.lightPosition(),
                                                      options.width, options.height, state_.project.render)};
    auto session = std::make_shared<RenderSession>(state_.project.scene, options, std::move(store));
    char name[64];
    std::snprintf(name, sizeof name, "ground truth %dx%d, %d spp", options.width, options.height, options.spp);
    const bool started = job_.start(name, [session](JobContext& ctx) { session->run(ctx); });
    if (!started) return false;
    // This render is of the scene as it is now: a restart an earlier edit asked for is done by it.
    restart_ = false;
    session_ = session;
    revision_ = 0;
    stamp_ = panels::ImageStamp{state_.project.scene.lightPosition(), state_.project.scene.contentHash(),
                                      options.width, options.height};
    state_.render = panels::RenderProgress{};
    state_.render.running = true;
    state_.render.targetSpp = options.spp;
    state_.log.info(std::string("render started: ") + name);
    return true;
}

void GroundTruthController::poll() {
    job_.poll();
    if (session_) {
        uint64_t revision = 0;
        double noise = 0;
        const auto snap = session_->latest(&revision, &noise);
        if (snap && revision != revision_) {
            revision_ = revision;
            panels::ImageSet& gt = state_.groundTruth;
            gt.direct = snap->direct;
            gt.indirect = snap->indirect;
            gt.global = snap->global;
            // The variances make the noise floors known (Objects, Views); the mask is the one
            // `rrf evaluate` would use for this image. Both were made on the render worker.
            // Below 2 spp the renderer's variance is 0, not known: left empty ("unknown", never 0).
            for (Term t : kTerms) gt.variances[int(t)] = snap->varianceKnown() ? snap->varianceOf(t) : Image();
            gt.footprint = session_->footprint();
            gt.label = session_->loadedFromStore() ? kStoredGroundTruthLabel : "ground truth";
            gt.stamp = stamp_;
            gt.touch();
            state_.render.spp = snap->sppCompleted;
            state_.render.relativeNoise = noise;
            state_.render.seconds = snap->seconds;
            state_.render.samplesPerSecond = snap->seconds > 0 ? double(snap->samples) / snap->seconds : 0.0;
            const double left = double(session_->options().spp - snap->sppCompleted);
            state_.render.etaSeconds = snap->sppCompleted > 0 ? snap->seconds * left / snap->sppCompleted : -1.0;
        }
    }
    const bool wasRunning = state_.render.running;
    state_.render.running = running();
    if (wasRunning && !state_.render.running) {
        state_.render.cancelled = state_.render.spp < state_.render.targetSpp;
        if (session_) {
            bool problem = false;
            const std::string note = session_->storeNote(&problem);
            if (!note.empty() && problem) state_.log.warning(note);
            else if (!note.empty()) state_.log.info(note);
        }
    }
    if (restart_ && !running() && std::chrono::steady_clock::now() >= restartAt_) {
        restart_ = false;
        start();
    }
    // A render replaced by an edit's restart is the same stage still: the pipeline hears of the
    // render that ends with none pending.
    if (done_ && !running() && !restart_) {
        const StageDone done = std::move(done_);
        done_ = nullptr;
        done(!state_.groundTruth.empty() && !state_.render.cancelled && state_.render.spp >= state_.render.targetSpp);
    }
}

}  // namespace rrf
