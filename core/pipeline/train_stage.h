#pragma once
/// The training stage: per-object samples -> trained networks -> a saved model directory -> what the
/// "train" run records. `rrf train`, `rrf pipeline`, the workbench's Train job and the sweeps all
/// train through here (core/nn/training_run.h does the training itself), so a change to what a
/// training stores or records is made once.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/data/dataset_file.h"
#include "core/data/sampling_settings.h"
#include "core/nn/model_set.h"
#include "core/nn/network_settings.h"
#include "core/nn/training_run.h"
#include "core/pipeline/run_recording.h"
#include "core/pipeline/stage_observer.h"

namespace rrf {

/// How the networks of one training are shared among processes (the CLI's MPI ranks,
/// app/cli/cli_ranks.h). Without one a single process trains them all.
class TrainingShare {
public:
    virtual ~TrainingShare() = default;
    /// The options this process trains with (the objects it owns) out of the whole job's `options`;
    /// options with no objects mean this process trains nothing.
    virtual ObjectTrainingOptions mine(const std::vector<ObjectSamples>& samples, const ObjectTrainingOptions& options) = 0;
    /// Every process's networks joined, on the process that saves them; this process's `run` on the
    /// others. Called by every process once its own part is trained.
    virtual TrainingRun join(TrainingRun run, const ObjectTrainingOptions& options) = 0;
    /// True on the one process that saves the models and records the run.
    virtual bool saves() const = 0;
};

/// What to train and where the models go.
struct TrainRequest {
    /// The network settings and the trainer (Project::trainingOptions, changed by the front end's
    /// flags or a sweep row) and the objects to train: joined here, where the training starts.
    ObjectTrainingOptions options;
    std::optional<SamplingSettings> sampling;  ///< the project's sampling section, for the run record
    uint64_t sceneHash = 0;
    std::vector<std::string> inputLayout;      ///< the records' inputs (RecordLayout::inputs)
    std::string modelsDir;                     ///< where models.json goes; empty: kept in memory only
    TrainingProvenance provenance;             ///< dataset and project files, for models.json
    /// Read the saved models back as the prediction loads them (a complete run only), so that a front
    /// end that shows them next does not read weights on its UI thread.
    bool readBack = false;
    TrainingShare* share = nullptr;            ///< null: this process trains every network
};

/// What the stage did.
struct TrainOutcome {
    TrainingRun run;                           ///< networks in memory, curves, time (joined across processes)
    int64_t records = 0;                       ///< training records the networks were trained on
    int plannedNetworks = 0;                   ///< networks the settings set out to train
    int leaves = 0;                            ///< kd-tree leaves (networks) over the trained models
    bool saved = false;                        ///< models.json was written to the request's modelsDir
    std::shared_ptr<const ModelSet> models;    ///< read back when the request asked and the run is complete
    /// What a "train" run records of it (setTrainRun); generateSeconds is the caller's to fill.
    TrainRecord record;
};

/// Trains `samples` as `request` says, reporting epochs, messages and progress to `observer` (whose
/// cancel flag stops it: the outcome's run is then marked cancelled and holds what was trained), and
/// saves the models when the request names a directory and a network was trained.
TrainOutcome trainStage(const std::vector<ObjectSamples>& samples, const TrainRequest& request, const StageObserver& observer);

/// trainStage on an open dataset file (its scene hash checked by the caller's Dataset): its records
/// with NaN or Inf values are dropped (and counted in a note to the observer); the request's
/// inputLayout is taken from the file, provenance.dataset names it.
TrainOutcome trainFromDataset(const Dataset& data, TrainRequest request, const StageObserver& observer);

}  // namespace rrf
