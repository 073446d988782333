#include "core/nn/training_part.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <utility>

#include "core/nn/model.h"
#include "core/util/byte_stream.h"

namespace rrf {

namespace {
void putEpoch(ByteWriter& w, const EpochRecord& r) {
    w.i64(r.epoch);
    w.f64(r.trainLoss);
    w.f64(r.validationLoss);
    w.f64(r.step);
    w.f64(r.seconds);
    w.f64(r.validationRelativeRmse);
    w.u64(r.failureWithinNoise);
}

EpochRecord getEpoch(ByteReader& r) {
    EpochRecord e;
    e.epoch = int(r.i64());
    e.trainLoss = r.f64();
    e.validationLoss = r.f64();
    e.step = r.f64();
    e.seconds = r.f64();
    e.validationRelativeRmse = r.f64();
    e.failureWithinNoise = r.u64() != 0;
    return e;
}

void putEpochs(ByteWriter& w, const std::vector<EpochRecord>& epochs) {
    w.u64(epochs.size());
    for (const EpochRecord& e : epochs) putEpoch(w, e);
}

std::vector<EpochRecord> getEpochs(ByteReader& r) {
    std::vector<EpochRecord> epochs(size_t(r.u64() & 0xFFFFFFFFu));
    for (EpochRecord& e : epochs) e = getEpoch(r);
    return epochs;
}

/// Every field of a training record: a model file keeps only some of them (nn/model.h).
void putTraining(ByteWriter& w, const TrainResult& t) {
    putEpochs(w, t.history);
    w.i64(t.epochs);
    w.i64(t.bestEpoch);
    w.string(t.stopReason);
    w.u64(t.cancelled);
    w.f64(t.trainLoss);
    w.f64(t.validationLoss);
    w.f64(t.testLoss);
    w.i64(t.trainSamples);
    w.i64(t.validationSamples);
    w.i64(t.testSamples);
    w.i64(t.trainSamplesUsed);
    w.f64(t.seconds);
    w.u64(t.messages.size());
    for (const std::string& m : t.messages) w.string(m);
    w.f64(t.errorGoal);
    w.u64(t.goalReached);
    w.f64(t.validationRelativeRmse);
    w.f64(t.validationRelativeRmseCorrected);
    w.f64(t.validationRelativeNoise);
    w.i64(t.members);
    w.i64(t.memberEpochs);
}

TrainResult getTraining(ByteReader& r) {
    TrainResult t;
    t.history = getEpochs(r);
    t.epochs = int(r.i64());
    t.bestEpoch = int(r.i64());
    t.stopReason = r.string();
    t.cancelled = r.u64() != 0;
    t.trainLoss = r.f64();
    t.validationLoss = r.f64();
    t.testLoss = r.f64();
    t.trainSamples = r.i64();
    t.validationSamples = r.i64();
    t.testSamples = r.i64();
    t.trainSamplesUsed = r.i64();
    t.seconds = r.f64();
    t.messages.resize(size_t(r.u64() & 0xFFFFFFFFu));
    for (std::string& m : t.messages) m = r.string();
    t.errorGoal = r.f64();
    t.goalReached = r.u64() != 0;
    t.validationRelativeRmse = r.f64();
    t.validationRelativeRmseCorrected = r.f64();
    t.validationRelativeNoise = r.f64();
    t.members = int(r.i64());
    t.memberEpochs = r.i64();
    return t;
}

void putTree(ByteWriter& w, const PartitionTree& tree) {
    w.u64(tree.nodes.size());
    for (const PartitionNode& n : tree.nodes) {
        w.i64(n.axis);
        w.f64(double(n.split));  // a float widened to double and back keeps its bits
        w.i64(n.left);
        w.i64(n.right);
        w.i64(n.leaf);
        w.i64(n.records);
        w.f64(n.error);
    }
}

PartitionTree getTree(ByteReader& r) {
    PartitionTree tree;
    tree.nodes.resize(size_t(r.u64() & 0xFFFFFFFFu));
    for (PartitionNode& n : tree.nodes) {
        n.axis = int(r.i64());
        n.split = float(r.f64());
        n.left = int(r.i64());
        n.right = int(r.i64());
        n.leaf = int(r.i64());
        n.records = r.i64();
        n.error = r.f64();
    }
    return tree;
}
}  // namespace

std::string encodeTrainingPart(const TrainingRun& run) {
    ByteWriter w;
    w.u64(run.models.size());
    for (const ObjectModel& m : run.models) {
        w.i64(m.objectId);
        w.string(m.objectName);
        w.string(m.target);
        w.u64(m.skipped);
        w.string(m.message);
        if (m.skipped) continue;
        putTree(w, m.model.tree);
        w.u64(m.model.leaves.size());
        for (const NetworkModel& leaf : m.model.leaves) {
            w.string(modelFileBytes(leaf));
            putTraining(w, leaf.training);
        }
    }
    w.u64(run.curves.size());
    for (const NetworkCurve& c : run.curves) {
        w.i64(c.objectId);
        w.string(c.object);
        w.string(c.target);
        putEpochs(w, c.epochs);
    }
    w.f64(run.seconds);
    w.u64(run.cancelled);
    return w.take();
}

TrainingRun decodeTrainingPart(const std::string& bytes, const std::string& source) {
    ByteReader r(bytes, source);
    TrainingRun run;
    run.models.resize(size_t(r.u64() & 0xFFFFFFFFu));
    for (ObjectModel& m : run.models) {
        m.objectId = int(r.i64());
        m.objectName = r.string();
        m.target = r.string();
        m.skipped = r.u64() != 0;
        m.message = r.string();
        (m.skipped ? run.skipped : run.networks) += 1;
        if (m.skipped) continue;
        m.model.tree = getTree(r);
        m.model.leaves.resize(size_t(r.u64() & 0xFFFFFFFFu));
        for (NetworkModel& leaf : m.model.leaves) {
            leaf = parseModel(r.string(), source);
            leaf.training = getTraining(r);
        }
    }
    run.curves.resize(size_t(r.u64() & 0xFFFFFFFFu));
    for (NetworkCurve& c : run.curves) {
        c.objectId = int(r.i64());
        c.object = r.string();
        c.target = r.string();
        c.epochs = getEpochs(r);
    }
    run.seconds = r.f64();
    run.cancelled = r.u64() != 0;
    if (!r.atEnd()) throw std::runtime_error(source + ": trailing bytes after the training part");
    return run;
}

TrainingRun joinTrainingParts(std::vector<TrainingRun> parts, const std::vector<int>& rankOfPosition,
                              int networksPerObject) {
    TrainingRun out;
    std::vector<size_t> next(parts.size(), 0);
    for (size_t p = 0; p < rankOfPosition.size(); ++p) {
        const size_t rank = size_t(rankOfPosition[p]);
        if (rank >= parts.size()) throw std::runtime_error("training join: object " + std::to_string(p) + " assigned to rank " + std::to_string(rank) + " of " + std::to_string(parts.size()));
        for (int k = 0; k < networksPerObject; ++k) {
            if (next[rank] >= parts[rank].models.size())
                throw std::runtime_error("rank " + std::to_string(rank) + " returned " + std::to_string(parts[rank].models.size()) +
                                         " models, fewer than its objects need");
            out.models.push_back(std::move(parts[rank].models[next[rank]++]));
        }
    }
    for (size_t r = 0; r < parts.size(); ++r)
        if (next[r] != parts[r].models.size())
            throw std::runtime_error("rank " + std::to_string(r) + " returned " + std::to_string(parts[r].models.size()) +
                                     " models, more than its objects need (" + std::to_string(next[r]) + ")");
    std::map<std::pair<int, std::string>, NetworkCurve> curves;
    for (TrainingRun& part : parts) {
        for (NetworkCurve& c : part.curves) curves.emplace(std::make_pair(c.objectId, c.target), std::move(c));
        out.seconds = std::max(out.seconds, part.seconds);
        out.cancelled = out.cancelled || part.cancelled;
    }
    for (auto& kv : curves) out.curves.push_back(std::move(kv.second));
    for (const ObjectModel& m : out.models) (m.skipped ? out.skipped : out.networks) += 1;
    return out;
}

}  // namespace rrf
