#include "core/nn/object_training.h"

#include <map>
#include <stdexcept>

#include <tbb/parallel_for.h>

namespace rrf {

void ObjectSamples::add(const float* in, const float directRgb[3], const float indirectRgb[3]) {
    inputs.insert(inputs.end(), in, in + numInputs);
    direct.insert(direct.end(), directRgb, directRgb + 3);
    indirect.insert(indirect.end(), indirectRgb, indirectRgb + 3);
}

Eigen::Map<const MatX<float>> ObjectSamples::inputMatrix() const {
    return {inputs.data(), numInputs, Eigen::Index(size())};
}
Eigen::Map<const MatX<float>> ObjectSamples::directMatrix() const { return {direct.data(), 3, Eigen::Index(size())}; }
Eigen::Map<const MatX<float>> ObjectSamples::indirectMatrix() const {
    return {indirect.data(), 3, Eigen::Index(size())};
}

void ObjectSamples::validate() const {
    const std::string who = "object " + std::to_string(objectId) + (name.empty() ? "" : " (" + name + ")");
    if (numInputs < 1 && !inputs.empty()) throw std::invalid_argument(who + ": numInputs must be positive");
    const size_t n = size();
    if (numInputs > 0 && inputs.size() != n * size_t(numInputs))
        throw std::invalid_argument(who + ": inputs length is not a multiple of numInputs");
    if (direct.size() != 3 * n || indirect.size() != 3 * n)
        throw std::invalid_argument(who + ": " + std::to_string(n) + " input records but " +
                                    std::to_string(direct.size() / 3) + " direct and " +
                                    std::to_string(indirect.size() / 3) + " indirect targets");
    const bool noVariance = directVariance.empty() && indirectVariance.empty();
    if (!noVariance && (directVariance.size() != 3 * n || indirectVariance.size() != 3 * n))
        throw std::invalid_argument(who + ": target variances must be given for every record or not at all");
}

const char* targetModeName(TargetMode m) {
    switch (m) {
        case TargetMode::Direct: return "direct";
        case TargetMode::Indirect: return "indirect";
        case TargetMode::Separate: return "separate";
        case TargetMode::Joint: return "joint";
        case TargetMode::Global:
        default: return "global";
    }
}

TargetMode parseTargetMode(const std::string& s) {
    for (TargetMode m : {TargetMode::Global, TargetMode::Direct, TargetMode::Indirect, TargetMode::Separate,
                         TargetMode::Joint})
        if (s == targetModeName(m)) return m;
    throw std::invalid_argument("unknown target mode '" + s +
                                "' (expected global, direct, indirect, separate or joint)");
}

std::string modelFileName(int objectId, const std::string& target) {
    return "object_" + std::to_string(objectId) + "_" + target + ".rrfm";
}

namespace {

struct Job {
    const ObjectSamples* samples = nullptr;
    std::string target;  // "global" | "direct" | "indirect" | "joint"
    size_t slot = 0;     // index into the result
};

MatX<float> targetMatrix(const ObjectSamples& s, const std::string& target) {
    if (target == "direct") return s.directMatrix();
    if (target == "indirect") return s.indirectMatrix();
    if (target == "joint") {
        MatX<float> t(6, Eigen::Index(s.size()));
        t.topRows(3) = s.directMatrix();
        t.bottomRows(3) = s.indirectMatrix();
        return t;
    }
    return s.directMatrix() + s.indirectMatrix();
}

/// Variance of the target's Monte Carlo mean (empty when unknown). The global target's is the sum:
/// under NEE the first vertex's light sample and the path's continuation use independent random
/// numbers, so direct and indirect estimates of one record are uncorrelated.
MatX<float> targetVariance(const ObjectSamples& s, const std::string& target) {
    if (s.directVariance.empty()) return {};
    const Eigen::Map<const MatX<float>> d(s.directVariance.data(), 3, Eigen::Index(s.size()));
    const Eigen::Map<const MatX<float>> i(s.indirectVariance.data(), 3, Eigen::Index(s.size()));
    if (target == "direct") return d;
    if (target == "indirect") return i;
    if (target == "joint") {
        MatX<float> t(6, Eigen::Index(s.size()));
        t.topRows(3) = d;
        t.bottomRows(3) = i;
        return t;
    }
    return d + i;
}

}  // namespace

std::vector<ObjectModel> trainObjects(const std::vector<ObjectSamples>& objects, const ObjectTrainingOptions& options,
                                      const ObjectTrainingObserver& observer) {
    std::map<int, const ObjectSamples*> byId;
    for (const ObjectSamples& s : objects) {
        s.validate();
        if (!byId.emplace(s.objectId, &s).second)
            throw std::invalid_argument("object " + std::to_string(s.objectId) + " appears twice in the training data");
    }
    std::vector<int> ids = options.objects;
    if (ids.empty())
        for (const ObjectSamples& s : objects) ids.push_back(s.objectId);

    std::vector<std::string> targets;
    if (options.targets == TargetMode::Separate) targets = {"direct", "indirect"};
    else targets = {targetModeName(options.targets)};

    auto message = [&](const std::string& m) {
        if (observer.onMessage) observer.onMessage(m);
    };
    std::vector<ObjectModel> result;
    std::vector<Job> jobs;
    for (int id : ids) {
        auto it = byId.find(id);
        for (const std::string& t : targets) {
            ObjectModel om;
            om.objectId = id;
            om.target = t;
            if (it == byId.end()) {
                om.skipped = true;
                om.message = "object " + std::to_string(id) + " is not in the training data: skipped";
            } else {
                om.objectName = it->second->name;
                if (it->second->size() == 0) {
                    om.skipped = true;
                    om.message = "object " + std::to_string(id) + (om.objectName.empty() ? "" : " (" + om.objectName + ")") +
                                 " has no samples: skipped";
                } else {
                    jobs.push_back({it->second, t, result.size()});
                }
            }
            if (om.skipped && t == targets.front()) message(om.message);
            result.push_back(std::move(om));
        }
    }

    auto run = [&](size_t j) {
        const Job& job = jobs[j];
        ObjectModel& om = result[job.slot];
        const ObjectSamples& s = *job.samples;
        if (observer.cancel && observer.cancel->load()) {
            om.skipped = true;
            om.message = "object " + std::to_string(s.objectId) + " (" + job.target + "): cancelled before training";
            return;
        }
        MlpArch arch;
        arch.inputs = s.numInputs;
        arch.hidden = options.hidden;
        arch.activation = options.activation;
        arch.outputs = job.target == "joint" ? 6 : 3;
        TrainObserver obs;
        obs.cancel = observer.cancel;
        const int id = s.objectId;
        const std::string target = job.target;
        if (observer.onEpoch) obs.onEpoch = [&, id, target](const EpochRecord& r) { observer.onEpoch(id, target, r); };
        if (observer.onMessage)
            obs.onMessage = [&, id, target](const std::string& m) {
                observer.onMessage("object " + std::to_string(id) + " (" + target + "): " + m);
            };
        if (s.size() < 7)
            message("object " + std::to_string(id) + " (" + target + "): only " + std::to_string(s.size()) +
                    " samples, trained without validation and test sets");
        // The object id keys split and initial weights, so adding or removing other objects, or
        // choosing other objects to train, never changes this object's network.
        om.model = fitNetwork(arch, options.trainer, s.inputMatrix(), targetMatrix(s, target),
                              targetVariance(s, target), obs, uint64_t(uint32_t(id)));
        om.model.objectId = id;
        om.model.objectName = s.name;
        om.model.target = target;
    };
    if (options.parallel)
        tbb::parallel_for(size_t(0), jobs.size(), run);
    else
        for (size_t j = 0; j < jobs.size(); ++j) run(j);
    return result;
}

}  // namespace rrf
