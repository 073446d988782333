#include "app/gui/render_session.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "core/eval/reference_noise.h"
#include "core/eval/stored_ground_truth_file.h"
#include "core/predict/gbuffer.h"

namespace rrf {

RenderSession::RenderSession(const Scene& scene, const RenderOptions& options, std::optional<Store> store)
    : scene_(scene), options_(options), store_(std::move(store)) {}

std::string RenderSession::storeNote(bool* problem) const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (problem) *problem = storeNoteIsProblem_;
    return storeNote_;
}

void RenderSession::run(JobContext& ctx) {
    ctx.setStatus("building BVH");
    auto accel = std::make_unique<Accel>(scene_);
    Renderer* renderer = nullptr;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        accel_ = std::move(accel);
        renderer_ = std::make_shared<Renderer>(scene_, *accel_, options_);
        renderer = renderer_.get();
    }
    // Installed after the renderer exists; onCancel() fires at once if cancel came during the build.
    // The hook owns a reference: JobRunner may call it after this session is destroyed (a finished
    // job not yet taken), and cancel() touches only the renderer's own flag.
    ctx.onCancel([keep = std::shared_ptr<Renderer>(renderer_)] { keep->cancel(); });
    if (ctx.cancelled()) return;
    ctx.setStatus("footprint mask");
    {
        // The G-buffer evaluate() builds for this image (one primary ray per pixel, with the scene's
        // own light position), so the views, the render status and `rrf evaluate` use one mask.
        const PathTracer tracer(scene_, *accel_, Estimator::NEE, 1);
        auto mask = std::make_shared<const FootprintMask>(footprintMask(
            buildGBuffer(tracer, RecordLayout::forScene(scene_), scene_.lightPosition(), options_.width, options_.height)));
        std::lock_guard<std::mutex> lock(mutex_);
        footprint_ = std::move(mask);
    }
    if (store_) {
        ctx.setStatus("looking for the stored ground truth");
        StoredGroundTruth stored = loadGroundTruth(store_->dir, store_->key, options_.spp);
        if (stored.snapshot) {
            {
                std::lock_guard<std::mutex> lock(mutex_);
                loadedStats_ = stored.stats;
                storeNote_ = "ground truth loaded from " + store_->dir + " (the same scene, light, size and spp)";
            }
            loaded_ = true;  // before the snapshot appears: whoever sees it sees where it came from
            publish(std::make_shared<const RenderSnapshot>(std::move(*stored.snapshot)));
            ctx.setProgress(1.0);
            ctx.setStatus("loaded");
            return;
        }
        if (!stored.why.empty()) {
            std::lock_guard<std::mutex> lock(mutex_);
            storeNote_ = "rendering the ground truth: " + stored.why;
            storeNoteIsProblem_ = stored.why.find("cannot be read") != std::string::npos;
        }
    }
    ctx.setStatus("rendering");
    renderer->run([&](int sppDone) {
        publish();
        ctx.setProgress(renderer->progress());
        char status[96];
        std::snprintf(status, sizeof status, "%d/%d spp", sppDone, options_.spp);
        ctx.setStatus(status);
    });
    if (store_ && !renderer->cancelled()) {
        ctx.setStatus("storing");
        std::string note;
        bool noteIsProblem = false;
        try {
            storeGroundTruth(store_->dir, store_->key, renderer_->snapshot(), renderer_->stats());
            note = "ground truth stored in " + store_->dir + " (shown at once when the project is opened again)";
        } catch (const std::exception& e) {
            note = std::string("the ground truth could not be stored: ") + e.what();
            noteIsProblem = true;
        }
        std::lock_guard<std::mutex> lock(mutex_);
        storeNote_ = note;
        storeNoteIsProblem_ = noteIsProblem;
    }
    ctx.setStatus(renderer->cancelled() ? "cancelled" : "done");
}

void RenderSession::publish() {
    // Called on the worker between passes, when the renderer's own lock is free: the snapshot is a
    // consistent copy, and the UI thread never waits for a pass to finish.
    publish(std::make_shared<const RenderSnapshot>(renderer_->snapshot()));
}

void RenderSession::publish(std::shared_ptr<const RenderSnapshot> snap) {
    // The noise is a pass over every pixel: done here, on the worker, once per pass. Below 2 spp the
    // renderer's variance is 0 (not estimable), which must not read as "no noise".
    const double noise = footprint_ && snap->varianceKnown() ? relativeNoiseFloor(snap->global, snap->variance, footprint_->kept)
                                    : std::numeric_limits<double>::quiet_NaN();
    std::lock_guard<std::mutex> lock(mutex_);
    latest_ = std::move(snap);
    latestNoise_ = noise;
    ++revision_;
}

std::shared_ptr<const RenderSnapshot> RenderSession::latest(uint64_t* revision, double* relativeNoise) const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (revision) *revision = revision_.load();
    if (relativeNoise) *relativeNoise = latestNoise_;
    return latest_;
}

std::shared_ptr<const FootprintMask> RenderSession::footprint() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return footprint_;
}

RenderStats RenderSession::stats() const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (loaded_) return loadedStats_;
    return renderer_ ? renderer_->stats() : RenderStats{};
}

RenderOutputs RenderSession::write(const std::string& dir, ImageFormat format, float exposure,
                                   const std::vector<std::pair<ImageFormat, float>>& moreFormats) const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!renderer_ || !latest_) throw std::runtime_error(dir + ": nothing rendered yet");
    return writeRenderOutputs(dir, scene_, *renderer_, *latest_, format, exposure, moreFormats,
                              loaded_ ? &loadedStats_ : nullptr);
}

}  // namespace rrf
