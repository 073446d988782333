#pragma once
/// Presets of the whole pipeline (render → generate → train → evaluate): named settings of the data
/// generator and the networks, and the sizes `rrf pipeline` evaluates at. One table, shared by the
/// CLI (`rrf pipeline --preset NAME`, `--quick`, the sweeps' sizes) and the workbench (the Sampling
/// and Network panels' preset choices and the one-click pipeline). A new preset is one more row of
/// pipelinePresets() (presets.cpp); everything that lists or applies presets reads that table.
///
///   quick  a smoke test of the whole pipeline: shrinks the sizes of the settings in
///          effect (grid 5³, 150 directions, 16 paths per record in the first round, 50 epochs) and
///          keeps everything else (network shape, trainer, adaptive sampling);
///   paper  the seed report's setting (docs/design.md §21): grid 15³ × 1200 directions, 64 paths per
///          record (fixed), one 20-10 tanh network per object and target, Levenberg–Marquardt with
///          at most 1000 epochs, by far the slowest;
///   default the project defaults (SamplingSettings(), NetworkSettings(): the structs'
///          initialisers): what a project without sections runs;
///   best   the most accurate setting measured (issue 16): eight times the default's records at a
///          quarter of their paths each, 32-32-32 tanh networks (one per object), Adam with
///          relative L2 to the end of a cosine schedule, exact direct light at 256 samples per
///          pixel. Its time and error: docs/results.md (pipeline-cornell-best).
///
/// paper, default and best set every data and network setting except the seeds; quick changes only sizes.

#include <string>
#include <vector>

#include "core/data/sampling_settings.h"
#include "core/nn/object_training.h"
#include "core/predict/prediction_settings.h"

namespace rrf {

struct Project;

/// The ground truth and held-out evaluation of `rrf pipeline` under a preset (≤ 0: the command's
/// default, the project's size and reference target).
struct PipelineEvaluationSizes {
    int groundTruthSpp = 64;   ///< samples per pixel of the ground truth
    int width = 0, height = 0; ///< image size; 0 = the project's
    int heldOutLights = 2;     ///< held-out light positions evaluated
    int referenceSppCap = 0;   ///< cap on the held-out references' spp; 0 = the project's
};

/// One row of the preset table.
struct PipelinePreset {
    const char* name;     ///< "quick", "paper", "default", "best": the CLI's --preset value and the panels' label
    const char* summary;  ///< one line for help texts and tooltips
    /// What a user should expect from it, accuracy first: the held-out figure measured on the bundled
    /// projects (docs/results.md, "What each preset gives") and what the prediction looks like, so
    /// the one-click pipeline never leaves a smoke test's image to pass for a result.
    const char* expectation;
    /// The same in a few words for the pipeline bar: "~0.04 held-out error", "smoke test (~0.24)".
    const char* expectationShort;
    /// Changes the data settings in effect (a project's samplingOrDefault()) into the preset's.
    void (*sampling)(SamplingSettings&);
    /// Changes the network and trainer settings in effect (networkOrDefault().options) into the preset's.
    void (*network)(ObjectTrainingOptions&);
    /// Changes the prediction settings (how exact direct light completes the networks) into the
    /// preset's; part of the network half (applyNetworkPreset, matchingNetworkPreset).
    void (*prediction)(PredictionSettings&);
    PipelineEvaluationSizes evaluation;
};

/// Every preset, in the order menus list them (quick, paper, default, best).
const std::vector<PipelinePreset>& pipelinePresets();
/// The preset named `name`, or null.
const PipelinePreset* findPreset(const std::string& name);
/// The preset both halves of whose settings the project has (applying it would change nothing, so its
/// expectation is the settings in effect's), or null for custom settings.
const PipelinePreset* matchingPreset(const Project& project);
/// The names joined by `separator` ("quick|paper|best"), for help texts and error messages.
std::string presetNames(const char* separator = "|");

/// The project's data settings in effect with `preset` applied.
SamplingSettings presetSampling(const Project& project, const PipelinePreset& preset);
/// The project's network and trainer settings in effect with `preset` applied.
ObjectTrainingOptions presetNetwork(const Project& project, const PipelinePreset& preset);
/// The project's prediction settings with `preset` applied.
PredictionSettings presetPrediction(const Project& project, const PipelinePreset& preset);
/// Stores presetSampling() as the project's "sampling" section.
void applySamplingPreset(Project& project, const PipelinePreset& preset);
/// Stores presetNetwork() as the project's "network" and "trainer" sections and presetPrediction()
/// as its "prediction" section.
void applyNetworkPreset(Project& project, const PipelinePreset& preset);
/// The preset whose data settings are the project's (applying it would change nothing), or null.
const PipelinePreset* matchingSamplingPreset(const Project& project);
/// The preset whose network, trainer and prediction settings are the project's, or null.
const PipelinePreset* matchingNetworkPreset(const Project& project);

}  // namespace rrf
