// EvaluationController (evaluation_controller.h): evaluation of the trained models against the ground
// truth shown in the views (core/eval/evaluation.h, CPU predictor, on a worker), the Objects table it
// fills, its CSV export, and the metrics it adds to the training run whose models it judged.
#include "app/gui/evaluation_controller.h"

#include "app/gui/cpu_frame.h"
#include "app/gui/prediction_controller.h"

#include <filesystem>

#include "core/util/atomic_file.h"
#include "core/util/stopwatch.h"
#include "core/eval/evaluation.h"
#include "core/render/renderer.h"
#include "core/pipeline/run_recording.h"
#include "panels/panels.h"

namespace rrf {

namespace fs = std::filesystem;

/// A finished evaluation: the Objects table, ready to show, and what the training run gets.
struct EvaluationOutcome {
    panels::EvaluationInfo info;
    ErrorStats global;         ///< the global term over all object pixels
    int width = 0, height = 0;  ///< the reference's size
    std::string modelsDir;     ///< the models that were judged
    EvaluationSource source;   ///< what was judged against what, as the job started (stored with it)
};

EvaluationController::EvaluationController(ControllerContext& ctx, const PredictionController& prediction)
    : ctx_(ctx),
      state_(ctx.state),
      prediction_(prediction),
      evaluateJob_(ctx.jobs, JobKind::Evaluate, ctx.state.log),
      pairJob_(ctx.jobs, JobKind::Compare, ctx.state.log),
      lightGridJob_(ctx.jobs, JobKind::LightGrid, ctx.state.log),
      sweepJob_(ctx.jobs, JobKind::Sweep, ctx.state.log),
      restoreJob_(ctx.jobs, JobKind::ReadBack, ctx.state.log) {}

// ~EvaluationController is in evaluation_sweep.cpp, where a sweep's GLSL timing is a complete type.

void EvaluationController::drop() {
    for (JobSessionBase* job :
         std::initializer_list<JobSessionBase*>{&evaluateJob_, &pairJob_, &lightGridJob_, &sweepJob_, &restoreJob_})
        job->drop();
    evaluateDone_ = nullptr;
    dropSweepTiming();
}

void EvaluationController::pollAfterPrediction() {
    pollEvaluateAfterTrain();
    pollSweep();
    pollRestoredSweeps();
    pollLightGrid();
    pollRunPair();
}

bool EvaluationController::startEvaluate(StageDone done) {
    if (!prediction_.live().loaded()) {
        state_.notify(panels::LogLevel::Error, "Training", "evaluate: no trained models; train first");
        return false;
    }
    if (state_.groundTruth.empty()) {
        state_.notify(panels::LogLevel::Error, "Training", "evaluate: no ground truth yet; render first");
        return false;
    }
    // The ground truth the views show may be of a light that has moved since (its render restarts):
    // an evaluation against it would report the wrong light's error.
    if (const auto& stamp = state_.groundTruth.stamp;
        stamp && (!(stamp->light == state_.project.scene.lightPosition()) ||
                  stamp->sceneHash != state_.project.scene.contentHash())) {
        state_.notify(panels::LogLevel::Error, "Training",
                      "evaluate: the ground truth shown is of another light or scene; wait for its render of this one");
        return false;
    }
    const PredictionSettings settings = state_.project.prediction;
    auto scene = std::make_shared<const Scene>(state_.project.scene);
    const std::shared_ptr<const ModelSet> models = prediction_.live().models();
    const std::string modelsDir = prediction_.live().dir();
    // The reference is the ground truth the views show, at the light position it was rendered at,
    // with the render's per-term variance of the mean (empty for a re-opened run's images: the
    // noise floors are then unknown, never 0). Image copies share nothing with the views, so the
    // worker reads them while the UI draws.
    auto reference = std::make_shared<Reference>();
    for (Term t : kTerms) {
        reference->images[int(t)] = state_.groundTruth.term(t);
        // Empty below 2 spp (pollRender keeps only a known variance): the floor is then unknown.
        reference->variances[int(t)] = state_.groundTruth.variance(t);
    }
    reference->lightPosition = state_.project.scene.lightPosition();
    reference->spp = state_.render.spp;
    reference->seconds = state_.render.seconds;
    // The CPU frame of these models at this light, scene and size already holds the prediction
    // (on a glossy scene, with its gather): its pixels are what predicting again would give.
    std::shared_ptr<const CpuFrame> frame = prediction_.lastCpuFrame();
    const Image& gt = state_.groundTruth.term(Term::Global);
    if (frame && !frame->matches(models, settings,
                                 panels::ImageStamp{reference->lightPosition, scene->contentHash(), gt.width, gt.height}))
        frame.reset();
    if (frame) state_.log.info("evaluate: reusing the CPU frame of these models (same light, scene and size)");
    // Keyed now: an edit while the job runs must not stamp this result as an evaluation of the new scene.
    EvaluationSource source = evaluationSource(reference->lightPosition, gt.width, gt.height);
    const bool started = evaluateJob_.start("evaluate", [scene, models, modelsDir, settings, reference, frame,
                                                         source = std::move(source)](JobContext& ctx) -> std::optional<EvaluationOutcome> {
        const Stopwatch clock;
        Evaluation e;
        if (frame) {
            e = evaluatePrediction(frame->gbuffer, frame->prediction, *reference);
            e.gbufferSeconds = frame->gbufferSeconds;
        } else {
            ctx.setStatus("predicting");
            const Predictor predictor(*scene, *models, settings);
            e = evaluate(predictor, *reference);
        }
        e.flip = flipEvaluation(e, *reference);
        EvaluationOutcome out;
        out.info = panels::evaluationInfo(e, *scene, *models);
        out.info.referenceSpp = reference->spp;
        out.info.seconds = clock.seconds();
        out.global = e.term(Term::Global).overall;
        out.width = reference->images[int(Term::Global)].width;
        out.height = reference->images[int(Term::Global)].height;
        out.modelsDir = modelsDir;
        out.source = source;
        ctx.setProgress(1.0);
        return out;
    });
    if (!started) return false;
    evaluateDone_ = std::move(done);
    state_.evaluation.running = true;
    return true;
}

void EvaluationController::pollEvaluateAfterTrain() {
    if (!evaluateAfterTrain_ || evaluateRunning()) return;
    // The pipeline evaluates as its own stage; a render of the current light still running (or
    // restarting after an edit) is waited for, its finished image being the reference the evaluation
    // needs; so is the CPU frame of the new models (a glossy gather, or no GLSL), which it reuses.
    if (holdEvaluation && holdEvaluation()) return;
    evaluateAfterTrain_ = false;
    const auto& stamp = state_.groundTruth.stamp;
    std::string why;
    if (!prediction_.live().loaded()) why = "no complete model set is loaded";
    else if (state_.groundTruth.empty() || state_.render.cancelled)
        why = "there is no finished ground truth of the current light (Render, then Evaluate)";
    else if (stamp && (!(stamp->light == state_.project.scene.lightPosition()) ||
                       stamp->sceneHash != state_.project.scene.contentHash()))
        why = "the ground truth shown is of another light or scene (Render, then Evaluate)";
    if (!why.empty()) {
        state_.notify(panels::LogLevel::Warning, "Training", "the trained models were not evaluated: " + why);
        return;
    }
    state_.log.info("evaluating the trained models against the ground truth of the current light");
    startEvaluate();
}

void EvaluationController::pollEvaluation() {
    state_.evaluation.running = evaluateRunning();
    bool delivered = false;
    const bool ended = evaluateJob_.poll([&](EvaluationOutcome& out) {
        delivered = true;
        const double seconds = out.info.seconds;
        const int spp = out.info.referenceSpp;
        const Vec3 light = out.info.lightPosition;
        state_.evaluation = std::move(out.info);
        state_.evaluation.modelsDir = out.modelsDir;
        state_.focusTab = "Objects";
        // The run that made these models gets the result, so the Cost panel can place it.
        const ErrorStats& g = out.global;
        EvaluationRecord record;
        record.global = g;
        record.referenceSpp = spp;
        record.lights = {light};
        record.width = out.width;
        record.height = out.height;
        record.seconds = seconds;
        if (recordEvaluation(state_.project.runs, projectDir(), out.modelsDir, record) > 0) state_.markDirty();
        // Kept beside a saved project, so that reopening it shows this table again; a failure
        // costs only that.
        if (ctx_.savedProject() && out.modelsDir == prediction_.live().dir()) {
            try {
                storeEvaluation((fs::path(projectDir()) / kEvaluationFile).string(), state_.evaluation, out.source);
            } catch (const std::exception& e) {
                state_.log.warning(std::string("the evaluation was not kept for the next opening: ") + e.what());
            }
        }
        char line[320];
        std::snprintf(line, sizeof line,
                      "evaluated: global term relative RMSE %.4g (noise floor %s, corrected (noise subtracted) %s), RMSE %.4g "
                      "over %llu pixels (%.1f s)",
                      g.relativeRmse, noiseFigureText(g.relativeRmseNoiseFloor).c_str(),
                      noiseFigureText(g.relativeRmseCorrected).c_str(), g.rmse, (unsigned long long)g.pixels, seconds);
        state_.log.info(line);
    });
    if (evaluateDone_ && ended) {
        const StageDone finished = std::move(evaluateDone_);
        evaluateDone_ = nullptr;
        finished(delivered);
    }
}

EvaluationSource EvaluationController::evaluationSource(const Vec3& light, int width, int height) const {
    EvaluationSource source;
    source.key = ReferenceKey::of(state_.project.scene, light, width, height, state_.project.render);
    source.models = projectRelative(projectDir(), prediction_.live().dir());
    if (const auto models = prediction_.live().models())
        source.modelsChecksum = models->indexChecksum;
    return source;
}

void EvaluationController::restoreEvaluation() {
    if (!ctx_.savedProject() || !prediction_.live().loaded()) return;
    // The evaluation's reference was the ground truth, rendered at the project's render size.
    const RenderOptions options = renderOptionsFor(state_.project.scene, state_.project.render, 1);
    const std::string file = (fs::path(projectDir()) / kEvaluationFile).string();
    StoredEvaluation stored = loadEvaluation(file, evaluationSource(state_.project.scene.lightPosition(), options.width, options.height));
    if (!stored.info) {
        if (stored.damaged) state_.log.warning(stored.why);
        else if (!stored.why.empty()) state_.log.info("the last evaluation is not shown: " + stored.why);
        return;
    }
    state_.evaluation = std::move(*stored.info);
    state_.evaluation.modelsDir = prediction_.live().dir();
    state_.log.info("restored the last evaluation (Objects table) from " + projectRelative(projectDir(), file));
}

bool EvaluationController::exportObjectsCsv(const std::string& path) {
    const panels::EvaluationInfo& e = state_.evaluation;
    if (!e.valid) {
        state_.notify(panels::LogLevel::Error, "Objects", "export table: evaluate first");
        return false;
    }
    const int t = int(state_.view.term);
    const auto rows = panels::sortedObjectRows(e.rows[t], state_.objectsView.sortColumn, state_.objectsView.ascending);
    try {
        writeFileAtomically(path, panels::objectRowsCsv(rows, termName(state_.view.term)));
    } catch (const std::exception& ex) {
        state_.notify(panels::LogLevel::Error, "Objects", std::string("export table: ") + ex.what());
        return false;
    }
    state_.notify(panels::LogLevel::Info, "", "per-object error table written to " + path);
    return true;
}

}  // namespace rrf
