#pragma once
/// One progressive ground-truth render running as a background job. The session owns a private copy
/// of the scene, its Embree BVH and the Renderer (built on the worker, so a large scene's BVH build
/// never stalls the UI); after every pass the worker publishes a RenderSnapshot, which the UI thread
/// picks up with latest(). A scene edit makes a new session: the old one is cancelled, never mutated.
///
/// Before the first pass the worker also builds the footprint mask of the image (its G-buffer at the
/// session's light position and size, core/predict/footprint_mask.h): the pixels every error against
/// this ground truth is measured over, as `rrf evaluate` does. With each snapshot it publishes the
/// image's relative noise over that mask (relativeNoiseFloor of the global term,
/// core/eval/reference_noise.h), so the UI thread does no per-pixel work for the render status.
///
/// With a store (the project's ground_truth directory, core/eval/stored_ground_truth_file.h) the worker
/// first looks there: a stored render of the same key and spp is published as the one snapshot
/// instead of rendering (the same pixels, by determinism), and a render that finishes is stored.

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "app/gui/job_runner.h"
#include "core/eval/reference_store.h"
#include "core/predict/footprint_mask.h"
#include "core/scene/accel.h"
#include "core/render/render_outputs.h"
#include "core/render/renderer.h"
#include "core/scene/scene.h"

namespace rrf {

class RenderSession {
public:
    /// Where a finished render is kept and looked for, and under which key.
    struct Store {
        std::string dir;
        ReferenceKey key;
    };
    RenderSession(const Scene& scene, const RenderOptions& options, std::optional<Store> store = std::nullopt);

    /// The job body: builds the BVH and renders until done or cancelled.
    void run(JobContext& context);

    /// The most recent snapshot (null before the first pass), its sequence number and its relative
    /// noise (NaN while unknown).
    std::shared_ptr<const RenderSnapshot> latest(uint64_t* revision = nullptr, double* relativeNoise = nullptr) const;
    /// The footprint mask of the image (null until the worker has built it, before the first pass).
    std::shared_ptr<const FootprintMask> footprint() const;
    RenderStats stats() const;
    const RenderOptions& options() const { return options_; }
    /// After the job: whether the images came from the store, and a line for the log about the
    /// store (loaded from, stored in, why a stored one was not used, a failed write); empty if none.
    bool loadedFromStore() const { return loaded_.load(); }
    /// `problem` (optional): whether the note reports a failure (a write that failed, a damaged set).
    std::string storeNote(bool* problem = nullptr) const;
    const Scene& scene() const { return scene_; }

    /// Writes the images and render.json of the latest snapshot into `dir` as one set
    /// (writeRenderOutputs), with the images also in each of `moreFormats`. Only after the job has
    /// finished (the renderer must be idle). Throws std::runtime_error naming the file on failure.
    RenderOutputs write(const std::string& dir, ImageFormat format, float exposure,
                        const std::vector<std::pair<ImageFormat, float>>& moreFormats = {}) const;

private:
    void publish();
    void publish(std::shared_ptr<const RenderSnapshot> snapshot);

    const Scene scene_;
    const RenderOptions options_;
    mutable std::mutex mutex_;  ///< guards renderer_ creation and latest_
    std::unique_ptr<Accel> accel_;
    /// Shared with the job's cancel hook, which may fire after the session is gone.
    std::shared_ptr<Renderer> renderer_;
    std::shared_ptr<const RenderSnapshot> latest_;
    double latestNoise_ = 0;  ///< relative noise of latest_ (guarded by mutex_)
    std::shared_ptr<const FootprintMask> footprint_;
    std::atomic<uint64_t> revision_{0};
    const std::optional<Store> store_;
    std::atomic<bool> loaded_{false};
    std::string storeNote_;  ///< guarded by mutex_
    bool storeNoteIsProblem_ = false;  ///< guarded by mutex_
    RenderStats loadedStats_;  ///< a loaded render's statistics (its renderer never ran); guarded by mutex_
};

/// The ground truth's label in the views when it was loaded from the store.
constexpr const char* kStoredGroundTruthLabel = "ground truth (stored)";

/// Passes per progressive render in the workbench: one sample per pass up to 64 spp gives a visible
/// refresh every pass; beyond that, passes of spp/64 keep snapshot copies a small part of the work.
constexpr int kGuiRenderPasses = 64;

/// The ground truth's camera: the scene camera at the render settings' size, so that a prediction
/// made with it lines up pixel for pixel with the ground truth and the error map.
inline Camera groundTruthCamera(const Scene& scene, const RenderSettings& settings) {
    const RenderOptions o = renderOptionsFor(scene, settings, kGuiRenderPasses);
    Camera c = scene.camera;
    c.width = o.width;
    c.height = o.height;
    return c;
}

}  // namespace rrf
