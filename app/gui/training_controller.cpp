// TrainingController (training_controller.h): the data-generation job (core/data/data_generator.h) and
// its dataset file, and the training job. Training reads the dataset, trains one network per object (and target) through core/pipeline/train_stage on a worker, publishes every network's epoch
// records under a mutex for the live loss plot, saves the models into <project dir>/runs/<run>/models and
// records a "train" run.
#include "app/gui/training_controller.h"

#include <filesystem>
#include <map>
#include <mutex>

#include "app/gui/live_prediction.h"
#include "core/data/data_generator.h"
#include "core/data/dataset_file.h"
#include "core/data/record_layout.h"
#include "core/data/sampling_settings.h"
#include "core/nn/model_set.h"
#include "core/nn/network_settings.h"
#include "core/pipeline/generate_stage.h"
#include "core/pipeline/run_recording.h"
#include "core/pipeline/train_stage.h"
#include "core/util/stopwatch.h"
#include "core/util/text_format.h"
#include "panels/plot.h"

namespace rrf {

namespace fs = std::filesystem;

/// What the loss plot shows while a training job runs: written by the trainer's threads, copied by
/// the UI thread when `revision` changed.
struct TrainingLive {
    std::mutex mutex;  ///< guards everything below
    std::vector<LossCurve> curves;
    std::map<std::pair<int, std::string>, size_t> curveIndex;
    int epoch = 0;
    double step = 0, seconds = 0;
    uint64_t revision = 0;
};

/// A finished training job: where its models went and what the run did (models themselves stay on
/// the worker; they are on disk).
struct TrainingOutcome {
    std::string dataset, modelsDir, runId;
    TrainRecord record;  ///< what the run records (core/pipeline/train_stage.h)
    /// The saved models read back on the worker (a complete run only), so that making them the
    /// live prediction does not read weights on the UI thread.
    std::shared_ptr<const ModelSet> models;
};

namespace {
LossPoint lossPoint(const EpochRecord& r) { return {r.epoch, r.trainLoss, r.validationLoss, r.seconds}; }

/// An empty loss curve for the live plot, which fills `points` as epochs finish.
LossCurve lossCurve(int objectId, const std::string& object, const std::string& target) {
    LossCurve c;
    c.objectId = objectId;
    c.object = object;
    c.target = target;
    return c;
}
}  // namespace

/// A dataset the generate job wrote: where, and what the generator did.
struct GeneratedDataset {
    std::string path;
    GeneratorStats stats;
    std::vector<std::string> objectNames;  ///< index = object id
    double seconds = 0.0;
    int inputCount = 0;
    SamplingSettings settings;  ///< what it was generated with (the coverage table's stale check)
    uint64_t sceneHash = 0;
};

TrainingController::TrainingController(ControllerContext& ctx, const LivePrediction& live)
    : ctx_(ctx),
      live_(live),
      generateJob_(ctx.jobs, JobKind::Generate, ctx.state.log),
      trainJob_(ctx.jobs, JobKind::Train, ctx.state.log) {}

TrainingController::~TrainingController() = default;

void TrainingController::poll() {
    pollGenerate();
    pollTrain();
}

void TrainingController::drop() {
    generateJob_.drop();
    trainJob_.drop();
    generateDone_ = trainDone_ = nullptr;
    trainLive_.reset();
}

bool TrainingController::startGenerate(StageDone done) {
    panels::WorkbenchState& state = ctx_.state;
    if (!state.hasProject) {
        state.log.error("generate: no project is open");
        return false;
    }
    const SamplingSettings settings = state.project.samplingOrDefault();
    auto scene = std::make_shared<const Scene>(state.project.scene);
    const std::string out = (fs::path(ctx_.projectDir()) / "data" / "dataset.rrfd").string();
    const std::string name = "dataset " + std::to_string(settings.nx) + "x" + std::to_string(settings.ny) + "x" +
                             std::to_string(settings.nz) + " x " + std::to_string(settings.directions);
    const bool started = generateJob_.start(name, [scene, settings, out](JobContext& ctx) -> std::optional<GeneratedDataset> {
        ctx.setStatus("preparing");
        const DataGenerator gen(*scene, settings);
        GenerateRequest request;
        request.datasetPath = out;
        GenerateOutcome generated = generateStage(gen, request, ctx.stageObserver());
        if (!generated.written) return std::nullopt;  // cancelled: the stage wrote nothing
        GeneratedData& data = generated.data;
        GeneratedDataset written;
        written.path = out;
        written.stats = std::move(data.stats);
        for (const Object& o : scene->objects) written.objectNames.push_back(o.name);
        written.seconds = data.seconds;
        written.inputCount = gen.layout().inputCount();
        written.settings = settings;
        written.sceneHash = scene->contentHash();
        return written;
    });
    if (!started) return false;
    generateDone_ = std::move(done);
    state.dataset.running = true;
    state.dataset.progress = 0.0;

    state.log.info("generate started: " + name + " -> " + out);
    return true;
}

void TrainingController::pollGenerate() {
    panels::WorkbenchState& state = ctx_.state;
    const bool wasRunning = state.dataset.running;
    if (generateRunning()) state.dataset.progress = generateJob_.progress();
    bool delivered = false;
    const bool ended = generateJob_.poll([&](GeneratedDataset& d) {
        delivered = true;
        state.dataset.progress = 1.0;
        state.dataset.path = d.path;
        state.dataset.objectNames = std::move(d.objectNames);
        state.dataset.generator = std::move(d.stats);
        state.dataset.seconds = d.seconds;
        state.dataset.inputCount = d.inputCount;
        state.dataset.madeWith = d.settings;
        state.dataset.sceneHash = d.sceneHash;
        state.dataset.lastCancelled = false;
        state.log.info("dataset written: " + d.path + " (" + std::to_string(state.dataset.generator.records) + " records)");
    });
    state.dataset.running = !ended;
    // A cancelled generation writes nothing: the table still shows the dataset before it, marked stale.
    if (wasRunning && ended && !delivered) state.dataset.lastCancelled = true;  // until a result arrives
    if (generateDone_ && ended) {
        const StageDone finished = std::move(generateDone_);
        generateDone_ = nullptr;
        finished(delivered);
    }
}

std::string TrainingController::datasetPath() const {
    const panels::WorkbenchState& state = ctx_.state;
    if (!state.dataset.path.empty()) return state.dataset.path;
    const fs::path p = fs::path(ctx_.projectDir()) / "data" / "dataset.rrfd";
    std::error_code ec;
    return fs::exists(p, ec) ? p.string() : std::string();
}

bool TrainingController::startTrain(int maxEpochs, StageDone done) {
    panels::WorkbenchState& state = ctx_.state;
    if (!state.hasProject) {
        state.notify(panels::LogLevel::Error, "Training", "train: no project is open");
        return false;
    }
    if (!ctx_.savedProject()) {
        state.notify(panels::LogLevel::Error, "Training", "train: save the project first (models are stored next to it)");
        return false;
    }
    TrainingOutcome job;
    job.dataset = datasetPath();
    if (job.dataset.empty()) {
        state.notify(panels::LogLevel::Error, "Training", "train: no dataset yet; generate one in the Sampling panel");
        return false;
    }
    job.runId = newRunId(state.project.runs, "train");
    job.modelsDir = (fs::path(ctx_.projectDir()) / "runs" / job.runId / "models").string();
    TrainRequest request;
    request.options = state.project.trainingOptions();
    auto& trainer = request.options.trainer;
    if (maxEpochs > 0)
        for (TrainerCommon* c : trainer.everyTrainer()) c->maxEpochs = maxEpochs;
    request.sampling = state.project.sampling;
    request.sceneHash = state.project.scene.contentHash();
    request.modelsDir = job.modelsDir;
    request.provenance = {job.dataset, state.project.path};
    request.readBack = true;
    std::vector<std::string> names;
    for (const Object& o : state.project.scene.objects) names.push_back(o.name);
    const ObjectTrainingOptions& o = request.options;
    const std::string name = "train " + hiddenSizesText(o.hidden) +
                             (o.ensemble > 1 ? " x" + std::to_string(o.ensemble) : std::string()) + " " + o.trainer.typeName();
    auto live = std::make_shared<TrainingLive>();
    const bool started = trainJob_.start(name, [job, request, live, names](JobContext& ctx) -> std::optional<TrainingOutcome> {
        TrainingOutcome out = job;
        const Stopwatch clock;
        StageObserver observer = ctx.stageObserver();
        observer.epoch = [&](int object, const std::string& target, const EpochRecord& r) {
            std::lock_guard<std::mutex> lock(live->mutex);
            auto [it, added] = live->curveIndex.emplace(std::make_pair(object, target), live->curves.size());
            if (added)
                live->curves.push_back(
                    lossCurve(object, object >= 0 && object < int(names.size()) ? names[size_t(object)] : "?", target));
            live->curves[it->second].points.push_back(lossPoint(r));
            live->epoch = std::max(live->epoch, r.epoch);
            live->step = r.step;
            live->seconds = clock.seconds();
            ++live->revision;
        };
        observer.setStatus("reading the dataset");
        const Dataset data(out.dataset, true, request.sceneHash);
        TrainOutcome trained = trainFromDataset(data, request, observer);
        out.record = std::move(trained.record);
        out.models = std::move(trained.models);
        return out;
    });
    if (!started) return false;
    trainDone_ = std::move(done);
    trainLive_ = live;
    trainRevision_ = ~0ull;
    const std::string lastModels = state.training.modelsDir;  // the prediction's, kept by a stop
    state.training = panels::TrainingInfo{};
    state.training.modelsDir = lastModels;
    state.training.running = true;
    state.training.trainer = o.trainer.typeName();
    state.training.runId = job.runId;
    state.focusTab = "Training";
    state.log.info("train started: " + name + " on " + job.dataset);
    return true;
}

void TrainingController::pollTrain() {
    panels::WorkbenchState& state = ctx_.state;
    state.training.running = trainRunning();
    if (trainLive_) {
        std::lock_guard<std::mutex> lock(trainLive_->mutex);
        if (trainLive_->revision != trainRevision_) {
            trainRevision_ = trainLive_->revision;
            state.training.curves = trainLive_->curves;
            state.training.epoch = trainLive_->epoch;
            state.training.step = trainLive_->step;
            state.training.seconds = trainLive_->seconds;
        }
    }
    if (state.training.running) state.training.progress = trainJob_.progress();
    bool delivered = false;
    const bool ended = trainJob_.poll([&](TrainingOutcome& outcome) { delivered = trainingFinished(outcome); });
    if (!state.training.running) trainLive_.reset();
    if (trainDone_ && ended) {
        const StageDone done = std::move(trainDone_);
        trainDone_ = nullptr;
        done(delivered);
    }
}

bool TrainingController::trainingFinished(TrainingOutcome& s) {
    panels::WorkbenchState& state = ctx_.state;
    const std::string projectDir = ctx_.projectDir();
    TrainRecord& record = s.record;
    if (!record.stopped) state.training.progress = 1.0;
    state.training.stopped = record.stopped;
    state.training.networks = record.networks;
    state.training.plannedNetworks = record.plannedNetworks;
    state.training.partialRun = -1;
    if (record.networks == 0) {
        state.notify(panels::LogLevel::Error, "Training", "train: no network was trained (see the Log); nothing saved");
        return false;
    }
    Run run = beginRun(state.project.runs, "train");
    run.id = run.name = s.runId;  // the models were saved under runs/<runId>/ when the job started
    auto rel = [&](const std::string& p) { return projectRelative(projectDir, p); };
    state.training.curves = record.curves;
    if (state.dataset.path == s.dataset && state.dataset.seconds > 0) record.generateSeconds = state.dataset.seconds;
    const bool stopped = record.stopped;
    const int networks = record.networks;
    const double seconds = record.seconds;
    setTrainRun(run, projectDir, std::move(record));
    state.project.runs.push_back(run);
    state.markDirty();
    if (stopped) {
        // A partial model set would leave the untrained objects without a prediction: the live view
        // keeps the last complete set; the Training panel offers the partial one.
        state.training.partialRun = int(state.project.runs.size()) - 1;
        state.notify(panels::LogLevel::Warning, "Training", "training " + trainRunStatusText(run) + "; partial run '" + run.name +
                           "' recorded (models in " + rel(s.modelsDir) + "); the prediction keeps " +
                           (live_.loaded() ? "the last complete models" : "no models") +
                           " (Training panel: \"Use the partial models\")");
        return false;
    }
    state.log.info("trained " + std::to_string(networks) + " networks in " + std::to_string(int(seconds + 0.5)) +
                    " s; models in " + rel(s.modelsDir) + ", run '" + run.name + "' recorded");
    if (onTrained) onTrained(s.modelsDir, std::move(s.models));
    return true;
}

}  // namespace rrf
