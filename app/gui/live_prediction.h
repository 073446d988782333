#pragma once
/// The trained models' prediction for the middle view, kept current as the light moves.
///
/// GLSL path (the normal one): a GlslPredictor (app/gl) lives on the GL worker (app/gl/gl_worker.h),
/// a thread with an OpenGL context of its own. It is built there, and its programs compiled and
/// drawn once, while the UI keeps drawing (issue 29: llvmpipe compiles at a program's first draw,
/// seconds, in the context that draws). Drafts of a light drag are rendered there while the UI
/// thread waits (a few ms: the draft's size adapts to its time, prediction_draft.h), so a drag
/// shows the new prediction in the same frame; the full-quality frame is rendered there in bands
/// without the UI waiting (startRows / takeRows). The terms come back as images because the error
/// map, the hover read-out and the exposure control work on the values, not on a texture.
/// CPU path (fallback, and for exported images): core/Predictor, which the workbench runs as a
/// Predict job when the GLSL path could not be built (no GL worker, missing GL features, a shader
/// error). UI thread only; the ModelSet is shared read-only with CPU jobs and the GL worker.

#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/gl/program_binary_cache.h"
#include "core/util/image.h"
#include "core/nn/model_set.h"
#include "core/predict/prediction_settings.h"
#include "core/render/term.h"
#include "core/scene/scene.h"

namespace rrf {

class GlWorker;
class GlslPredictor;

class LivePrediction {
public:
    LivePrediction();
    /// Releases the predictor on the GL worker, then stops the worker.
    ~LivePrediction();
    LivePrediction(const LivePrediction&) = delete;
    LivePrediction& operator=(const LivePrediction&) = delete;

    /// Starts loading the model directory `dir` for `scene`: reads the set here unless `preloaded`
    /// (read by a worker already) holds it (models of another scene throw, naming the file), and,
    /// when `tryGlsl`, builds the GLSL predictor on the GL worker and renders one tiny frame with
    /// `warmUp`'s settings, which compiles its programs' machine code. The new models drive the
    /// prediction once takeBuild() has handed over the outcome; until then the models loaded
    /// before stay (for CPU frames, exports, evaluations), but no GLSL frame may be asked for
    /// while building(): the worker is busy with the build, and the frame would wait for it.
    /// A load still building is dropped.
    void load(const Scene& scene, const std::string& dir, bool tryGlsl, const PredictionSettings& warmUp,
              std::shared_ptr<const ModelSet> preloaded = nullptr);
    /// Forgets the models and a build in flight (a new project, or a scene edit that makes them stale).
    void reset();

    /// How a load ended (the models it replaced are forgotten): `glslError` is empty when the GLSL path is in use, else why not (the CPU
    /// path is used); the build's seconds on the GL worker and what the program binary cache did.
    struct Build {
        std::string glslError;
        double seconds = 0.0;
        ProgramBinaryCache::Counts programs;  ///< hits and misses of this build
        std::vector<std::string> notes;       ///< the program cache's warnings and notes
    };
    /// True from load() until takeBuild() handed its outcome over.
    bool building() const { return pendingModels_ != nullptr; }
    /// Once the load has ended: its outcome, and from then on the new models are loaded(). Empty
    /// while the GL worker is still building (or no load is pending).
    std::optional<Build> takeBuild();

    bool loaded() const { return models_ != nullptr; }
    bool usesGlsl() const { return glsl_ != nullptr; }
    const std::string& dir() const { return dir_; }
    /// Scene::contentHash() of the scene the models were loaded for.
    uint64_t sceneHash() const { return sceneHash_; }
    std::shared_ptr<const ModelSet> models() const { return models_; }

    /// GLSL path only: renders with `camera` (its width × height), the light at `lightPos` and the
    /// project's `prediction` settings (exact or learned direct light) on the GL worker, waiting
    /// for it, and returns the images of every term, out[int(Term)] (top row first); returns the
    /// frame's cost in seconds (GlslPredictor::frameSeconds: its passes' GPU time, plus the CPU's
    /// direct light in mode 2). Throws GlError on GL failure.
    double renderGlsl(const Camera& camera, const Vec3& lightPos, const PredictionSettings& prediction,
                      Image out[kTermCount]);
    /// GLSL path only: starts rendering the image rows [rowBegin, rowEnd) (top row first, as images
    /// count) of the frame renderGlsl would render, the other rows kept from earlier bands of the
    /// same camera, light and settings (GlslPredictor::render(rowBegin, rowEnd)), without waiting.
    /// A band that starts at the bottom of the image renders the G-buffer too, so the bands of a
    /// frame go bottom up. `readImages`: the band ends the frame, read every term back after it.
    /// One band at a time (a band still running is dropped).
    void startRows(const Camera& camera, const Vec3& lightPos, const PredictionSettings& prediction, int rowBegin,
                   int rowEnd, bool readImages);
    /// A band finished: its cost as renderGlsl returns it, the wall seconds it held the GL worker,
    /// and, when it was asked to read them, the images of every term (index int(Term)).
    struct Rows {
        double seconds = 0.0, wallSeconds = 0.0;
        std::vector<Image> images;
    };
    /// True while a band started by startRows has not been taken.
    bool rowsRunning() const { return rows_.valid(); }
    /// The band, once it has finished (empty before); rethrows its GlError.
    std::optional<Rows> takeRows();
    /// Forgets the band in flight (its frame was abandoned); it still finishes on the worker.
    void dropRows() { rows_ = {}; }

    /// The GL worker, made at the first call (null, with the reason in `error`, when no context
    /// could be made).
    GlWorker* worker(std::string& error);

private:
    void releasePredictor();
    /// Forgets the load in flight (its predictor is released on the worker once built).
    void dropBuild();

    std::unique_ptr<GlWorker> worker_;
    std::string workerError_;
    std::shared_ptr<const ModelSet> models_;
    std::shared_ptr<GlslPredictor> glsl_;  ///< used and destroyed on the GL worker only
    std::string dir_;
    uint64_t sceneHash_ = 0;
    /// The load in flight: its models, directory and scene, and the GL worker's build.
    std::shared_ptr<const ModelSet> pendingModels_;
    std::string pendingDir_;
    uint64_t pendingSceneHash_ = 0;
    struct Built {
        std::shared_ptr<GlslPredictor> glsl;
        Build build;
    };
    std::future<Built> build_;
    std::optional<Built> builtAtOnce_;  ///< a load without the GLSL path (or without a worker)
    std::future<Rows> rows_;
};

}  // namespace rrf
