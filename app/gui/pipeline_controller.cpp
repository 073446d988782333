// The one-click pipeline (pipeline_controller.h). It chains the jobs the panels' own buttons start
// (render, generate, train, evaluate), each through its owner's start function, advancing when that
// job's StageDone says it delivered, and publishes one progress display in state.pipeline:
//  - overall fraction: the stages weighted by their estimates (core/pipeline/time_estimate.h; the
//    geometric middle of each estimate's range), the current one by its job's progress;
//  - ETA: the current stage's time left (extrapolated from its progress once it has some) plus the
//    later stages' estimates scaled by how the finished stages compared with theirs.
#include "app/gui/pipeline_controller.h"

#include <algorithm>
#include <cmath>

#include "core/pipeline/presets.h"
#include "panels/pipeline_controls.h"

namespace rrf {

namespace {
const char* const kStageNames[] = {"render", "generate", "train", "evaluate"};

double secondsSince(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}
}  // namespace

PipelineController::PipelineController(ControllerContext& ctx, std::array<StageHooks, kStages> stages)
    : ctx_(ctx), stages_(std::move(stages)) {}

std::string PipelineController::refusal() const {
    const panels::WorkbenchState& state = ctx_.state;
    if (!state.hasProject) return "no project is open";
    if (!ctx_.savedProject()) return "save the project first (models are stored next to it)";
    if (running()) return "it is running already";
    // The render the project started on opening is the pipeline's first stage; a generation, training
    // or evaluation already running is one of its stages (the user decides what to stop).
    for (const JobInfo& j : ctx_.jobs.jobs())
        if (j.kind == JobKind::Generate || j.kind == JobKind::Train || j.kind == JobKind::Evaluate)
            return std::string("a ") + jobKindName(j.kind) + " job is running";
    return {};
}

bool PipelineController::start(const std::string& presetName) {
    panels::WorkbenchState& state = ctx_.state;
    // "" is the bar's default: the project's settings as the panels show them, nothing applied.
    if (presetName.empty()) return run(panels::pipelineChoiceLabel(presetName));
    const PipelinePreset* preset = findPreset(presetName);
    const std::string why = preset ? refusal() : "unknown preset '" + presetName + "' (" + presetNames(", ") + ")";
    if (!why.empty()) {
        state.notify(panels::LogLevel::Error, "", "pipeline: " + why);
        return false;
    }
    applySamplingPreset(state.project, *preset);
    applyNetworkPreset(state.project, *preset);
    state.markDirty();
    return run(preset->name);
}

bool PipelineController::run(const std::string& label) {
    panels::WorkbenchState& state = ctx_.state;
    const std::string why = refusal();
    if (!why.empty()) {
        state.notify(panels::LogLevel::Error, "", "pipeline: " + why);
        return false;
    }
    // Estimates of the settings in effect: a preset applied changes nothing (quick, paper and best
    // are idempotent), so the current settings stand for every preset here.
    const std::vector<StageEstimate> estimates = panels::pipelineEstimates(panels::estimateInputs(state), nullptr);
    for (int i = 0; i < kStages; ++i) {
        weights_[i] = std::max(0.1, std::sqrt(estimates[size_t(i)].low * estimates[size_t(i)].high));
        spent_[i] = 0;
    }
    stage_.reset();
    cancelled_ = false;
    start_ = std::chrono::steady_clock::now();
    label_ = label;
    state.pipeline.preset = label;
    state.pipeline.running = true;
    state.pipeline.outcome.clear();
    state.log.info("pipeline started (" + label + ", expect " + panels::pipelineExpectation(state.project, "", false) + "; estimated render " + rangeText(estimates[0]) + ", generate " +
                   rangeText(estimates[1]) + ", train " + rangeText(estimates[2]) + ", evaluate " + rangeText(estimates[3]) + ")");
    // A finished ground truth of the current scene is kept: the pipeline starts with the data then.
    const StageHooks& render = stages_[int(Stage::Render)];
    if (render.finished && render.finished()) return begin(Stage::Generate);
    return begin(Stage::Render);
}

bool PipelineController::begin(Stage stage) {
    if (stage_ && *stage_ != stage) spent_[int(*stage_)] = secondsSince(stageStart_);
    const int index = int(stage);
    stage_ = stage;
    delivered_.reset();
    stageStart_ = std::chrono::steady_clock::now();
    const uint64_t token = ++token_;
    const bool started = stages_[index].start([this, token](bool delivered) {
        if (token == token_ && stage_) delivered_ = delivered;
    });
    ctx_.state.pipeline.stage = kStageNames[index];
    ctx_.state.pipeline.stageIndex = index;
    if (!started) end(std::string("failed: the ") + kStageNames[index] + " stage could not start (see the Log)");
    return started;
}

void PipelineController::cancel() {
    if (!running()) return;
    cancelled_ = true;
    stages_[int(*stage_)].cancel();
}

void PipelineController::abandon(const std::string& why) {
    if (!running()) return;
    cancelled_ = true;
    end(why);
}

void PipelineController::end(const std::string& outcome) {
    stage_.reset();
    ++token_;  // whatever the stage's job still reports is no longer the pipeline's
    panels::PipelineInfo& info = ctx_.state.pipeline;
    info.running = false;
    info.seconds = secondsSince(start_);
    info.etaSeconds = -1;
    info.outcome = outcome;
    const std::string line = "pipeline (" + label_ + ") " + outcome;
    if (outcome.rfind("done", 0) == 0) ctx_.state.log.info(line);
    else if (cancelled_) ctx_.state.log.warning(line);
    else ctx_.state.notify(panels::LogLevel::Error, "", line);
}

void PipelineController::poll() {
    if (!running()) return;
    const int index = int(*stage_);
    if (delivered_) {
        if (cancelled_) {
            end(std::string("stopped in the ") + kStageNames[index] + " stage after " + durationText(secondsSince(start_)));
            return;
        }
        if (!*delivered_) {
            end(std::string("failed: the ") + kStageNames[index] + " stage ended without a result (see the Log)");
            return;
        }
        if (*stage_ == Stage::Evaluate) {
            spent_[index] = secondsSince(stageStart_);
            const std::vector<Run>& runs = ctx_.state.project.runs;
            const Run* run = runs.empty() ? nullptr : &runs.back();
            end("done in " + durationText(secondsSince(start_)) + (run ? "; run '" + run->name + "'" : std::string()));
            return;
        }
        const StageHooks& next = stages_[index + 1];
        if (next.ready && !next.ready()) return;  // asked again next frame
        begin(Stage(index + 1));
        return;
    }
    // Overall fraction and ETA (see the top of this file).
    double total = 0, done = 0, estimatedDone = 0, spentDone = 0;
    for (int i = 0; i < kStages; ++i) total += weights_[i];
    for (int i = 0; i < index; ++i) {
        done += weights_[i];
        if (spent_[i] > 0) {
            estimatedDone += weights_[i];
            spentDone += spent_[i];
        }
    }
    const double progress = std::clamp(stages_[index].progress(), 0.0, 1.0);
    const double scale = estimatedDone > 0 ? std::clamp(spentDone / estimatedDone, 0.1, 10.0) : 1.0;
    const double inStage = secondsSince(stageStart_);
    const double stageLeft = progress > 0.05 ? inStage * (1 - progress) / progress : weights_[index] * scale * (1 - progress);
    double later = 0;
    for (int i = index + 1; i < kStages; ++i) later += weights_[i] * scale;
    panels::PipelineInfo& info = ctx_.state.pipeline;
    info.fraction = total > 0 ? (done + progress * weights_[index]) / total : 0.0;
    info.etaSeconds = stageLeft + later;
    info.seconds = secondsSince(start_);
}

}  // namespace rrf
