// PredictionController (prediction_controller.h): the trained models' prediction in the middle view.
// The GLSL path renders on the GL worker (drafts within the frame of a light move, full frames in
// bands the UI does not wait for); the CPU path
// (core/predict/predictor.h) runs as a Predict job when the GLSL predictor could not be built.
#include "app/gui/prediction_controller.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "app/gl/program_binary_cache.h"
#include "app/gui/cpu_frame.h"
#include "app/gui/prediction_bands.h"
#include "app/gui/prediction_draft.h"
#include "app/gui/render_session.h"
#include "core/eval/evaluation.h"
#include "core/predict/glossy_gather.h"
#include "core/predict/predictor.h"
#include "core/pipeline/run_recording.h"
#include "core/util/stopwatch.h"
#include "panels/panels.h"
#include "panels/view_model.h"

namespace rrf {

namespace fs = std::filesystem;

/// A CPU prediction and the time it took (G-buffer + networks), for the runs table.
struct TimedPrediction {
    Prediction prediction;
    double seconds = 0;
    Vec3 light{0.f};  ///< the light it was predicted for: a frame for a light that moved on is dropped
    panels::ImageStamp stamp;  ///< light, scene and size it was predicted for
    std::shared_ptr<const CpuFrame> frame;  ///< a copy for an evaluation of the same models to reuse
};

namespace {
Camera viewCamera(const Project& project) { return groundTruthCamera(project.scene, project.render); }
}  // namespace

/// The leaf of every view pixel, for the prediction of revision `forPrediction`.
struct LeafOverlay {
    std::vector<int> pixelLeaf;
    int width = 0, height = 0;
    uint64_t forPrediction = 0;
};

PredictionController::PredictionController(ControllerContext& ctx)
    : ctx_(ctx),
      state_(ctx.state),
      predictJob_(ctx.jobs, JobKind::Predict, ctx.state.log),
      overlayJob_(ctx.jobs, JobKind::Overlay, ctx.state.log),
      flipJob_(ctx.jobs, JobKind::Overlay, ctx.state.log),
      spreadJob_(ctx.jobs, JobKind::Spread, ctx.state.log),
      modelRead_(ctx.jobs, ctx.state.log) {}

PredictionController::~PredictionController() = default;

void PredictionController::drop() {
    for (JobSessionBase* job : std::initializer_list<JobSessionBase*>{&predictJob_, &overlayJob_, &flipJob_, &spreadJob_})
        job->drop();
    modelRead_.drop();
    upload_.reset();
    predictPending_ = false;
    bands_.active = false;
    live_.dropRows();
}

bool PredictionController::loadModels(const std::string& dir, std::shared_ptr<const ModelSet> preloaded,
                                      std::function<void()> then) {
    if (dir.empty()) return false;
    if (preloaded) {
        modelRead_.drop();  // these replace whatever set was still being read
        upload_ = PendingUpload{dir, std::move(preloaded), 0.0, state_.project.scene.contentHash(), std::move(then)};
        uploadAnnounced_ = false;
        return true;
    }
    // The weights are read (and checked against the scene) on a worker; the GL upload stays here.
    const uint64_t sceneHash = state_.project.scene.contentHash();
    return modelRead_.start(
        "models",
        [dir, sceneHash](JobContext&) -> std::optional<ReadModels> {
            ReadModels r;
            const Stopwatch clock;
            try {
                r.models = std::make_shared<const ModelSet>(loadModelSet(dir, sceneHash));
            } catch (const std::exception& e) {
                r.error = e.what();
            }
            r.seconds = clock.seconds();
            return r;
        },
        [this, dir, sceneHash, then = std::move(then)](ReadModels& r) {
            if (!r.error.empty()) {
                state_.notify(panels::LogLevel::Error, "Project", "loading the models failed: " + r.error);
                return;
            }
            upload_ = PendingUpload{dir, std::move(r.models), r.seconds, sceneHash, then};
            uploadAnnounced_ = false;
        });
}

void PredictionController::uploadPendingModels() {
    if (!upload_) return;
    // Not before a frame has shown the note (a set trained or read earlier in this very frame);
    // should no frame draw it (no status bar), after one frame all the same.
    if (!uploadAnnounced_ && ++upload_->polls < 2) return;
    PendingUpload u = std::move(*upload_);
    upload_.reset();
    const bool announced = uploadAnnounced_;
    uploadAnnounced_ = false;
    // An edit since they were read or trained: they were checked against the scene as it was.
    if (state_.project.scene.contentHash() != u.sceneHash) {
        state_.log.warning("the scene changed while the models of " + u.dir + " were loaded; train again for a prediction");
        return;
    }
    ++uploads_;
    announcedUploads_ += announced;
    uploadModels(u.dir, std::move(u.models), u.readSeconds, std::move(u.then));
}

bool PredictionController::uploadModels(const std::string& dir, std::shared_ptr<const ModelSet> models, double readSeconds,
                                        std::function<void()> then) {
    try {
        live_.load(state_.project.scene, dir, true, state_.project.prediction, std::move(models));
    } catch (const std::exception& e) {
        state_.notify(panels::LogLevel::Error, "Project", std::string("loading the models failed: ") + e.what());
        return false;
    }
    // The GL worker builds the predictor and compiles its programs; finishUpload() takes it over.
    building_ = Building{dir, readSeconds, std::move(then)};
    bands_ = BandedFrame{};
    return true;
}

void PredictionController::finishUpload() {
    if (!building_) return;
    std::optional<LivePrediction::Build> built = live_.takeBuild();
    if (!built) return;  // still compiling on the GL worker
    Building b = std::move(*building_);
    building_.reset();
    // The program cache's notes (a driver without binaries, a damaged file, named) and what it did.
    for (const std::string& line : built->notes) state_.log.warning(line);
    lastLoadPrograms_ = built->programs;
    if (!built->glslError.empty())
        state_.log.warning("GLSL prediction unavailable, using the CPU predictor (slower): " + built->glslError);
    state_.training.modelsDir = b.dir;
    lastCpuFrame_.reset();
    state_.lightRegion.map.reset();  // it judged the models these replace
    for (int k = 0; k < 2; ++k) {
        frameSeconds_[k].clear();
        framesSinceRecorded_[k] = 0;
    }
    predictedOnce_ = draftShown_ = false;  // the first frame of new models is a draft, then the full one in bands
    bands_ = BandedFrame{};
    secondsPerRow_ = 0.0;  // their full frame's cost is not known yet
    fullFrameLogged_ = false;
    state_.leaves = panels::leavesOf(*live_.models());
    state_.view.compareSource = panels::CompareSource::Prediction;
    char timing[224];
    char read[64] = "";
    if (b.readSeconds > 0.0) std::snprintf(read, sizeof read, " after %.2f s of reading on a worker", b.readSeconds);
    std::snprintf(timing, sizeof timing, " in %.2f s on the GL worker%s (GLSL programs: %d from the binary cache, %d compiled)",
                  built->seconds, read, lastLoadPrograms_.hits, lastLoadPrograms_.misses);
    state_.log.info("models loaded from " + b.dir + (live_.usesGlsl() ? " (GLSL live prediction)" : " (CPU prediction)") +
                    (live_.usesGlsl() ? std::string(timing) : ""));
    refresh();
    if (b.then && live_.loaded()) b.then();  // not when the scene changed meanwhile (refresh dropped them)
}

void PredictionController::startGlWorker() {
    std::string error;
    if (!live_.worker(error)) state_.log.warning("no GL worker (" + error + "): the live prediction runs on the CPU");
}

void PredictionController::refresh() {
    if (!live_.loaded() || !state_.hasProject) return;
    const Scene& scene = state_.project.scene;
    if (scene.contentHash() != live_.sceneHash()) {
        // Materials or geometry changed: the networks learnt another scene.
        state_.log.warning("the scene changed since the models were trained; train again for a prediction");
        live_.reset();
        state_.training.modelsDir.clear();
        state_.leaves = panels::LeavesInfo{};
        state_.prediction = panels::ImageSet{};
        state_.prediction.touch();
        return;
    }
    const Camera camera = viewCamera(state_.project);
    if (live_.usesGlsl()) {
        // New models are being built on the GL worker: a frame of the old ones would wait for
        // that; the new ones' first frame follows the build (finishUpload).
        if (live_.building()) return;
        // A light that moved since the last frame is being dragged: draft until it rests. The
        // first frame of new models is a draft too, shown while the full frame renders in bands.
        const Vec3 light = scene.lightPosition();
        const bool draft = !predictedOnce_ || !(light == predictedLight_);
        if (draft) {
            Image images[kTermCount];
            try {
                const Stopwatch clock;
                const int divisor = draftDivisor_;
                live_.renderGlsl(draftCamera(camera, divisor), light, draftPrediction(state_.project.prediction),
                                 images);
                for (Image& im : images) im = replicatePixels(im, camera.width, camera.height);
                draftSeconds_.push_back(clock.seconds());
                // Until a full frame has been timed, its cost per row is guessed from the draft's on
                // the safe side: as if every pixel and every light sample cost what the draft's did.
                if (!(secondsPerRow_ > 0.0))
                    secondsPerRow_ = draftSeconds_.back() * divisor * divisor * kDraftSampleDivisor / camera.height;
                draftDivisor_ = nextDraftDivisor(draftDivisor_, draftSeconds_.back());
                if (draftSeconds_.size() > 64) draftSeconds_.erase(draftSeconds_.begin());
            } catch (const std::exception& e) {
                state_.log.error(std::string("GLSL prediction failed: ") + e.what());
                return;
            }
            const bool first = !predictedOnce_;
            showGlsl(images, camera, true);
            bands_.active = false;  // a frame of the previous light is of no use now
            if (!first) return;     // the full frame follows once the light has rested (finishDraft)
            draftShown_ = false;    // ... or right away for new models
        }
        startBands(camera);
        return;
    }
    startCpuPrediction(camera);
}

void PredictionController::showGlsl(Image images[kTermCount], const Camera& camera, bool draft) {
    const Scene& scene = state_.project.scene;
    const Vec3 light = scene.lightPosition();
    predictedLight_ = light;
    predictedOnce_ = true;
    draftShown_ = draft;
    if (draft) draftTime_ = std::chrono::steady_clock::now();
    // The glossy gather runs on the CPU only (core/predict/glossy_gather.h): the GLSL frame shows
    // the networks' own indirect light on the gathered objects until the CPU frame replaces it.
    const bool gather = !draft && !gatheredObjects(scene, *live_.models(), state_.project.prediction).empty();
    panels::ImageSet& p = state_.prediction;
    for (Term t : kTerms) p.term(t) = std::move(images[int(t)]);
    p.label = draft    ? "Prediction (GLSL, draft until the full frame is done)"
              : gather ? "Prediction (GLSL; the glossy gather follows on the CPU)"
                       : "Prediction (GLSL)";
    p.withoutNetwork = panels::objectsWithoutNetwork(state_.objectIds, *live_.models(), state_.project.prediction);
    p.stamp = panels::ImageStamp{light, scene.contentHash(), camera.width, camera.height};
    p.touch();
    if (gather) startCpuPrediction(camera);
}

void PredictionController::startBands(const Camera& camera) {
    live_.dropRows();
    bands_ = BandedFrame{};
    bands_.active = true;
    bands_.camera = camera;
    bands_.light = state_.project.scene.lightPosition();
    bands_.settings = state_.project.prediction;
    bands_.bandRows = firstBandRows(camera.height, secondsPerRow_);
    // The first band comes with the next frame's poll: this frame may already have paid for a draft.
}

void PredictionController::renderBand() {
    if (!bands_.active) {
        live_.dropRows();  // a frame abandoned (the light moved, new models): its band is of no use
        return;
    }
    if (!live_.loaded() || !live_.usesGlsl()) {
        bands_.active = false;
        return;
    }
    const int height = bands_.camera.height;
    if (live_.rowsRunning()) {
        std::optional<LivePrediction::Rows> done;
        try {
            done = live_.takeRows();
        } catch (const std::exception& e) {
            bands_.active = false;
            state_.log.error(std::string("GLSL prediction failed: ") + e.what());
            return;
        }
        if (!done) return;  // still rendering on the GL worker; the UI goes on meanwhile
        bands_.gpuSeconds += done->seconds;
        bands_.wallSeconds += done->wallSeconds;  // how long the band held the GL worker
        bands_.longestBand = std::max(bands_.longestBand, done->wallSeconds);
        bands_.bandRows = nextBandRows(bands_.rowsInFlight, done->wallSeconds, height);
        bands_.rowsDone += bands_.rowsInFlight;
        ++bands_.bands;
        if (bands_.rowsDone >= height) {
            finishBands(*done);
            return;
        }
    }
    const int rows = std::min(bands_.bandRows, height - bands_.rowsDone);
    const int end = height - bands_.rowsDone;  // image rows, from the bottom up (the G-buffer comes first)
    bands_.rowsInFlight = rows;
    live_.startRows(bands_.camera, bands_.light, bands_.settings, end - rows, end, bands_.rowsDone + rows >= height);
}

void PredictionController::finishBands(LivePrediction::Rows& last) {
    bands_.active = false;
    const int height = bands_.camera.height;
    Image images[kTermCount];
    for (Term t : kTerms) images[int(t)] = std::move(last.images[size_t(t)]);
    secondsPerRow_ = bands_.wallSeconds / height;
    lastFullFrame_ = BandedFrameSummary{bands_.gpuSeconds, bands_.longestBand, bands_.bands};
    if (!fullFrameLogged_) {
        fullFrameLogged_ = true;
        char line[200];
        std::snprintf(line, sizeof line,
                      "first full GLSL frame of these models: %.3f s on the device, in %d band(s) of at most %.3f s on the GL worker",
                      bands_.gpuSeconds, bands_.bands, bands_.longestBand);
        state_.log.info(line);
    }
    // The figure recorded is the frame's cost on the device (its bands' GPU time from timer
    // queries, plus the CPU's direct light where the GPU cannot do it); read-back to the CPU and
    // the split into bands are the workbench's own overhead.
    noteFrameSeconds(FramePath::Glsl, bands_.gpuSeconds, bands_.camera.width, height);
    showGlsl(images, bands_.camera, false);
}

void PredictionController::startCpuPrediction(const Camera& camera) {
    if (predictRunning()) {
        predictPending_ = true;  // the light moved again: predict once more when this one is done
        return;
    }
    const Scene& scene = state_.project.scene;
    const PredictionSettings settings = state_.project.prediction;
    auto shared = std::make_shared<const Scene>(scene);
    const std::shared_ptr<const ModelSet> models = live_.models();
    const Vec3 light = scene.lightPosition();
    std::string why;
    const bool started = predictJob_.start("CPU prediction", [shared, models, settings, light, camera](JobContext& ctx)
                                               -> std::optional<TimedPrediction> {
        const Stopwatch clock;
        const Predictor predictor(*shared, *models, settings);
        auto frame = std::make_shared<CpuFrame>();
        frame->gbuffer = predictor.gbuffer(light, camera.width, camera.height);
        frame->gbufferSeconds = clock.seconds();
        TimedPrediction p{predictor.predict(frame->gbuffer), 0.0, light,
                          panels::ImageStamp{light, shared->contentHash(), camera.width, camera.height}, nullptr};
        // The frame's time is the prediction's: the members' spread (an extra pass for the spread
        // view and evaluations) is not part of what a frame costs.
        p.seconds = clock.seconds() - p.prediction.spreadSeconds;
        frame->models = models;
        frame->settings = settings;
        frame->stamp = p.stamp;
        frame->prediction = p.prediction;  // the views take the images; the copy is made here, off the UI thread
        p.frame = std::move(frame);
        ctx.setProgress(1.0);
        return p;
    }, &why);
    if (!started) {
        state_.log.warning("prediction deferred: " + why);
        predictPending_ = true;
        return;
    }
    predictPending_ = false;
}

void PredictionController::finishDraft() {
    if (!draftShown_) return;
    const double rested = std::chrono::duration<double>(std::chrono::steady_clock::now() - draftTime_).count();
    if (rested < kDraftRestSeconds) return;
    draftShown_ = false;
    if (live_.loaded() && live_.usesGlsl()) refresh();  // same light: the full-quality frame
}

void PredictionController::noteFrameSeconds(FramePath path, double seconds, int width, int height) {
    // The median of the last few frames: the first GLSL frame also compiles and uploads, and a
    // single frame is noisy; the figure lands in the models' training run for the runs table.
    constexpr size_t kFrames = 9;
    const int kind = path == FramePath::Glsl ? kGlslFrames : kCpuFrames;
    std::vector<double>& frames = frameSeconds_[kind];
    frames.push_back(seconds);
    if (frames.size() > kFrames) frames.erase(frames.begin());
    // Finding the run resolves its paths on the file system: once per kFrames frames, not per
    // frame of a light drag (and at once for the first, single CPU frames).
    if (++framesSinceRecorded_[kind] < kFrames && frames.size() > 1) return;
    framesSinceRecorded_[kind] = 0;
    std::vector<double> sorted = frames;
    std::sort(sorted.begin(), sorted.end());
    recordFrameSeconds(state_.project.runs, ctx_.projectDir(), live_.dir(), path, sorted[sorted.size() / 2], width, height);
}

void PredictionController::objectIdsChanged() {
    if (!live_.loaded() || state_.prediction.empty()) return;
    std::vector<int> without = panels::objectsWithoutNetwork(state_.objectIds, *live_.models(), state_.project.prediction);
    if (without == state_.prediction.withoutNetwork) return;  // the views redraw only for a change
    state_.prediction.withoutNetwork = std::move(without);
    state_.prediction.touch();
}

void PredictionController::poll() {
    // A set waiting since the last frame (which announced it) is uploaded first, then a set whose
    // read has just ended waits for the next frame.
    uploadPendingModels();
    finishUpload();
    modelRead_.poll();
    predictJob_.poll([&](TimedPrediction& timed) {
        // Beside the GLSL view (the glossy gather's frame), a frame for a light that has moved on
        // would replace the newer GLSL frame with the old light's image; the CPU-only view shows
        // what it has (its stamp keeps the error figures honest).
        if (live_.usesGlsl() && !(timed.light == state_.project.scene.lightPosition())) return;
        lastCpuFrame_ = std::move(timed.frame);
        Prediction& prediction = timed.prediction;
        noteFrameSeconds(FramePath::Cpu, timed.seconds, timed.stamp.width, timed.stamp.height);
        panels::ImageSet& p = state_.prediction;
        for (Term t : kTerms) p.term(t) = std::move(prediction.images[int(t)]);
        p.label = prediction.pixelsGathered ? "Prediction (CPU, glossy gather)" : "Prediction (CPU)";
        p.stamp = timed.stamp;
        if (live_.loaded())
            p.withoutNetwork = panels::objectsWithoutNetwork(state_.objectIds, *live_.models(), state_.project.prediction);
        p.touch();
    });
    if (predictPending_ && !predictRunning() && !(holdCpuFrames && holdCpuFrames())) refresh();
    // A band per frame of a full-quality frame of the light and camera it was started for; a light
    // that moved meanwhile has its own draft (refresh) and full frame later.
    if (bands_.active && (!(bands_.light == state_.project.scene.lightPosition()) ||
                          !live_.loaded() || live_.sceneHash() != state_.project.scene.contentHash()))
        bands_.active = false;
    renderBand();
    updateLeafOverlay();
}

void PredictionController::updateLeafOverlay() {
    panels::LeavesInfo& l = state_.leaves;
    overlayJob_.poll([&](LeafOverlay& o) {
        // A result for an older prediction is still shown until the newer one arrives.
        l.pixelLeaf = std::move(o.pixelLeaf);
        l.width = o.width;
        l.height = o.height;
        l.forPrediction = o.forPrediction;
        ++l.revision;
    });
    if (!state_.view.leafOverlay || !live_.loaded() || l.forPrediction == state_.prediction.revision) return;
    if (overlayJob_.running() || overlayFor_ == state_.prediction.revision) return;  // one at a time, once per revision
    // Leaf lookup only (no network runs): a G-buffer of the view camera at the current light, on a
    // worker, since both grow with the image and the trees.
    const Camera camera = viewCamera(state_.project);
    auto scene = std::make_shared<const Scene>(state_.project.scene);
    const std::shared_ptr<const ModelSet> models = live_.models();
    const PredictionSettings settings = state_.project.prediction;
    const uint64_t revision = state_.prediction.revision;
    const bool started = overlayJob_.start("leaf overlay", [=](JobContext&) -> std::optional<LeafOverlay> {
        const Predictor predictor(*scene, *models, settings);
        LeafOverlay o;
        o.pixelLeaf = predictor.leaves(predictor.gbuffer(scene->lightPosition(), camera.width, camera.height));
        o.width = camera.width;
        o.height = camera.height;
        o.forPrediction = revision;
        return o;
    });
    if (started) overlayFor_ = revision;
}

bool PredictionController::exportImages(const std::string& dir) {
    if (!live_.loaded()) return true;  // nothing trained: nothing to add
    // Exported images come from the CPU predictor: the reference implementation, independent of
    // the GL driver that drew the view.
    try {
        const Predictor predictor(state_.project.scene, *live_.models(), state_.project.prediction);
        const Camera camera = viewCamera(state_.project);
        const Prediction p = predictor.predict(
            predictor.gbuffer(state_.project.scene.lightPosition(), camera.width, camera.height));
        writePredictionImages(dir, p, state_.view.exposure);
    } catch (const std::exception& e) {
        state_.notify(panels::LogLevel::Error, "", std::string("export prediction: ") + e.what());
        return false;
    }
    return true;
}

}  // namespace rrf
