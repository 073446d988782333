#include "core/nn/training_run.h"

#include <algorithm>
#include <map>
#include <mutex>
#include <tuple>

#include "core/nn/model_set.h"
#include "core/nn/training_split.h"
#include "core/util/stopwatch.h"

namespace rrf {

double TrainingProgress::fraction() const {
    const double budget = epochBudget.load();
    return budget > 0 ? std::min(1.0, double(epochs.load()) / budget) : 0.0;
}

double trainingEpochBudget(const std::vector<ObjectSamples>& samples, const ObjectTrainingOptions& options) {
    const size_t objects = options.objects.empty() ? samples.size() : options.objects.size();
    return double(objects) * networksPerObject(options) * options.trainer.maxEpochs() * options.ensemble;
}

TrainingRun trainNetworks(const std::vector<ObjectSamples>& samples, const ObjectTrainingOptions& options,
                          const ObjectTrainingObserver& observer, TrainingProgress* progress) {
    std::map<int, const std::string*> names;
    for (const ObjectSamples& s : samples) names.emplace(s.objectId, &s.name);
    if (progress) {
        progress->epochs = 0;
        progress->epochBudget = trainingEpochBudget(samples, options);
    }
    // Objects train concurrently: the curves are collected under a lock and ordered at the end, so the
    // result does not depend on which thread finished an epoch first.
    std::mutex mutex;
    std::map<std::pair<int, std::string>, NetworkCurve> curves;
    ObjectTrainingObserver inner;
    inner.cancel = observer.cancel;
    inner.onMessage = observer.onMessage;
    inner.onEpoch = [&](int object, const std::string& target, const EpochRecord& r) {
        {
            std::lock_guard<std::mutex> lock(mutex);
            NetworkCurve& c = curves[{object, target}];
            if (c.epochs.empty()) {
                c.objectId = object;
                const auto it = names.find(object);
                c.object = it != names.end() ? *it->second : std::string();
                c.target = target;
            }
            c.epochs.push_back(r);
        }
        if (observer.onEpoch) observer.onEpoch(object, target, r);
    };
    inner.onWork = [&](int64_t done, int64_t budget) {
        if (progress) {
            progress->epochs += done;
            // Budget grows only between tree levels, on the thread that decides the splits (no race).
            if (budget) progress->epochBudget = progress->epochBudget.load() + double(budget);
        }
        if (observer.onWork) observer.onWork(done, budget);
    };

    TrainingRun run;
    const Stopwatch clock;
    run.models = trainObjects(samples, options, inner);
    run.seconds = clock.seconds();
    run.cancelled = observer.cancel && observer.cancel->load();
    for (const ObjectModel& m : run.models) (m.skipped ? run.skipped : run.networks) += 1;
    for (auto& kv : curves) run.curves.push_back(std::move(kv.second));
    return run;
}

void saveTrainingRun(const std::string& dir, const TrainingRun& run, const ObjectTrainingOptions& options,
                     uint64_t sceneHash, const std::vector<std::string>& inputLayout,
                     const TrainingProvenance& provenance) {
    const ModelSetRecord record{provenance.dataset, provenance.project, NetworkSettings{options.network()},
                                options.trainer,    run.seconds,        run.cancelled};
    saveModelSet(dir, run.models, sceneHash, inputLayout, &record);
}

}  // namespace rrf
