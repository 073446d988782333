#pragma once
/// The whole pipeline in one call: ground truth at the scene's light, training data, networks, and
/// the evaluation at the ground truth's light and at held-out lights (references from the project's
/// store), each stage's files under one output directory and each stage's wall time. `rrf pipeline`
/// runs it (alone or across MPI ranks, through PipelineProcesses); the stages are the functions of
/// generate_stage.h, train_stage.h and evaluate_stage.h, so what a stage writes or records is the
/// same whichever front end chained it.
///
/// Output directory: ground_truth/ (direct, indirect, global EXR + variances, global.png,
/// render.json), dataset.rrfd, models/, evaluation/ (at the ground truth's light), held_out/.

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/eval/evaluation.h"
#include "core/eval/reference_store.h"
#include "core/pipeline/evaluate_stage.h"
#include "core/pipeline/generate_stage.h"
#include "core/pipeline/train_stage.h"
#include "core/predict/prediction_settings.h"
#include "core/project/project.h"
#include "core/render/renderer.h"

namespace rrf {

/// The settings of one pipeline run, resolved by the front end (project, preset, flags).
struct PipelineRequest {
    SamplingSettings sampling;          ///< the data stage's
    ObjectTrainingOptions training;     ///< the networks'
    PredictionSettings prediction;      ///< the predictor's (a preset's direct samples, flags)
    RenderOptions groundTruth;          ///< spp, size and seed of the ground truth; the references' size
    int heldOutLights = 0;              ///< held-out light positions to evaluate at
    uint64_t heldOutSeed = 1;           ///< seed of their positions
    NoiseTarget referenceTarget;        ///< what the held-out references converge to
    std::string out;                    ///< output directory
    std::string projectFile;            ///< the project (or scene) file, for models.json
};

/// How the stages share their work among processes (the CLI's MPI ranks, app/cli/cli_ranks.h).
/// Empty members: this one process does all of it.
struct PipelineProcesses {
    bool writes = true;  ///< this process writes every file (one per job)
    /// Renders the ground truth (default: renderFixedReference under the runner).
    std::function<Reference(const Scene&, const Vec3&, const RenderOptions&)> groundTruth;
    /// Makes the records; must return the whole data on every process, which all train on it.
    GenerateFunction generate;
    TrainingShare* training = nullptr;
    /// Gives every process the networks the writing process joined (it evaluates them as one
    /// process would; the held-out references converge relative to their error).
    std::function<void(TrainingRun& run)> shareNetworks;
    /// Lets every process render its share of the held-out references into the store before the
    /// writing process evaluates (then finds them all there).
    std::function<void(const std::vector<Vec3>& lights, const ReferenceSource& source)> prefetchReferences;
};

struct PipelineOutcome {
    std::vector<std::pair<std::string, double>> stageSeconds;  ///< "ground truth", "generate", "train", "evaluate"
    std::vector<Evaluation> atGroundTruth, heldOut;            ///< on the writing process
    bool cancelled = false;                                    ///< the training was stopped
};

/// Runs the pipeline on `project` (its scene, render and reference settings), each stage under
/// `run`, its notes ("[1/4] ground truth: 3.2 s -> out/ground_truth", the evaluation tables) to
/// `notes`. Throws what the stages throw; a stage interrupted before its result throws
/// std::runtime_error, an interrupted training ends the run after saving the partial models.
PipelineOutcome runPipeline(const Project& project, const PipelineRequest& request, ReferenceStore& store,
                            const StageRunner& run, const StageObserver& notes, const PipelineProcesses& processes = {});

}  // namespace rrf
