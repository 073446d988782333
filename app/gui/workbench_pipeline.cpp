// Workbench: the one-click pipeline. It chains the jobs the panels' own buttons start (render,
// generate, train, evaluate: workbench_render/data/train/evaluate.cpp), advancing when a stage's job
// delivered its result, and publishes one progress display in state().pipeline:
//  - overall fraction: the stages weighted by their estimates (core/pipeline/time_estimate.h; the
//    geometric middle of each estimate's range), the current one by its job's progress;
//  - ETA: the current stage's time left (extrapolated from its progress once it has some) plus the
//    later stages' estimates scaled by how the finished stages compared with theirs.
#include "app/gui/workbench.h"

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

std::string Workbench::pipelineRefusal() const {
    if (!state_.hasProject) return "no project is open";
    if (untitled_ || state_.project.path.empty()) return "save the project first (models are stored next to it)";
    if (pipelineRunning()) return "it is running already";
    // The render the project started on opening is the pipeline's first stage; a generation, training
    // or evaluation already running is one of its stages (the user decides what to stop).
    for (const JobInfo& j : jobs_.jobs())
        if (j.kind == JobKind::Generate || j.kind == JobKind::Train || j.kind == JobKind::Evaluate)
            return std::string("a ") + jobKindName(j.kind) + " job is running";
    return {};
}

bool Workbench::startPipeline(const std::string& presetName) {
    // "" is the bar's default: the project's settings as the panels show them, nothing applied.
    if (presetName.empty()) return runPipeline(panels::pipelineChoiceLabel(presetName));
    const PipelinePreset* preset = findPreset(presetName);
    const std::string why = preset ? pipelineRefusal() : "unknown preset '" + presetName + "' (" + presetNames(", ") + ")";
    if (!why.empty()) {
        state_.notify(panels::LogLevel::Error, "", "pipeline: " + why);
        return false;
    }
    applySamplingPreset(state_.project, *preset);
    applyNetworkPreset(state_.project, *preset);
    state_.markDirty();
    return runPipeline(preset->name);
}

bool Workbench::runPipeline(const std::string& label) {
    const std::string why = pipelineRefusal();
    if (!why.empty()) {
        state_.notify(panels::LogLevel::Error, "", "pipeline: " + why);
        return false;
    }
    // Estimates of the settings in effect: a preset applied changes nothing (quick, paper and best
    // are idempotent), so the current settings stand for every preset here.
    const std::vector<StageEstimate> estimates = panels::pipelineEstimates(state_, nullptr);
    pipeline_ = PipelineRun{};
    for (size_t i = 0; i < 4; ++i) pipeline_.weights[i] = std::max(0.1, std::sqrt(estimates[i].low * estimates[i].high));
    pipeline_.start = std::chrono::steady_clock::now();
    pipeline_.preset = label;
    state_.pipeline.preset = label;
    state_.pipeline.running = true;
    state_.pipeline.outcome.clear();
    state_.log.info("pipeline started (" + label + ", expect " + panels::pipelineExpectation(state_, "", false) + "; estimated render " + rangeText(estimates[0]) + ", generate " +
                    rangeText(estimates[1]) + ", train " + rangeText(estimates[2]) + ", evaluate " + rangeText(estimates[3]) + ")");
    // A finished ground truth of the current scene is kept: the pipeline starts with the data then.
    const bool groundTruthDone = !renderRunning() && !state_.groundTruth.empty() && !state_.render.cancelled &&
                                 state_.render.spp >= state_.render.targetSpp && state_.render.targetSpp > 0;
    if (groundTruthDone) return beginPipelineStage(PipelineStage::Generate);
    return beginPipelineStage(PipelineStage::Render);
}

bool Workbench::beginPipelineStage(PipelineStage stage) {
    if (pipeline_.stage != PipelineStage::Idle && pipeline_.stage != stage)
        pipeline_.spent[int(pipeline_.stage) - 1] = secondsSince(pipeline_.stageStart);
    pipeline_.stage = stage;
    pipeline_.stageStart = std::chrono::steady_clock::now();
    bool started = true;
    switch (stage) {
        case PipelineStage::Render:
            pipeline_.mark = 0;
            started = renderRunning() || startRender();
            break;
        case PipelineStage::Generate:
            pipeline_.mark = datasetsDelivered_;
            started = startGenerate();
            break;
        case PipelineStage::Train:
            pipeline_.mark = trainingsCompleted_;
            started = startTrain();
            break;
        case PipelineStage::Evaluate:
            pipeline_.mark = evaluationsDelivered_;
            started = startEvaluate();
            break;
        case PipelineStage::Idle: break;
    }
    state_.pipeline.stage = kStageNames[int(stage) - 1];
    state_.pipeline.stageIndex = int(stage) - 1;
    if (!started) endPipeline(std::string("failed: the ") + kStageNames[int(stage) - 1] + " stage could not start (see the Log)");
    return started;
}

