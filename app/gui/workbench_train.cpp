// Workbench: the training job. It reads the dataset, trains one network per object (and target)
// through core/pipeline/train_stage on a worker, publishes every network's epoch records under a mutex for
// the live loss plot, saves the models into <project dir>/runs/<run>/models and records a "train" run.
#include "app/gui/workbench.h"

#include <filesystem>
#include <map>
#include <mutex>

#include "core/data/dataset_file.h"
#include "core/nn/model_set.h"
#include "core/nn/network_settings.h"
#include "core/pipeline/run_recording.h"
#include "core/pipeline/train_stage.h"
#include "core/util/stopwatch.h"
#include "core/util/text_format.h"
#include "panels/plot.h"

namespace rrf {

namespace fs = std::filesystem;
using nlohmann::json;

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

bool Workbench::trainRunning() const { return trainJob_.running(); }

std::string Workbench::datasetPath() const {
    if (!state_.dataset.path.empty()) return state_.dataset.path;
    const fs::path p = fs::path(projectDir()) / "data" / "dataset.rrfd";
    std::error_code ec;
    return fs::exists(p, ec) ? p.string() : std::string();
}

bool Workbench::startTrain(int maxEpochs) {
    if (!state_.hasProject) {
        state_.notify(panels::LogLevel::Error, "Training", "train: no project is open");
        return false;
    }
    if (untitled_ || state_.project.path.empty()) {
        state_.notify(panels::LogLevel::Error, "Training", "train: save the project first (models are stored next to it)");
        return false;
    }
    TrainingOutcome job;
    job.dataset = datasetPath();
    if (job.dataset.empty()) {
        state_.notify(panels::LogLevel::Error, "Training", "train: no dataset yet; generate one in the Sampling panel");
        return false;
    }
    job.runId = newRunId(state_.project.runs, "train");
    job.modelsDir = (fs::path(projectDir()) / "runs" / job.runId / "models").string();
    TrainRequest request;
    request.settings = state_.project.networkOrDefault();
    auto& trainer = request.settings.options.trainer;
    if (maxEpochs > 0) trainer.lm.maxEpochs = trainer.adam.maxEpochs = maxEpochs;
    request.sampling = state_.project.sampling;
    request.sceneHash = state_.project.scene.contentHash();
    request.modelsDir = job.modelsDir;
    request.provenance = {job.dataset, state_.project.path};
    request.readBack = true;
    std::vector<std::string> names;
    for (const Object& o : state_.project.scene.objects) names.push_back(o.name);
    const ObjectTrainingOptions& o = request.settings.options;
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
    trainLive_ = live;
    trainRevision_ = ~0ull;
    const std::string lastModels = state_.training.modelsDir;  // the prediction's, kept by a stop
    state_.training = panels::TrainingInfo{};
    state_.training.modelsDir = lastModels;
    state_.training.running = true;
    state_.training.trainer = o.trainer.typeName();
    state_.training.runId = job.runId;
    state_.focusTab = "Training";
    state_.log.info("train started: " + name + " on " + job.dataset);
    return true;
}

void Workbench::pollTrain() {
    state_.training.running = trainRunning();
    if (trainLive_) {
        std::lock_guard<std::mutex> lock(trainLive_->mutex);
        if (trainLive_->revision != trainRevision_) {
            trainRevision_ = trainLive_->revision;
            state_.training.curves = trainLive_->curves;
            state_.training.epoch = trainLive_->epoch;
            state_.training.step = trainLive_->step;
            state_.training.seconds = trainLive_->seconds;
        }
    }
    if (state_.training.running) state_.training.progress = trainJob_.progress();
    trainJob_.poll([&](TrainingOutcome& outcome) { trainingFinished(outcome); });
    if (!state_.training.running) trainLive_.reset();
}

void Workbench::trainingFinished(TrainingOutcome& s) {
    TrainRecord& record = s.record;
    if (!record.stopped) state_.training.progress = 1.0;
    state_.training.stopped = record.stopped;
    state_.training.networks = record.networks;
    state_.training.plannedNetworks = record.plannedNetworks;
    state_.training.partialRun = -1;
    if (record.networks == 0) {
        state_.notify(panels::LogLevel::Error, "Training", "train: no network was trained (see the Log); nothing saved");
        return;
    }
    Run run = beginRun(state_.project.runs, "train");
    run.id = run.name = s.runId;  // the models were saved under runs/<runId>/ when the job started
    auto rel = [&](const std::string& p) { return projectRelative(projectDir(), p); };
    state_.training.curves = record.curves;
    if (state_.dataset.path == s.dataset && state_.dataset.seconds > 0) record.generateSeconds = state_.dataset.seconds;
    const bool stopped = record.stopped;
    const int networks = record.networks;
    const double seconds = record.seconds;
    setTrainRun(run, projectDir(), std::move(record));
    state_.project.runs.push_back(run);
    state_.markDirty();
    if (stopped) {
        // A partial model set would leave the untrained objects without a prediction: the live view
        // keeps the last complete set; the Training panel offers the partial one.
        state_.training.partialRun = int(state_.project.runs.size()) - 1;
        state_.notify(panels::LogLevel::Warning, "Training", "training " + trainRunStatusText(run) + "; partial run '" + run.name +
                           "' recorded (models in " + rel(s.modelsDir) + "); the prediction keeps " +
                           (live_.loaded() ? "the last complete models" : "no models") +
                           " (Training panel: \"Use the partial models\")");
        return;
    }
    state_.log.info("trained " + std::to_string(networks) + " networks in " + std::to_string(int(seconds + 0.5)) +
                    " s; models in " + rel(s.modelsDir) + ", run '" + run.name + "' recorded");
    loadModels(s.modelsDir, std::move(s.models));
    ++trainingsCompleted_;
    // The pipeline evaluates as its own stage; a manual training is evaluated here (issue 29 item 8).
    if (!pipelineRunning()) evaluateAfterTrain_ = true;
}

}  // namespace rrf
