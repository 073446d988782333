// Workbench: evaluation of the trained models against the ground truth shown in the views
// (core/eval/evaluation.h, CPU predictor, on a worker), the Objects table it fills, its CSV export, and
// the metrics it adds to the training run whose models it judged.
#include "app/gui/workbench.h"

#include <filesystem>
#include <mutex>

#include "core/util/atomic_file.h"
#include "core/eval/evaluation.h"
#include "panels/panels.h"

namespace rrf {

namespace fs = std::filesystem;
using nlohmann::json;

/// Shared between the evaluate job and the UI thread.
struct EvaluateSession {
    Scene scene;
    std::shared_ptr<const ModelSet> models;
    PredictionSettings settings;
    Reference reference;
    std::string modelsDir;
    std::mutex mutex;
    bool done = false;
    Evaluation result;
    double seconds = 0;
};

bool Workbench::evaluateRunning() const { return evaluateJob_ != 0 && jobs_.running(JobKind::Evaluate); }

bool Workbench::startEvaluate() {
    if (!live_.loaded()) {
        state_.log.error("evaluate: no trained models; train first");
        return false;
    }
    if (state_.groundTruth.empty()) {
        state_.log.error("evaluate: no ground truth yet; render first");
        return false;
    }
    auto session = std::make_shared<EvaluateSession>();
    session->scene = state_.project.scene;
    session->models = live_.models();
    session->modelsDir = live_.dir();
    try {
        session->settings = state_.project.prediction;
    } catch (const std::exception& e) {
        state_.log.error(std::string("evaluate: ") + e.what());
        return false;
    }
    // The reference is the ground truth the views show, at the light position it was rendered at.
    Reference& ref = session->reference;
    for (Term t : kTerms) ref.images[int(t)] = state_.groundTruth.term(t);
    ref.lightPosition = state_.project.scene.lightPosition();
    ref.spp = state_.render.spp;
    ref.seconds = state_.render.seconds;
    std::string why;
    const int id = jobs_.start(JobKind::Evaluate, "evaluate", [session](JobContext& ctx) {
        const auto start = std::chrono::steady_clock::now();
        ctx.setStatus("predicting");
        const Predictor predictor(session->scene, *session->models, session->settings);
        Evaluation e = evaluate(predictor, session->reference);
        ctx.setProgress(1.0);
        std::lock_guard<std::mutex> lock(session->mutex);
        session->result = std::move(e);
        session->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        session->done = true;
    }, &why);
    if (!id) {
        state_.log.error("evaluate refused: " + why);
        return false;
    }
    evaluate_ = session;
    evaluateJob_ = id;
    state_.evaluation.running = true;
    return true;
}

void Workbench::pollEvaluate() {
    state_.evaluation.running = evaluateRunning();
    if (!evaluate_ || state_.evaluation.running) return;
    // The local keeps the session (and its mutex) alive until the lock is released below.
    const std::shared_ptr<EvaluateSession> session = evaluate_;
    std::lock_guard<std::mutex> lock(session->mutex);
    if (!evaluate_->done) {
        evaluate_.reset();
        return;
    }
    const Evaluation& e = evaluate_->result;
    panels::EvaluationInfo info;
    info.valid = true;
    info.lightPosition = e.lightPosition;
    info.referenceSpp = evaluate_->reference.spp;
    info.seconds = evaluate_->seconds;
    // Samples and training time per object, from the models' own training records.
    std::map<int, std::pair<uint64_t, double>> training;
    for (const ObjectNetworks& o : evaluate_->models->objects)
        for (const auto& [target, m] : o.byTarget) {
            auto& t = training[o.objectId];
            const TrainResult& r = m.training;
            t.first = std::max<uint64_t>(t.first, uint64_t(r.trainSamples + r.validationSamples + r.testSamples));
            t.second += r.seconds;
        }
    const Scene& scene = evaluate_->scene;
    for (Term t : kTerms) {
        const TermErrors& te = e.term(t);
        info.available[int(t)] = te.available;
        info.overall[int(t)] = te.overall;
        for (size_t id = 0; id < te.perObject.size() && id < scene.objects.size(); ++id) {
            if (te.perObject[id].pixels == 0 && !training.count(int(id))) continue;  // out of view, untrained
            panels::ObjectErrorRow row;
            row.objectId = int(id);
            row.name = scene.objects[id].name;
            row.stats = te.perObject[id];
            if (training.count(int(id))) row.samples = training[int(id)].first, row.trainSeconds = training[int(id)].second;
            info.rows[int(t)].push_back(row);
        }
    }
    state_.evaluation = std::move(info);
    state_.focusTab = "Objects";

    // The run that made these models gets the result, so the Cost panel can place it.
    const ErrorStats& g = e.term(Term::Global).overall;
    for (Run& r : state_.project.runs) {
        if (r.kind != "train" || r.artifacts.empty()) continue;
        if (fs::path(projectDir()) / fs::path(r.artifacts.front()).parent_path() != fs::path(evaluate_->modelsDir)) continue;
        r.metrics["relative_rmse"] = g.relativeRmse;
        r.metrics["rmse"] = g.rmse;
        r.metrics["mae"] = g.mae;
        r.metrics["evaluated_spp"] = evaluate_->reference.spp;
        r.metrics["evaluated_light"] = json::array({e.lightPosition.x, e.lightPosition.y, e.lightPosition.z});
        r.timings["evaluate"] = evaluate_->seconds;
        state_.markDirty();
    }
    char line[160];
    std::snprintf(line, sizeof line, "evaluated: global term relative RMSE %.4g, RMSE %.4g over %llu pixels (%.1f s)",
                  g.relativeRmse, g.rmse, (unsigned long long)g.pixels, evaluate_->seconds);
    state_.log.info(line);
    evaluate_.reset();
}

bool Workbench::exportObjectsCsv(const std::string& path) {
    const panels::EvaluationInfo& e = state_.evaluation;
    if (!e.valid) {
        state_.log.error("export table: evaluate first");
        return false;
    }
    const int t = int(state_.view.term);
    const auto rows = panels::sortedObjectRows(e.rows[t], state_.objectsView.sortColumn, state_.objectsView.ascending);
    try {
        writeFileAtomically(path, panels::objectRowsCsv(rows, termName(state_.view.term)));
    } catch (const std::exception& ex) {
        state_.log.error(std::string("export table: ") + ex.what());
        return false;
    }
    state_.log.info("per-object error table written to " + path);
    return true;
}

}  // namespace rrf
