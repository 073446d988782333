#pragma once
/// Recording runs: the one definition of what a render, training or evaluation run stores (settings
/// snapshot, metrics, timings, loss curves, artifacts), shared by the workbench and `rrf ... --record`
/// so that a run made by either front end has the same fields and the workbench can list, re-open
/// and compare it. Artifacts live under <project dir>/runs/<id>/ and are stored relative to the
/// project directory.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/eval/error_metrics.h"
#include "core/nn/network_settings.h"
#include "core/eval/reference_store.h"
#include "core/nn/training_run.h"
#include "core/project/project.h"
#include "core/project/runs.h"
#include "core/render/render_outputs.h"
#include "core/render/render_settings.h"
#include "core/scene/scene.h"

namespace rrf {

/// The directory runs of `project` are stored under: the project file's directory (absolute).
std::string projectDirectory(const Project& project);
/// The project's reference store, <project dir>/references (core/eval/reference_store.h): the one
/// place the CLI and the workbench keep and find its converged references.
ReferenceStore projectReferenceStore(const Project& project);
/// True when `project` was loaded from a bare scene file: there is no project file to record into.
bool isBareScene(const Project& project);
/// `file` relative to `projectDir`, '/'-separated, as Run::artifacts stores it.
std::string projectRelative(const std::string& projectDir, const std::string& file);

/// A new run of `kind` ("render", "train", ...) with an id unused in `runs`, name = id, created now.
Run beginRun(const std::vector<Run>& runs, const std::string& kind);
/// <projectDir>/runs/<run.id>: where a run's files go.
std::string runDirectory(const std::string& projectDir, const Run& run);

/// Fills a "render" run: settings {render (with the target spp), light_position, scene_hash,
/// scene_overrides when there are any}, metrics {spp, relative_error, non_finite_samples,
/// samples_per_second}, timings {render} and the images and render.json of `outputs` as artifacts.
void setRenderRun(Run& run, const std::string& projectDir, RenderSettings settings, int targetSpp, const Scene& scene,
                  const SceneOverrides& overrides, const RenderSnapshot& snapshot, const RenderStats& stats,
                  const RenderOutputs& outputs);

/// What a finished training job produced, for setTrainRun.
struct TrainRecord {
    NetworkSettings network;                  ///< the network settings it ran with
    TrainerConfig trainer = TrainerConfig::projectDefault();  ///< the trainer it ran with
    std::optional<SamplingSettings> sampling;  ///< the project's sampling section, when it has one
    std::string dataset;                      ///< dataset file it read
    std::string modelsDir;                    ///< where saveModelSet wrote models.json
    uint64_t sceneHash = 0;
    std::vector<LossCurve> curves;            ///< one per network, ordered by (object, target)
    int networks = 0, skipped = 0;
    double seconds = 0;                       ///< training wall time
    std::optional<double> generateSeconds;    ///< time that made the dataset, when known
    /// The user stopped the training: only `networks` of `plannedNetworks` were trained, so the models
    /// are a partial set (the run says so, and the workbench does not make them the live prediction).
    bool stopped = false;
    int plannedNetworks = 0;                  ///< networks the run set out to train (0 = unknown)
    int leaves = 0;                           ///< kd-tree leaves (networks) over all models (0 = unknown)
    int64_t records = 0;                      ///< training records read from the dataset (0 = unknown)
};

/// The loss curves of a training run as a run stores them ("?" for a network without an object name).
std::vector<LossCurve> lossCurves(const std::vector<NetworkCurve>& curves);

/// Fills a "train" run: settings {network, trainer, dataset, scene_hash, sampling, kernel (the MLP
/// kernel this process trains with, nn/mlp_kernel.h)}, the per-network
/// curves and their aggregate loss, metrics {networks, skipped, epochs, and when known
/// planned_networks, leaves, records; stopped when the user stopped it}, timings {train, generate} and models.json as the first
/// artifact (the workbench loads the models from its directory).
void setTrainRun(Run& run, const std::string& projectDir, TrainRecord record);

/// True for a "train" run the user stopped before every network was trained (metrics.stopped).
bool isStoppedTrainRun(const Run& run);
/// "stopped at epoch 12, 2 of 14 networks" (without "of N" when `planned` is 0): the one wording of
/// a stopped training, shared by the runs table, the Training panel's progress bar and the log.
std::string stoppedTrainingText(int epoch, int networks, int planned);
/// A training run's state for the runs table: stoppedTrainingText for a stopped run, else
/// "<n> networks"; empty for other kinds.
std::string trainRunStatusText(const Run& run);

/// The models directory a "train" run names (absolute), or empty when it lists no artifacts.
std::string trainRunModelsDir(const Run& run, const std::string& projectDir);
/// The first "train" run whose models are in `modelsDir`, or null.
const Run* findTrainRun(const std::vector<Run>& runs, const std::string& projectDir, const std::string& modelsDir);

/// What an evaluation of a model set measured on the global term, for recordEvaluation.
struct EvaluationRecord {
    ErrorStats global;                ///< over all object pixels; the mean over lights when several
    int referenceSpp = 0;
    std::vector<Vec3> lights;         ///< light positions evaluated at
    int width = 0, height = 0;        ///< the reference's image size (0: unknown)
    double seconds = 0;
    std::vector<std::string> artifacts;  ///< report files written, absolute or cwd-relative
};

/// Adds an evaluation's metrics {relative_rmse, rmse, mae, evaluated_spp, evaluated_width and
/// evaluated_height (when known), evaluated_light (one light) or evaluated_lights (their count),
/// relative_rmse_noise_floor and relative_rmse_corrected when the
/// reference's noise is known (removed otherwise)}, timings {evaluate} and artifacts to every "train" run whose
/// models are in `modelsDir`, so the Cost panel can place it. Returns how many runs it changed.
int recordEvaluation(std::vector<Run>& runs, const std::string& projectDir, const std::string& modelsDir,
                     const EvaluationRecord& record);

/// Where a frame of prediction was timed.
enum class FramePath { Cpu, Glsl };
/// Sets the frame time of `path` (RunMetrics::frameSeconds or glslFrameSeconds: one frame of
/// prediction, the names sweeps use) and the frame's size beside it in every "train" run whose
/// models are in `modelsDir`. Returns how many changed.
int recordFrameSeconds(std::vector<Run>& runs, const std::string& projectDir, const std::string& modelsDir,
                       FramePath path, double seconds, int width, int height);

/// Appends `run` to the runs of the project file `projectFile` and saves it atomically (saveProject).
/// The file is read again first, so that runs another program (the workbench) saved while the work
/// ran are kept. Throws InputError when the file is a bare scene or already has a run with this id,
/// std::runtime_error when saving fails.
void recordRun(const std::string& projectFile, const Run& run);

/// Replaces the file's runs with `edit` applied to them and saves it atomically, reading it first as
/// recordRun does. Throws as recordRun.
void editRuns(const std::string& projectFile, const std::function<void(std::vector<Run>&)>& edit);

}  // namespace rrf
