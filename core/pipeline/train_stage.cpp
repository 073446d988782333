#include "core/pipeline/train_stage.h"

#include <algorithm>

#include "core/nn/training_samples.h"

namespace rrf {

TrainOutcome trainStage(const std::vector<ObjectSamples>& samples, const TrainRequest& request, const StageObserver& observer) {
    const ObjectTrainingOptions& options = request.options;
    TrainingProgress progress;
    ObjectTrainingObserver o;
    o.cancel = observer.cancel;
    o.onEpoch = [&](int object, const std::string& target, const EpochRecord& r) {
        observer.setProgress(progress.fraction());
        if (observer.epoch) observer.epoch(object, target, r);
    };
    if (observer.message) o.onMessage = observer.message;

    TrainOutcome out;
    observer.setStatus("training");
    if (!request.share) {
        out.run = trainNetworks(samples, options, o, &progress);
    } else {
        const ObjectTrainingOptions mine = request.share->mine(samples, options);
        if (!mine.objects.empty()) out.run = trainNetworks(samples, mine, o, &progress);
        out.run = request.share->join(std::move(out.run), options);
    }
    const TrainingRun& run = out.run;
    for (const ObjectModel& m : run.models)
        if (!m.skipped) out.leaves += m.model.leafCount();
    for (const ObjectSamples& s : samples) out.records += int64_t(s.size());
    // The budget counts every network's epoch limit; divided by one network's, it counts networks.
    const int epochLimit = std::max(1, options.trainer.maxEpochs() * options.ensemble);
    out.plannedNetworks = int(trainingEpochBudget(samples, options) / epochLimit + 0.5);

    const bool saves = !request.share || request.share->saves();
    if (saves && !request.modelsDir.empty() && run.networks > 0) {
        observer.setStatus("saving the models");
        saveTrainingRun(request.modelsDir, run, options, request.sceneHash, request.inputLayout, request.provenance);
        out.saved = true;
        // Read back as the prediction will load them: the files are what the run records.
        if (request.readBack && !run.cancelled)
            out.models = std::make_shared<const ModelSet>(loadModelSet(request.modelsDir, request.sceneHash));
    }
    TrainRecord& r = out.record;
    r.network.options = options.network();
    r.trainer = options.trainer;
    r.sampling = request.sampling;
    r.dataset = request.provenance.dataset;
    r.modelsDir = request.modelsDir;
    r.sceneHash = request.sceneHash;
    r.curves = lossCurves(run.curves);
    r.networks = run.networks;
    r.skipped = run.skipped;
    r.seconds = run.seconds;
    r.stopped = run.cancelled;
    r.plannedNetworks = out.plannedNetworks;
    r.leaves = out.leaves;
    r.records = out.records;
    observer.setStatus(out.saved ? "models saved" : run.networks > 0 ? "trained" : "no network trained");
    return out;
}

TrainOutcome trainFromDataset(const Dataset& data, TrainRequest request, const StageObserver& observer) {
    uint64_t dropped = 0;
    const std::vector<ObjectSamples> samples = samplesFromDataset(data, &dropped);
    if (dropped) observer.note(std::to_string(dropped) + " records with NaN/Inf dropped from " + request.provenance.dataset);
    request.inputLayout = data.inputLayout();
    return trainStage(samples, request, observer);
}

}  // namespace rrf