void Workbench::cancelPipeline() {
    if (!pipelineRunning()) return;
    pipeline_.cancelled = true;
    switch (pipeline_.stage) {
        case PipelineStage::Render: cancelRender(); break;
        case PipelineStage::Generate: generateJob_.cancel(); break;
        case PipelineStage::Train: trainJob_.cancel(); break;
        case PipelineStage::Evaluate: evaluateJob_.cancel(); break;
        case PipelineStage::Idle: break;
    }
}

void Workbench::endPipeline(const std::string& outcome) {
    pipeline_.stage = PipelineStage::Idle;
    state_.pipeline.running = false;
    state_.pipeline.seconds = secondsSince(pipeline_.start);
    state_.pipeline.etaSeconds = -1;
    state_.pipeline.outcome = outcome;
    const std::string line = "pipeline (" + pipeline_.preset + ") " + outcome;
    if (outcome.rfind("done", 0) == 0) state_.log.info(line);
    else if (pipeline_.cancelled) state_.log.warning(line);
    else state_.notify(panels::LogLevel::Error, "", line);
}

void Workbench::pollPipeline() {
    if (!pipelineRunning()) return;
    PipelineRun& p = pipeline_;
    const int index = int(p.stage) - 1;
    bool running = false, delivered = false;
    double progress = 0;
    switch (p.stage) {
        case PipelineStage::Render:
            running = renderRunning() || restartRender_;
            progress = state_.render.targetSpp > 0 ? double(state_.render.spp) / state_.render.targetSpp : 0.0;
            delivered = !state_.groundTruth.empty() && !state_.render.cancelled && state_.render.spp >= state_.render.targetSpp;
            break;
        case PipelineStage::Generate:
            running = generateRunning();
            progress = generateJob_.progress();
            delivered = datasetsDelivered_ > p.mark;
            break;
        case PipelineStage::Train:
            running = trainRunning();
            progress = trainJob_.progress();
            delivered = trainingsCompleted_ > p.mark;
            break;
        case PipelineStage::Evaluate:
            running = evaluateRunning();
            progress = evaluateJob_.progress();
            delivered = evaluationsDelivered_ > p.mark;
            break;
        case PipelineStage::Idle: return;
    }
    if (!running) {
        if (p.cancelled) {
            endPipeline(std::string("stopped in the ") + kStageNames[index] + " stage after " +
                        durationText(secondsSince(p.start)));
            return;
        }
        if (!delivered) {
            endPipeline(std::string("failed: the ") + kStageNames[index] + " stage ended without a result (see the Log)");
            return;
        }
        if (p.stage == PipelineStage::Evaluate) {
            p.spent[index] = secondsSince(p.stageStart);
            const Run* run = state_.project.runs.empty() ? nullptr : &state_.project.runs.back();
            endPipeline("done in " + durationText(secondsSince(p.start)) + (run ? "; run '" + run->name + "'" : std::string()));
            return;
        }
        beginPipelineStage(PipelineStage(int(p.stage) + 1));
        return;
    }
    // Overall fraction and ETA (see the top of this file).
    double total = 0, done = 0, estimatedDone = 0, spentDone = 0;
    for (int i = 0; i < 4; ++i) total += p.weights[i];
    for (int i = 0; i < index; ++i) {
        done += p.weights[i];
        if (p.spent[i] > 0) {
            estimatedDone += p.weights[i];
            spentDone += p.spent[i];
        }
    }
    progress = std::clamp(progress, 0.0, 1.0);
    const double scale = estimatedDone > 0 ? std::clamp(spentDone / estimatedDone, 0.1, 10.0) : 1.0;
    const double inStage = secondsSince(p.stageStart);
    const double stageLeft = progress > 0.05 ? inStage * (1 - progress) / progress : p.weights[index] * scale * (1 - progress);
    double later = 0;
    for (int i = index + 1; i < 4; ++i) later += p.weights[i] * scale;
    state_.pipeline.fraction = total > 0 ? (done + progress * p.weights[index]) / total : 0.0;
    state_.pipeline.etaSeconds = stageLeft + later;
    state_.pipeline.seconds = secondsSince(p.start);
}

}  // namespace rrf
