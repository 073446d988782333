// Workbench: evaluation of the trained models against the ground truth shown in the views
// (core/eval/evaluation.h, CPU predictor, on a worker), the Objects table it fills, its CSV export, and
// the metrics it adds to the training run whose models it judged.
#include "app/gui/workbench.h"

#include <filesystem>
#include <map>

#include "core/util/atomic_file.h"
#include "core/util/stopwatch.h"
#include "core/eval/evaluation.h"
#include "core/project/run_recording.h"
#include "panels/panels.h"

namespace rrf {

namespace fs = std::filesystem;
using nlohmann::json;

/// A finished evaluation: the Objects table, ready to show, and what the training run gets.
struct EvaluationOutcome {
    panels::EvaluationInfo info;
    ErrorStats global;         ///< the global term over all object pixels
    std::string modelsDir;     ///< the models that were judged
};

namespace {
/// The Objects table of `e`: per term, one row per object in view or trained, with the samples and
/// training time from the models' own training records.
panels::EvaluationInfo objectsTable(const Evaluation& e, const Scene& scene, const ModelSet& models) {
    panels::EvaluationInfo info;
    info.valid = true;
    info.lightPosition = e.lightPosition;
    std::map<int, std::pair<uint64_t, double>> training;
    for (const ObjectNetworks& o : models.objects)
        for (const auto& [target, m] : o.byTarget) {
            auto& t = training[o.objectId];
            uint64_t records = 0;  // a partitioned model's leaves share out the object's records
            for (const NetworkModel& leaf : m.leaves) {
                const TrainResult& r = leaf.training;
                records += uint64_t(r.trainSamples + r.validationSamples + r.testSamples);
                t.second += r.seconds;
            }
            t.first = std::max<uint64_t>(t.first, records);
        }
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
    return info;
}
}  // namespace

bool Workbench::evaluateRunning() const { return evaluateJob_.running(); }

bool Workbench::startEvaluate() {
    if (!live_.loaded()) {
        state_.log.error("evaluate: no trained models; train first");
        return false;
    }
    if (state_.groundTruth.empty()) {
        state_.log.error("evaluate: no ground truth yet; render first");
        return false;
    }
    const PredictionSettings settings = state_.project.prediction;
    auto scene = std::make_shared<const Scene>(state_.project.scene);
    const std::shared_ptr<const ModelSet> models = live_.models();
    const std::string modelsDir = live_.dir();
    // The reference is the ground truth the views show, at the light position it was rendered at.
    // Image copies share nothing with the views, so the worker reads them while the UI draws.
    auto reference = std::make_shared<Reference>();
    for (Term t : kTerms) reference->images[int(t)] = state_.groundTruth.term(t);
    reference->lightPosition = state_.project.scene.lightPosition();
    reference->spp = state_.render.spp;
    reference->seconds = state_.render.seconds;
    const bool started = evaluateJob_.start("evaluate", [scene, models, modelsDir, settings, reference](JobContext& ctx)
                                                            -> std::optional<EvaluationOutcome> {
        const Stopwatch clock;
        ctx.setStatus("predicting");
        const Predictor predictor(*scene, *models, settings);
        const Evaluation e = evaluate(predictor, *reference);
        EvaluationOutcome out;
        out.info = objectsTable(e, *scene, *models);
        out.info.referenceSpp = reference->spp;
        out.info.seconds = clock.seconds();
        out.global = e.term(Term::Global).overall;
        out.modelsDir = modelsDir;
        ctx.setProgress(1.0);
        return out;
    });
    if (!started) return false;
    state_.evaluation.running = true;
    return true;
}

void Workbench::pollEvaluate() {
    state_.evaluation.running = evaluateRunning();
    evaluateJob_.poll([&](EvaluationOutcome& out) {
        const double seconds = out.info.seconds;
        const int spp = out.info.referenceSpp;
        const Vec3 light = out.info.lightPosition;
        state_.evaluation = std::move(out.info);
        state_.focusTab = "Objects";
        // The run that made these models gets the result, so the Cost panel can place it.
        const ErrorStats& g = out.global;
        EvaluationRecord record;
        record.global = g;
        record.referenceSpp = spp;
        record.lights = {light};
        record.seconds = seconds;
        if (recordEvaluation(state_.project.runs, projectDir(), out.modelsDir, record) > 0) state_.markDirty();
        char line[160];
        std::snprintf(line, sizeof line, "evaluated: global term relative RMSE %.4g, RMSE %.4g over %llu pixels (%.1f s)",
                      g.relativeRmse, g.rmse, (unsigned long long)g.pixels, seconds);
        state_.log.info(line);
    });
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
