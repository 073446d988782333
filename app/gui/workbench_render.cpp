// Workbench: the progressive ground-truth render job, its snapshots, and scene edits that restart it.
#include "app/gui/workbench.h"

#include <cstdio>
#include <filesystem>

#include "core/eval/stored_ground_truth.h"
#include "core/scene/camera_rays.h"

namespace rrf {

namespace fs = std::filesystem;

bool Workbench::renderRunning() const { return renderJob_.running(); }

bool Workbench::renderShown() const {
    if (renderRunning()) return false;
    if (!render_) return true;
    uint64_t revision = 0;
    (void)render_->latest(&revision);
    return revision == renderRevision_ && state_.render.running == false;
}

bool Workbench::groundTruthConverged() const {
    return !renderRunning() && !state_.groundTruth.empty() && !state_.render.cancelled &&
           state_.render.spp >= state_.render.targetSpp && state_.render.targetSpp > 0;
}

bool Workbench::startRenderStage(StageDone done) {
    // The render the project started on opening (or an edit restarted) is the stage's own.
    if (!renderRunning() && !startRender()) return false;
    renderDone_ = std::move(done);
    return true;
}

void Workbench::cancelRender() {
    renderJob_.cancel();
    restartRender_ = false;
}

bool Workbench::startRender() {
    if (!state_.hasProject) {
        state_.log.error("render: no project is open");
        return false;
    }
    const RenderOptions options = renderOptionsFor(state_.project.scene, state_.project.render, kGuiRenderPasses);
    // A saved project keeps its last finished ground truth beside it (restored on reopen); an
    // untitled one has no place for it yet.
    std::optional<RenderSession::Store> store;
    if (!ctx_.untitled && !state_.project.path.empty())
        store = RenderSession::Store{(fs::path(projectDir()) / kGroundTruthDir).string(),
                                     ReferenceKey::of(state_.project.scene, state_.project.scene.lightPosition(),
                                                      options.width, options.height, state_.project.render)};
    auto session = std::make_shared<RenderSession>(state_.project.scene, options, std::move(store));
    char name[64];
    std::snprintf(name, sizeof name, "ground truth %dx%d, %d spp", options.width, options.height, options.spp);
    const bool started = renderJob_.start(name, [session](JobContext& ctx) { session->run(ctx); });
    if (!started) return false;
    render_ = session;
    renderRevision_ = 0;
    renderStamp_ = panels::ImageStamp{state_.project.scene.lightPosition(), state_.project.scene.contentHash(),
                                      options.width, options.height};
    state_.render = panels::RenderProgress{};
    state_.render.running = true;
    state_.render.targetSpp = options.spp;
    state_.log.info(std::string("render started: ") + name);
    return true;
}

void Workbench::pollRender() {
    renderJob_.poll();
    if (render_) {
        uint64_t revision = 0;
        double noise = 0;
        const auto snap = render_->latest(&revision, &noise);
        if (snap && revision != renderRevision_) {
            renderRevision_ = revision;
            panels::ImageSet& gt = state_.groundTruth;
            gt.direct = snap->direct;
            gt.indirect = snap->indirect;
            gt.global = snap->global;
            // The variances make the noise floors known (Objects, Views); the mask is the one
            // `rrf evaluate` would use for this image. Both were made on the render worker.
            // Below 2 spp the renderer's variance is 0, not known: left empty ("unknown", never 0).
            for (Term t : kTerms) gt.variances[int(t)] = snap->varianceKnown() ? snap->varianceOf(t) : Image();
            gt.footprint = render_->footprint();
            gt.label = render_->loadedFromStore() ? kStoredGroundTruthLabel : "ground truth";
            gt.stamp = renderStamp_;
            gt.touch();
            state_.render.spp = snap->sppCompleted;
            state_.render.relativeNoise = noise;
            state_.render.seconds = snap->seconds;
            state_.render.samplesPerSecond = snap->seconds > 0 ? double(snap->samples) / snap->seconds : 0.0;
            const double left = double(render_->options().spp - snap->sppCompleted);
            state_.render.etaSeconds = snap->sppCompleted > 0 ? snap->seconds * left / snap->sppCompleted : -1.0;
        }
    }
    const bool wasRunning = state_.render.running;
    state_.render.running = renderRunning();
    if (wasRunning && !state_.render.running) {
        state_.render.cancelled = state_.render.spp < state_.render.targetSpp;
        if (render_) {
            bool problem = false;
            const std::string note = render_->storeNote(&problem);
            if (!note.empty() && problem) state_.log.warning(note);
            else if (!note.empty()) state_.log.info(note);
        }
    }
    if (restartRender_ && !renderRunning()) {
        restartRender_ = false;
        startRender();
    }
    // A render replaced by an edit's restart is the same stage still: the pipeline hears of the
    // render that ends with none pending.
    if (renderDone_ && !renderRunning() && !restartRender_) {
        const StageDone done = std::move(renderDone_);
        renderDone_ = nullptr;
        done(!state_.groundTruth.empty() && !state_.render.cancelled && state_.render.spp >= state_.render.targetSpp);
    }
}

void Workbench::sceneChanged(bool restartRender, bool geometryChanged) {
    // Rebuilding traces a BVH and one ray per pixel on the UI thread; a drag must not pay that per frame.
    const RenderOptions o = renderOptionsFor(state_.project.scene, state_.project.render, kGuiRenderPasses);
    if (geometryChanged || !state_.pickAccel || o.width != state_.idWidth || o.height != state_.idHeight)
        rebuildPicking();
    // The prediction follows the light at once (GLSL: this frame); the ground truth restarts below.
    prediction_.refresh();
    if (!restartRender) return;
    // The old render no longer matches the scene: stop it and start again once it has stopped.
    // This is a replacement the user asked for by editing, not a queued conflicting job.
    if (renderRunning()) {
        renderJob_.cancel();
        restartRender_ = true;
    } else {
        startRender();
    }
}

void Workbench::rebuildPicking() {
    state_.pickAccel.reset();
    state_.objectIds.clear();
    state_.idWidth = state_.idHeight = 0;
    if (!state_.hasProject) return;
    try {
        auto accel = std::make_shared<Accel>(state_.project.scene);
        // The object-id buffer for highlighting: one primary ray per pixel centre. For the
        // scenes this tool targets (≤ 1024² pixels) this takes milliseconds.
        const RenderOptions o = renderOptionsFor(state_.project.scene, state_.project.render, kGuiRenderPasses);
        CameraRays camera(state_.project.scene.camera, o.width, o.height);
        state_.objectIds.assign(size_t(o.width) * size_t(o.height), -1);
        for (int y = 0; y < o.height; ++y)
            for (int x = 0; x < o.width; ++x) {
                Hit hit;
                if (accel->intersect(camera.generate(x, y, 0.5f, 0.5f), hit))
                    state_.objectIds[size_t(y) * size_t(o.width) + size_t(x)] = hit.object;
            }
        state_.idWidth = o.width;
        state_.idHeight = o.height;
        state_.pickAccel = std::move(accel);
    } catch (const std::exception& e) {
        state_.log.error(std::string("building the picking BVH failed: ") + e.what());
    }
}

}  // namespace rrf
