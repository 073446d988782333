#include "app/gui/live_prediction.h"

#include "app/gl/gl_context.h"
#include "app/gl/gl_worker.h"
#include "app/gl/glsl_predictor.h"
#include "core/util/stopwatch.h"

namespace rrf {

namespace {

/// Brings `gp` to `camera`, the light at `lightPos` and `prediction` (each only when it changed:
/// a new camera reallocates the targets, a moved light re-uploads its geometry).
void configure(GlslPredictor& gp, const Camera& camera, const Vec3& lightPos, const PredictionSettings& prediction) {
    const Camera& current = gp.camera();
    if (current.width != camera.width || current.height != camera.height || !(current.eye == camera.eye) ||
        !(current.target == camera.target) || !(current.up == camera.up) || current.fovYDegrees != camera.fovYDegrees)
        gp.setCamera(camera);
    if (!(gp.lightPosition() == lightPos)) gp.setLightPosition(lightPos);
    gp.setPrediction(prediction);
}

/// Side of the warm-up frame: enough pixels to run every pass, few enough to cost nothing.
constexpr int kWarmUpSize = 4;

}  // namespace

LivePrediction::LivePrediction() = default;

LivePrediction::~LivePrediction() {
    reset();          // posts the release of the predictor, and of one still being built
    worker_.reset();  // runs what was posted, then stops
}

GlWorker* LivePrediction::worker(std::string& error) {
    if (!worker_ && workerError_.empty()) {
        try {
            worker_ = std::make_unique<GlWorker>();
        } catch (const std::exception& e) {
            workerError_ = e.what();
        }
    }
    error = workerError_;
    return worker_.get();
}

void LivePrediction::releasePredictor() {
    rows_ = {};
    if (!glsl_) return;
    // Its GL names belong to the worker's context: it is destroyed there.
    worker_->post([gp = std::move(glsl_)]() mutable { gp.reset(); });
    glsl_.reset();
}

void LivePrediction::load(const Scene& scene, const std::string& dir, bool tryGlsl, const PredictionSettings& warmUp,
                          std::shared_ptr<const ModelSet> preloaded) {
    dropBuild();
    std::shared_ptr<const ModelSet> models =
        preloaded ? std::move(preloaded) : std::make_shared<const ModelSet>(loadModelSet(dir, scene.contentHash()));
    if (models->objects.empty()) throw std::runtime_error(dir + ": the model set holds no networks");
    pendingModels_ = models;
    pendingDir_ = dir;
    pendingSceneHash_ = scene.contentHash();
    std::string error = "not requested";
    GlWorker* gl = tryGlsl ? worker(error) : nullptr;
    if (!gl) {
        builtAtOnce_ = Built{nullptr, Build{}};
        builtAtOnce_->build.glslError = error;
        return;
    }
    build_ = gl->post([scene, models, warmUp]() -> Built {
        Built b;
        const Stopwatch clock;
        ProgramBinaryCache& cache = ProgramBinaryCache::shared();
        const ProgramBinaryCache::Counts before = cache.countsOnThisThread();
        try {
            auto gp = std::make_shared<GlslPredictor>(scene, *models);
            Camera tiny = scene.camera;
            tiny.width = tiny.height = kWarmUpSize;
            configure(*gp, tiny, scene.lightPosition(), warmUp);
            gp->render();
            gp->read(Term::Global);  // waits for the draws, which compiled the programs' machine code
            b.glsl = std::move(gp);
        } catch (const std::exception& e) {
            b.build.glslError = e.what();
        }
        const ProgramBinaryCache::Counts after = cache.countsOnThisThread();
        b.build.programs.hits = after.hits - before.hits;
        b.build.programs.misses = after.misses - before.misses;
        b.build.notes = cache.takeNotes();
        b.build.seconds = clock.seconds();
        return b;
    });
}

std::optional<LivePrediction::Build> LivePrediction::takeBuild() {
    if (!pendingModels_) return std::nullopt;
    Built b;
    if (builtAtOnce_) {
        b = std::move(*builtAtOnce_);
        builtAtOnce_.reset();
    } else {
        if (!resultReady(build_)) return std::nullopt;
        b = build_.get();  // the task catches its own errors
    }
    releasePredictor();  // the models these replace
    glsl_ = std::move(b.glsl);
    models_ = std::move(pendingModels_);
    dir_ = std::move(pendingDir_);
    sceneHash_ = pendingSceneHash_;
    return std::move(b.build);
}

void LivePrediction::dropBuild() {
    if (build_.valid() && worker_) {
        // A build in flight: its predictor is released on the worker when it is done.
        worker_->post([b = std::make_shared<std::future<Built>>(std::move(build_))] { b->get().glsl.reset(); });
    }
    build_ = {};
    builtAtOnce_.reset();
    pendingModels_.reset();
    pendingDir_.clear();
}

void LivePrediction::reset() {
    dropBuild();
    releasePredictor();  // before the models it was built from
    models_.reset();
    dir_.clear();
    sceneHash_ = 0;
}

double LivePrediction::renderGlsl(const Camera& camera, const Vec3& lightPos, const PredictionSettings& prediction,
                                  Image out[kTermCount]) {
    std::vector<Image> images;
    const double seconds = worker_->run([gp = glsl_, camera, lightPos, prediction, &images] {
        configure(*gp, camera, lightPos, prediction);
        gp->render();
        for (Term t : kTerms) images.push_back(gp->read(t));
        return gp->frameSeconds();
    });
    for (Term t : kTerms) out[int(t)] = std::move(images[size_t(t)]);
    return seconds;
}

void LivePrediction::startRows(const Camera& camera, const Vec3& lightPos, const PredictionSettings& prediction,
                               int rowBegin, int rowEnd, bool readImages) {
    rows_ = worker_->post([gp = glsl_, camera, lightPos, prediction, rowBegin, rowEnd, readImages] {
        const Stopwatch clock;
        configure(*gp, camera, lightPos, prediction);
        // Image rows count from the top, GL's from the bottom.
        gp->render(camera.height - rowEnd, camera.height - rowBegin);
        Rows r;
        r.seconds = gp->frameSeconds();  // waits for the band's passes
        r.wallSeconds = clock.seconds();
        if (readImages)
            for (Term t : kTerms) r.images.push_back(gp->read(t));
        return r;
    });
}

std::optional<LivePrediction::Rows> LivePrediction::takeRows() {
    if (!resultReady(rows_)) return std::nullopt;
    return rows_.get();
}

}  // namespace rrf
