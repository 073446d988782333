#pragma once
/// Data and training as a controller: the generate job that writes <project dir>/data/dataset.rrfd
/// and the training job that trains the project's networks on it, saves them under runs/<run>/models
/// and records a "train" run.
/// It owns both job sessions and publishes their snapshots, state.dataset (panels::DatasetInfo) and
/// state.training (panels::TrainingInfo: progress and the live loss curves). A finished complete
/// training is handed to onTrained, which the Workbench wires to the prediction (load the models)
/// and to the evaluation that follows a manual training. UI thread only.

#include <functional>
#include <memory>
#include <string>

#include "app/gui/controller_context.h"
#include "app/gui/job_session.h"

namespace rrf {

class LivePrediction;
struct ModelSet;
struct GeneratedDataset;
struct TrainingOutcome;
struct TrainingLive;

class TrainingController {
public:
    /// `live`: the prediction on screen, read to say what a stopped training leaves it showing.
    TrainingController(ControllerContext& ctx, const LivePrediction& live);
    ~TrainingController();

    /// Starts the data generator with the project's sampling settings, writing
    /// <project dir>/data/dataset.rrfd (refused while a conflicting job runs). `done`: told once when
    /// the job ended (delivered: the dataset was written).
    bool startGenerate(StageDone done = nullptr);
    bool generateRunning() const { return generateJob_.running(); }
    double generateProgress() const { return generateJob_.progress(); }
    void cancelGenerate() { generateJob_.cancel(); }

    /// Trains the project's networks on the generated dataset (or <project dir>/data/dataset.rrfd);
    /// `maxEpochs` > 0 overrides the trainer's epoch limit. `done`: told once when the job ended
    /// (delivered: a complete model set was saved and recorded as a run).
    bool startTrain(int maxEpochs = 0, StageDone done = nullptr);
    bool trainRunning() const { return trainJob_.running(); }
    double trainProgress() const { return trainJob_.progress(); }
    void cancelTrain() { trainJob_.cancel(); }

    /// Each frame: publishes progress and loss curves, takes finished jobs' results.
    void poll();
    /// Forgets both jobs (a project was closed): nothing they still produce arrives.
    void drop();

    /// A complete training was saved and recorded: its models directory and the set read back on
    /// the worker (the Workbench loads it for the live prediction).
    std::function<void(const std::string& modelsDir, std::shared_ptr<const ModelSet> models)> onTrained;

private:
    void pollGenerate();
    void pollTrain();
    /// A finished training job: records it as a run; true when it is a complete model set.
    bool trainingFinished(TrainingOutcome& outcome);
    /// The dataset training reads: this session's, else the project's data/dataset.rrfd if present.
    std::string datasetPath() const;

    ControllerContext& ctx_;
    const LivePrediction& live_;
    JobSession<GeneratedDataset> generateJob_;
    StageDone generateDone_;
    std::shared_ptr<TrainingLive> trainLive_;  ///< loss curves of the running training, for the plot
    uint64_t trainRevision_ = 0;
    JobSession<TrainingOutcome> trainJob_;
    StageDone trainDone_;
};

}  // namespace rrf
