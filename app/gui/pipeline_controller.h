#pragma once
/// The one-click pipeline (render → generate → train → evaluate) as a controller: it starts each
/// stage through the start function of the controller that owns the stage's job, hears how the job
/// ended through that start function's StageDone callback, and publishes one progress display in
/// state.pipeline (panels::PipelineInfo). It owns no job of its own: the jobs stay the ones the
/// panels' own buttons start. UI thread only.

#include <array>
#include <chrono>
#include <functional>
#include <optional>
#include <string>

#include "app/gui/controller_context.h"

namespace rrf {

class PipelineController {
public:
    /// The stages in order; their index is PipelineInfo::stageIndex.
    enum class Stage { Render, Generate, Train, Evaluate };
    static constexpr int kStages = 4;

    /// One stage as the controller that owns its job offers it to the pipeline.
    struct StageHooks {
        /// Starts (or, for a render already running, joins) the stage's job. False when refused (the
        /// owner said why); otherwise `done` is called once, from the owner's poll, when the job ended.
        std::function<bool(StageDone done)> start;
        /// Fraction done of the stage's running job.
        std::function<double()> progress;
        /// Stops the stage's job (it ends within a second and then calls `done` with false).
        std::function<void()> cancel;
        /// True when the stage's result is on hand already and the pipeline may skip it (the
        /// ground truth of the current scene, converged); null: never skipped.
        std::function<bool()> finished;
        /// False while what the stage needs from the one before is still on its way to the UI
        /// (the evaluation: the trained models wait for their GL upload); the pipeline starts the
        /// stage once it is true. Null: always ready.
        std::function<bool()> ready;
    };

    PipelineController(ControllerContext& ctx, std::array<StageHooks, kStages> stages);

    /// Applies `preset` (core/pipeline/presets.h; "" applies nothing) to the project's data and
    /// network settings and runs the pipeline. Refused (false, with a notice) without a saved project,
    /// while it runs or while a generation, training or evaluation runs.
    bool start(const std::string& preset);
    /// The pipeline with the settings in effect; `label` names them in its display and log.
    bool run(const std::string& label);
    /// Stops the running stage's job and the stages after it.
    void cancel();
    /// The project was closed under it: it ends at once, as stopped with `why`, and forgets its stage.
    void abandon(const std::string& why);
    bool running() const { return stage_.has_value(); }
    /// Each frame, after the stage owners' polls: moves to the next stage once the current one
    /// delivered, ends on a stage that did not, and publishes the overall fraction and ETA.
    void poll();
    /// The published display (also state.pipeline, which the pipeline bar draws).
    const panels::PipelineInfo& info() const { return ctx_.state.pipeline; }

private:
    /// Why the pipeline cannot start now ("" when it can).
    std::string refusal() const;
    /// Starts `stage`; false (the pipeline ends saying so) when its owner refused.
    bool begin(Stage stage);
    void end(const std::string& outcome);

    ControllerContext& ctx_;
    std::array<StageHooks, kStages> stages_;
    std::optional<Stage> stage_;         ///< the running stage; none while idle
    /// How the running stage's job ended (set by its StageDone); none while it runs.
    std::optional<bool> delivered_;
    /// Counts begun stages: a StageDone of an earlier stage (or run) is ignored.
    uint64_t token_ = 0;
    double weights_[kStages] = {0, 0, 0, 0};  ///< estimated seconds per stage
    double spent_[kStages] = {0, 0, 0, 0};    ///< measured seconds of the stages done (0: skipped)
    std::chrono::steady_clock::time_point start_, stageStart_;
    bool cancelled_ = false;
    std::string label_;
};

}  // namespace rrf
