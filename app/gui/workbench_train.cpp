// Workbench: the training job. It reads the dataset, trains one network per object (and target)
// with core/nn_objects on a worker, publishes every network's epoch records under a mutex for the
// live loss plot, saves the models into <project dir>/runs/<run>/models and records a "train" run.
#include "app/gui/workbench.h"

#include <filesystem>
#include <map>
#include <mutex>

#include "core/data/dataset_file.h"
#include "core/nn/model_set.h"
#include "core/nn/network_settings.h"
#include "core/util/text_format.h"
#include "core/nn/training_samples.h"
#include "panels/plot.h"

namespace rrf {

namespace fs = std::filesystem;
using nlohmann::json;

/// Shared between the train job (worker, and trainObjects' own threads) and the UI thread.
struct TrainSession {
    Scene scene;
    NetworkSettings settings;
    std::string dataset, modelsDir, runId;
    std::mutex mutex;  ///< guards everything below
    std::vector<LossCurve> curves;
    std::map<std::pair<int, std::string>, size_t> curveIndex;
    int epoch = 0;
    double step = 0, seconds = 0;
    int64_t epochsDone = 0;
    uint64_t revision = 0;
    std::vector<std::string> messages;
    bool saved = false;  ///< models written
    double trainSeconds = 0;
    int networks = 0, skipped = 0;
};

bool Workbench::trainRunning() const { return trainJob_ != 0 && jobs_.running(JobKind::Train); }

std::string Workbench::datasetPath() const {
    if (!state_.dataset.path.empty()) return state_.dataset.path;
    const fs::path p = fs::path(projectDir()) / "data" / "dataset.rrfd";
    std::error_code ec;
    return fs::exists(p, ec) ? p.string() : std::string();
}

bool Workbench::startTrain(int maxEpochs) {
    if (!state_.hasProject) {
        state_.log.error("train: no project is open");
        return false;
    }
    if (untitled_ || state_.project.path.empty()) {
        state_.log.error("train: save the project first (models are stored next to it)");
        return false;
    }
    auto session = std::make_shared<TrainSession>();
    session->dataset = datasetPath();
    if (session->dataset.empty()) {
        state_.log.error("train: no dataset yet; generate one in the Sampling panel");
        return false;
    }
    try {
        session->settings = state_.project.networkOrDefault();
    } catch (const std::exception& e) {
        state_.log.error(std::string("train: ") + e.what());
        return false;
    }
    if (maxEpochs > 0) session->settings.options.trainer.lm.maxEpochs = session->settings.options.trainer.adam.maxEpochs = maxEpochs;
    session->scene = state_.project.scene;
    session->runId = newRunId(state_.project.runs, "train");
    session->modelsDir = (fs::path(projectDir()) / "runs" / session->runId / "models").string();
    const ObjectTrainingOptions& o = session->settings.options;
    const std::string name = std::string("train ") + json(o.hidden).dump() + " " + o.trainer.typeName();
    std::string why;
    const int id = jobs_.start(JobKind::Train, name, [session](JobContext& ctx) {
        ctx.setStatus("reading the dataset");
        const Dataset data(session->dataset, true, session->scene.contentHash());
        uint64_t dropped = 0;
        const std::vector<ObjectSamples> samples = samplesFromDataset(data, &dropped);
        if (dropped) {
            std::lock_guard<std::mutex> lock(session->mutex);
            session->messages.push_back(std::to_string(dropped) + " records with NaN/Inf dropped from the dataset");
        }
        const ObjectTrainingOptions& opt = session->settings.options;
        const double budget = double(samples.size()) * (opt.targets == TargetMode::Separate ? 2 : 1) * opt.trainer.maxEpochs();
        const auto start = std::chrono::steady_clock::now();
        ObjectTrainingObserver observer;
        observer.cancel = &ctx.cancelFlag();
        observer.onEpoch = [&, session](int object, const std::string& target, const EpochRecord& r) {
            std::lock_guard<std::mutex> lock(session->mutex);
            auto [it, added] = session->curveIndex.emplace(std::make_pair(object, target), session->curves.size());
            if (added) {
                LossCurve c;
                c.objectId = object;
                c.object = object >= 0 && object < int(session->scene.objects.size()) ? session->scene.objects[size_t(object)].name : "?";
                c.target = target;
                session->curves.push_back(std::move(c));
            }
            session->curves[it->second].points.push_back({r.epoch, r.trainLoss, r.validationLoss, r.seconds});
            session->epoch = std::max(session->epoch, r.epoch);
            session->step = r.step;
            session->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            ++session->epochsDone;
            ++session->revision;
            ctx.setProgress(std::min(1.0, double(session->epochsDone) / std::max(1.0, budget)));
        };
        observer.onMessage = [session](const std::string& m) {
            std::lock_guard<std::mutex> lock(session->mutex);
            session->messages.push_back(m);
        };
        ctx.setStatus("training");
        const std::vector<ObjectModel> trained = trainObjects(samples, opt, observer);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        int networks = 0, skipped = 0;
        for (const ObjectModel& m : trained) (m.skipped ? skipped : networks) += 1;
        if (networks > 0) {
            ctx.setStatus("saving the models");
            const json extra = {{"dataset", session->dataset}, {"network", session->settings.networkJson()},
                                {"trainer", session->settings.trainerJson()}, {"seconds", seconds},
                                {"cancelled", ctx.cancelled()}};
            saveModelSet(session->modelsDir, trained, session->scene.contentHash(),
                         data.header().at("input_layout").get<std::vector<std::string>>(), extra);
        }
        std::lock_guard<std::mutex> lock(session->mutex);
        session->saved = networks > 0;
        session->networks = networks;
        session->skipped = skipped;
        session->trainSeconds = seconds;
        ++session->revision;
        ctx.setStatus(networks > 0 ? "models saved" : "no network trained");
    }, &why);
    if (!id) {
        state_.log.error("train refused: " + why);
        return false;
    }
    train_ = session;
    trainJob_ = id;
    trainRevision_ = ~0ull;
    state_.training = panels::TrainingInfo{};
    state_.training.running = true;
    state_.training.trainer = o.trainer.typeName();
    state_.training.runId = session->runId;
    state_.focusTab = "Training";
    state_.log.info("train started: " + name + " on " + session->dataset);
    return true;
}

void Workbench::pollTrain() {
    state_.training.running = trainRunning();
    if (!train_) return;
    // The local keeps the session (and its mutex) alive while it is locked below and train_ is reset.
    const std::shared_ptr<TrainSession> session = train_;
    TrainSession& s = *session;
    std::vector<std::string> messages;
    {
        std::lock_guard<std::mutex> lock(s.mutex);
        messages.swap(s.messages);
        if (s.revision != trainRevision_) {
            trainRevision_ = s.revision;
            state_.training.curves = s.curves;
            state_.training.epoch = s.epoch;
            state_.training.step = s.step;
            state_.training.seconds = s.seconds;
        }
    }
    for (const std::string& m : messages) state_.log.info("train: " + m);
    for (const JobInfo& j : jobs_.jobs())
        if (j.id == trainJob_) state_.training.progress = j.progress;
    if (state_.training.running) return;

    std::lock_guard<std::mutex> lock(s.mutex);
    state_.training.progress = 1.0;
    if (!s.saved) {
        state_.log.error("train: no network was trained (see the messages above); nothing saved");
        train_.reset();
        return;
    }
    Run run;
    run.kind = "train";
    run.id = s.runId;
    run.name = s.runId;
    run.created = localTimestamp();
    auto rel = [&](const std::string& p) { return fs::path(p).lexically_relative(projectDir()).generic_string(); };
    run.settings = json{{"network", s.settings.networkJson()}, {"trainer", s.settings.trainerJson()},
                        {"dataset", rel(s.dataset)}, {"scene_hash", hexString(s.scene.contentHash())}};
    if (state_.project.sampling) run.settings["sampling"] = state_.project.sampling->toJson();
    run.curves = s.curves;
    run.loss = panels::aggregateLoss(s.curves);
    run.metrics = json{{"networks", s.networks}, {"skipped", s.skipped}, {"epochs", s.epoch}};
    run.timings = json{{"train", s.trainSeconds}};
    if (state_.dataset.path == s.dataset && state_.dataset.seconds > 0) run.timings["generate"] = state_.dataset.seconds;
    run.artifacts.push_back(rel((fs::path(s.modelsDir) / "models.json").string()));
    state_.project.runs.push_back(run);
    state_.markDirty();
    state_.log.info("trained " + std::to_string(s.networks) + " networks in " + std::to_string(int(s.trainSeconds + 0.5)) +
                    " s; models in " + rel(s.modelsDir) + ", run '" + run.name + "' recorded");
    const std::string dir = s.modelsDir;
    train_.reset();
    loadModels(dir);
}

}  // namespace rrf
