#pragma once
/// Presets and the one-click pipeline in the workbench: the preset choices of the Sampling and
/// Network panels (each with its estimated time and the estimate's basis), and the pipeline bar
/// (preset, Run / Stop, one progress display: overall fraction, current stage, ETA). The presets
/// and estimates are core's (core/pipeline/presets.h, core/pipeline/time_estimate.h); these functions
/// only choose and show them, and ask the application to run the pipeline with a Request.

#include "core/pipeline/presets.h"
#include "core/pipeline/time_estimate.h"
#include "panels/panel_views.h"

namespace rrf::panels {

/// The path-sample rate estimates use: the last render's samples/s, else the reference machine's
/// per-thread rate times this machine's threads.
PathRate pathRateOf(const RenderProgress& render);
/// Records per generated ray measured by the last dataset of this scene (records ÷ (cells ×
/// directions)); 1 (the upper bound) when there is none.
double recordsPerRayOf(const DatasetInfo& dataset);
/// Data time of `s` for the open project.
StageEstimate dataEstimate(const EstimateInputs& in, const SamplingSettings& s);
/// Training time of `o` on the data `s` makes, for the open project.
StageEstimate trainingEstimate(const EstimateInputs& in, const SamplingSettings& s, const ObjectTrainingOptions& o);
/// Why a generation with `s` cannot run on this machine (its record memory bound exceeds the memory
/// available, in the generator's own words), or "" when it can: the Generate and Run pipeline buttons
/// are disabled with this reason instead of failing in the Log after a click.
std::string generateRefusal(const EstimateInputs& in, const SamplingSettings& s);
/// The four stages of the pipeline under `preset` (null: the settings in effect), in order: render,
/// generate, train, evaluate.
std::vector<StageEstimate> pipelineEstimates(const EstimateInputs& in, const PipelinePreset* preset);

/// The pipeline bar's name for a choice: the preset's name, "project settings" for "" (the settings
/// in effect, the bar's default).
std::string pipelineChoiceLabel(const std::string& preset);
/// What to expect from running the pipeline with `preset` ("" = the settings in effect: the
/// expectation of the preset they equal, else a note that custom settings have no preset figures);
/// `brief` gives the bar's few words, else the sentence of the tooltips.
std::string pipelineExpectation(const Project& project, const std::string& preset, bool brief);

/// Sampling panel: the preset choice (applies the preset's data half) and its estimated time.
void drawSamplingPresets(const SamplingPanelView& panel);
/// Network panel: the preset choice (applies the network and trainer half) and its estimated time.
void drawNetworkPresets(const NetworkPanelView& panel);
/// The pipeline bar: "Run pipeline" (or "Stop pipeline" while it runs) first, then the preset choice
/// with the whole pipeline's estimate, then the progress display while it runs or how it ended.
void drawPipelineBar(const PipelineBarView& bar);

}  // namespace rrf::panels
