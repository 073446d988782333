#pragma once
/// Judging the models as a controller: the evaluation of the loaded models against the ground truth
/// shown (the Objects table, and the metrics it adds to the training run that made them), the
/// evaluation that follows a manual training, the comparison of two training runs side by side
/// (evaluation_pair.cpp), the Light region panel's light grid (evaluation_light_grid.cpp) and the Cost
/// panel's sweeps (evaluation_sweep.cpp). It owns those four job sessions and publishes
/// state.evaluation, state.runPair, state.lightRegion and state.cost. UI thread only.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "app/gui/controller_context.h"
#include "app/gui/job_session.h"
#include "app/gui/stored_evaluation_file.h"

namespace rrf {

class PredictionController;
struct EvaluationOutcome;
struct PairOutcome;
struct LightGridResult;
struct SweepOutcome;
struct SweepTiming;
struct RestoredSweeps;
struct SweepResult;

class EvaluationController {
public:
    /// `prediction`: the loaded models (what is judged) and their last CPU frame (reused).
    EvaluationController(ControllerContext& ctx, const PredictionController& prediction);
    ~EvaluationController();

    /// Compares the prediction with the ground truth per object and term (fills the Objects panel).
    /// `done`: told once when the job ended (delivered: an evaluation was made).
    bool startEvaluate(StageDone done = nullptr);
    bool evaluateRunning() const { return evaluateJob_.running(); }
    double evaluateProgress() const { return evaluateJob_.progress(); }
    void cancelEvaluate() { evaluateJob_.cancel(); }
    /// A manual training finished: evaluate its models once nothing they need is still on its way.
    void evaluateWhenReady() { evaluateAfterTrain_ = true; }
    /// True while a finished training's models wait to be evaluated.
    bool evaluationPending() const { return evaluateAfterTrain_; }
    /// Writes the Objects table (the views' term, the table's sort order) as CSV, atomically.
    bool exportObjectsCsv(const std::string& path);

    /// Predicts the models of training runs runPair.a and runPair.b at the current light (and judges
    /// each against the ground truth, when there is one) on a worker.
    bool compareRunPair();
    /// The Light region panel's evaluation of the loaded models over state.lightRegion.counts.
    bool startLightGrid();
    bool lightGridRunning() const { return lightGridJob_.running(); }
    void cancelLightGrid() { lightGridJob_.cancel(); }
    /// Runs a cost sweep of one of the kinds in kSweepKinds (core/pipeline/sweep.h) with interactive sizes.
    bool startSweep(const std::string& what);
    /// True while a sweep runs, or its GLSL frames are timed on a GL worker of its own.
    bool sweepRunning() const { return sweepJob_.running() || sweepTiming_ != nullptr; }
    void cancelSweep() { sweepJob_.cancel(); }
    /// The Objects table of the project's last evaluation (<project dir>/evaluation.json,
    /// app/gui/stored_evaluation_file.h) when it judged the models now loaded against the ground truth
    /// of the current scene, light and size: called when a project is opened, after its models.
    void restoreEvaluation();
    /// The Cost panel's series of the project's sweeps on disk (<project dir>/sweeps/*.json), as they
    /// were when they finished: called when a project is opened; read on a worker, shown when read.
    void restoreSweeps();

    /// Each frame, before the prediction's poll: takes a finished evaluation.
    void pollEvaluation();
    /// Each frame, after the prediction's poll (a CPU frame that has just ended is then delivered
    /// before the evaluation that waited for it looks for it): the evaluation after a training, the
    /// sweep, light grid and run-pair jobs.
    void pollAfterPrediction();
    /// Forgets every job (a project was closed): nothing they still produce arrives.
    void drop();

    /// True while the evaluation after a training must wait (the Workbench: the pipeline runs, the
    /// ground truth of the current light is still rendering, a CPU frame of the models is on its way).
    std::function<bool()> holdEvaluation;

private:
    /// Starts the evaluation a manual training asked for when its ground truth is ready, or says why
    /// it cannot be made (a notice on the Training panel).
    void pollEvaluateAfterTrain();
    void pollSweep();
    /// Times the GLSL predictor on each finished row's networks on a GL worker of its own (so that
    /// neither the UI nor the live prediction's worker waits for the compiles).
    void startSweepTiming(SweepOutcome out);
    /// Once every row is timed: the Cost panel's series and the sweep's files.
    void finishSweep();
    /// Forgets the timing of a finished sweep (its rows still being timed are skipped).
    void dropSweepTiming();
    void pollRestoredSweeps();
    void pollLightGrid();
    void pollRunPair();
    /// Adds `r`'s series to the Cost panel, named "sweep <what>" (" #n" for the n-th of a kind).
    void addSweepSeries(const SweepResult& r);
    std::string projectDir() const { return ctx_.projectDir(); }
    /// What an evaluation of the loaded models against a ground truth of width × height of the
    /// current scene with the light at `light` is made of (stored_evaluation_file.h).
    EvaluationSource evaluationSource(const Vec3& light, int width, int height) const;

    ControllerContext& ctx_;
    panels::WorkbenchState& state_;  ///< ctx_.state: what the controller publishes into
    const PredictionController& prediction_;
    JobSession<EvaluationOutcome> evaluateJob_;
    StageDone evaluateDone_;  ///< the pipeline's, while its evaluate stage runs
    bool evaluateAfterTrain_ = false;  ///< see evaluationPending()
    JobSession<PairOutcome> pairJob_;
    JobSession<LightGridResult> lightGridJob_;
    JobSession<SweepOutcome> sweepJob_;
    std::unique_ptr<SweepTiming> sweepTiming_;  ///< a finished sweep whose GLSL frames are being timed
    /// Dropped timings whose worker still finishes a row; destroyed once idle (pollSweep).
    std::vector<std::unique_ptr<SweepTiming>> retiredTimings_;
    JobSession<RestoredSweeps> restoreJob_;  ///< the project's sweeps read back when it was opened
};

}  // namespace rrf
