// EvaluationController: two training runs compared side by side. A worker loads both runs' model sets, predicts
// each at the current light with the CPU predictor (the reference implementation: the two columns
// differ only by their models) and, when a ground truth is shown, judges each against it per object,
// so the Views show prediction A | prediction B | difference and the Objects panel both error columns.
#include "app/gui/evaluation_controller.h"

#include <filesystem>

#include "app/gui/render_session.h"
#include "core/eval/evaluation.h"
#include "core/nn/model_set.h"
#include "core/predict/predictor.h"
#include "core/pipeline/run_recording.h"
#include "panels/panels.h"
#include "panels/view_model.h"

namespace rrf {

namespace fs = std::filesystem;

/// What the comparison job delivers for each run.
struct PairSide {
    Prediction prediction;
    std::vector<int> withoutNetwork;
    panels::EvaluationInfo errors;  ///< valid = false without a ground truth
};

struct PairOutcome {
    PairSide a, b;
    std::string error;  ///< a model set that could not be loaded (then nothing else is set)
};

namespace {
/// The models of training run `name` in `dir` (its trainRunModelsDir), or an error naming the run.
std::shared_ptr<const ModelSet> runModels(const std::string& dir, const std::string& name, uint64_t sceneHash) {
    if (dir.empty()) throw std::runtime_error("run '" + name + "' lists no models");
    return std::make_shared<const ModelSet>(loadModelSet(dir, sceneHash));
}
}  // namespace

bool EvaluationController::compareRunPair() {
    const panels::RunPair& p = state_.runPair;
    const int n = int(state_.project.runs.size());
    if (p.a < 0 || p.b < 0 || p.a >= n || p.b >= n || p.a == p.b) {
        state_.notify(panels::LogLevel::Error, "Project", "compare runs: tick A and B on two different training runs");
        return false;
    }
    const Run& ra = state_.project.runs[size_t(p.a)];
    const Run& rb = state_.project.runs[size_t(p.b)];
    if (ra.kind != "train" || rb.kind != "train") {
        state_.notify(panels::LogLevel::Error, "Project", "compare runs: both runs must be training runs");
        return false;
    }
    // The model sets load on the worker (reading weights grows with the models); a missing or foreign
    // set comes back as the outcome's error, shown where the user clicked.
    const std::string dirA = trainRunModelsDir(ra, projectDir()), dirB = trainRunModelsDir(rb, projectDir());
    const std::string nameA = ra.name, nameB = rb.name;
    const uint64_t sceneHash = state_.project.scene.contentHash();
    auto scene = std::make_shared<const Scene>(state_.project.scene);
    const PredictionSettings settings = state_.project.prediction;
    const Camera camera = groundTruthCamera(state_.project.scene, state_.project.render);
    std::shared_ptr<Reference> reference;
    if (!state_.groundTruth.empty()) {
        reference = std::make_shared<Reference>();
        for (Term t : kTerms) {
            reference->images[int(t)] = state_.groundTruth.term(t);
            reference->variances[int(t)] = state_.groundTruth.variance(t);
        }
        reference->lightPosition = state_.project.scene.lightPosition();
        reference->spp = state_.render.spp;
    }
    const std::vector<int> ids = state_.objectIds;
    const bool started = pairJob_.start("compare runs", [=](JobContext& ctx) -> std::optional<PairOutcome> {
        PairOutcome out;
        auto side = [&](const ModelSet& models, PairSide& s) {
            const Predictor predictor(*scene, models, settings);
            if (reference && reference->images[0].width == camera.width && reference->images[0].height == camera.height) {
                const Evaluation e = evaluate(predictor, *reference);
                s.errors = panels::evaluationInfo(e, *scene, models);
                s.errors.referenceSpp = reference->spp;
                s.prediction = e.prediction;
            } else {
                s.prediction = predictor.predict(predictor.gbuffer(scene->lightPosition(), camera.width, camera.height));
            }
            s.withoutNetwork = panels::objectsWithoutNetwork(ids, models, settings);
        };
        std::shared_ptr<const ModelSet> ma, mb;
        try {
            ctx.setStatus("loading the models");
            ma = runModels(dirA, nameA, sceneHash);
            mb = runModels(dirB, nameB, sceneHash);
        } catch (const std::exception& e) {
            out.error = e.what();
            return out;
        }
        ctx.setStatus("run A");
        side(*ma, out.a);
        ctx.setProgress(0.5);
        if (ctx.cancelled()) return std::nullopt;
        ctx.setStatus("run B");
        side(*mb, out.b);
        ctx.setProgress(1.0);
        return out;
    });
    if (!started) return false;
    state_.runPair.running = true;
    state_.runPair.nameA = ra.name;
    state_.runPair.nameB = rb.name;
    state_.log.info("comparing runs '" + ra.name + "' (A) and '" + rb.name + "' (B)");
    return true;
}

void EvaluationController::pollRunPair() {
    state_.runPair.running = pairJob_.running();
    pairJob_.poll([&](PairOutcome& out) {
        if (!out.error.empty()) {
            state_.notify(panels::LogLevel::Error, "Project", "compare runs: " + out.error);
            return;
        }
        panels::RunPair& p = state_.runPair;
        auto publish = [](PairSide& s, panels::ImageSet& images, panels::EvaluationInfo& errors, const std::string& label) {
            for (Term t : kTerms) images.term(t) = std::move(s.prediction.images[int(t)]);
            images.withoutNetwork = std::move(s.withoutNetwork);
            images.label = label;
            images.touch();
            errors = std::move(s.errors);
        };
        publish(out.a, p.imagesA, p.errorsA, "run '" + p.nameA + "' (CPU prediction)");
        publish(out.b, p.imagesB, p.errorsB, "B: run '" + p.nameB + "' (CPU prediction)");
        state_.view.compareSource = panels::CompareSource::RunPair;
        state_.focusTab = "Views";
    });
}

}  // namespace rrf
