#pragma once
/// One training run over per-object samples, as `rrf train`, the workbench's Train job and the sweeps
/// all do it: the networks of every selected object (core/nn/object_training.h), each network's loss
/// curve, the wall time and the counts of trained and skipped networks. Front ends differ only in
/// where the samples come from and what they do with the result (save a model directory, record a
/// run, evaluate in memory), so the result is identical for identical samples and options.

#include <atomic>
#include <string>
#include <vector>

#include "core/nn/network_settings.h"
#include "core/nn/object_training.h"

namespace rrf {

/// Live counters of a training run, readable from another thread while it runs (the data
/// generator's GeneratorProgress pattern): the UI thread or the CLI's progress line polls fraction().
struct TrainingProgress {
    /// Network epochs finished over all networks (kd-tree nodes included), plus the epochs of
    /// networks that stopped before max_epochs (ObjectTrainingObserver::onWork).
    std::atomic<int64_t> epochs{0};
    /// Most epochs the networks scheduled so far can take: the roots' when the run starts, growing by
    /// two networks' max_epochs whenever a kd-tree node splits.
    std::atomic<double> epochBudget{0.0};
    double fraction() const;
};

/// The epochs of one network in the order they ran.
struct NetworkCurve {
    int objectId = -1;
    std::string object;  ///< object name
    std::string target;  ///< "global" | "direct" | "indirect" | "joint"
    std::vector<EpochRecord> epochs;
};

struct TrainingRun {
    std::vector<ObjectModel> models;  ///< as trainObjects returns them (skipped entries included)
    /// One per network that ran at least one epoch, ordered by (object id, target name).
    std::vector<NetworkCurve> curves;
    double seconds = 0.0;             ///< wall time of the whole run
    int networks = 0, skipped = 0;    ///< trained networks / skipped entries of `models`
    bool cancelled = false;           ///< the cancel flag was set when the run ended
};

/// The most network epochs `options` can spend on `samples` (selected objects × networks per
/// object × epoch limit): the denominator of a progress fraction.
double trainingEpochBudget(const std::vector<ObjectSamples>& samples, const ObjectTrainingOptions& options);

/// Trains the networks of `samples` with `options`. `observer` (may be empty) sees every epoch and
/// message from the worker threads and carries the cancel flag; `progress` (may be null) is updated
/// as epochs finish. Throws what trainObjects throws.
TrainingRun trainNetworks(const std::vector<ObjectSamples>& samples, const ObjectTrainingOptions& options,
                          const ObjectTrainingObserver& observer = {}, TrainingProgress* progress = nullptr);

/// Where a training run's samples and settings came from, for models.json.
struct TrainingProvenance {
    std::string dataset;  ///< the dataset file the samples were read from
    std::string project;  ///< the project (or bare scene) file the settings came from
};

/// Saves the models of `run` into `dir` as a model set (core/nn/model_set.h) for the scene with hash
/// `sceneHash`, whose inputs are `inputLayout`. Every front end that trains (`rrf train`,
/// `rrf pipeline`, the workbench's Train job) saves through here, so models.json holds the same
/// fields whoever wrote it: "dataset", "project", "network" and "trainer" (the two sections of
/// `options`), "seconds" and "cancelled" (from `run`).
void saveTrainingRun(const std::string& dir, const TrainingRun& run, const ObjectTrainingOptions& options,
                               uint64_t sceneHash, const std::vector<std::string>& inputLayout,
                               const TrainingProvenance& provenance);

}  // namespace rrf
