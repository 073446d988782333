#include "core/nn/object_training.h"

#include "core/nn/encoding_presets.h"
#include "core/util/error.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
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

std::string modelFileName(int objectId, const std::string& target) {
    return "object_" + std::to_string(objectId) + "_" + target + ".rrfm";
}

std::string leafModelFileName(int objectId, const std::string& target, int leaf) {
    return "object_" + std::to_string(objectId) + "_" + target + "_leaf" + std::to_string(leaf) + ".rrfm";
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

/// A tree node whose network is to be trained: its records (indices into the object's samples).
struct NodeTask {
    size_t job = 0;
    int node = 0;
    int depth = 0;
    std::vector<uint32_t> records;
};

/// A tree being grown: nodes and the network trained for each node (internal ones are dropped at the end).
struct TreeBuild {
    PartitionTree tree;
    std::vector<NetworkModel> nets;   // index = node
    std::vector<char> trained;        // index = node
    std::vector<int> parent;          // index = node, −1 for the root
    int leaves = 1;
};

/// Split and initial weights of node k of object `id`: the root keeps the unpartitioned network's
/// stream, so a tree that never splits is exactly the network trainObjects made before partitioning.
uint64_t nodeStream(int id, int node) { return uint64_t(uint32_t(id)) | (uint64_t(uint32_t(node)) << 32); }

MatX<float> gatherColumns(const Eigen::Ref<const MatX<float>>& m, const std::vector<uint32_t>& idx) {
    MatX<float> out(m.rows(), Eigen::Index(idx.size()));
    for (size_t j = 0; j < idx.size(); ++j) out.col(Eigen::Index(j)) = m.col(idx[j]);
    return out;
}

/// The tree with only the nodes reachable from the root, in pre-order, leaves numbered left to
/// right, and each leaf's network moved into place.
PartitionedNetwork finishTree(TreeBuild& b) {
    PartitionedNetwork out;
    std::vector<int> stack = {0};
    std::vector<int> newIndex(b.tree.nodes.size(), -1);
    while (!stack.empty()) {
        const int old = stack.back();
        stack.pop_back();
        newIndex[size_t(old)] = int(out.tree.nodes.size());
        PartitionNode n = b.tree.nodes[size_t(old)];
        if (n.isLeaf()) {
            n.leaf = int(out.leaves.size());
            out.leaves.push_back(std::move(b.nets[size_t(old)]));
        } else {
            n.leaf = -1;
            stack.push_back(n.right);
            stack.push_back(n.left);
        }
        out.tree.nodes.push_back(n);
    }
    for (PartitionNode& n : out.tree.nodes)
        if (!n.isLeaf()) {
            n.left = newIndex[size_t(n.left)];
            n.right = newIndex[size_t(n.right)];
        }
    return out;
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

    const PartitionSettings& part = options.partition;
    auto cancelled = [&] { return observer.cancel && observer.cancel->load(); };
    // Each object's hidden sizes, inputs and encoding: the section's, or its "objects" entry's.
    std::vector<ObjectNetworkChoice> choices;  // index = job
    std::vector<InputEncoding> encodings;      // index = job
    checkEncodingTrainer(options.encoding, options.trainer);
    checkEnsembleEncoding(options.encoding, options.ensemble);
    for (const Job& job : jobs) {
        choices.push_back(options.choiceFor(job.samples->name));
        const ObjectNetworkChoice& c = choices.back();
        checkEncodingTrainer(c.encoding, options.trainer);
        checkEnsembleEncoding(c.encoding, options.ensemble);
        encodings.push_back(networkEncoding(c.encoding, job.samples->numInputs, c.inputs));
    }
    // Every network is an ensemble of options.ensemble members, each budgeted max_epochs.
    const int64_t members = options.ensemble;
    auto archFor = [&](const Job& job) {
        MlpArch arch;
        const size_t j = size_t(&job - jobs.data());  // job is an element of jobs
        arch.inputs = encodings[j].outputs();  // the identity: the record inputs and the derived ones
        arch.hidden = choices[j].hidden;
        arch.activation = options.activation;
        arch.outputs = job.target == "joint" ? 6 : 3;
        return arch;
    };
    // Seams: two neighbouring leaves that each stop at the error goal e can differ by up to ~2e across
    // their plane. The networks of split nodes (depth > 0) therefore train to half the partition goal
    // (the root keeps the trainer's goal, so a tree that never splits is the plain network), so the
    // jump across a plane stays below the goal (PartitionedTraining.JumpAcrossSplitPlanesStaysBelowTheGoal).
    TrainerConfig leafTrainer = options.trainer;
    if (part.enabled()) {
        const double goal = std::min(leafTrainer.errorGoal(), part.goal / 2);
        for (TrainerCommon* c : leafTrainer.everyTrainer()) c->errorGoal = goal;
    }
    std::vector<MatX<float>> targetsOf(jobs.size());
    std::vector<MatX<float>> variancesOf(jobs.size());  // empty = the targets' noise is unknown
    std::vector<TreeBuild> builds(jobs.size());
    std::vector<NodeTask> level;
    for (size_t j = 0; j < jobs.size(); ++j) {
        const ObjectSamples& s = *jobs[j].samples;
        targetsOf[j] = targetMatrix(s, jobs[j].target);
        variancesOf[j] = targetVariance(s, jobs[j].target);
        builds[j].tree = PartitionTree::singleLeaf(int64_t(s.size()));
        builds[j].nets.resize(1);
        builds[j].trained.assign(1, 0);
        builds[j].parent.assign(1, -1);
        NodeTask root;
        root.job = j;
        root.records.resize(s.size());
        for (size_t i = 0; i < s.size(); ++i) root.records[i] = uint32_t(i);
        level.push_back(std::move(root));
        if (s.size() < 7)
            message("object " + std::to_string(s.objectId) + " (" + jobs[j].target + "): only " + std::to_string(s.size()) +
                    " samples, trained without validation and test sets");
    }

    // Level by level: train every node of the level (all objects and targets) in parallel, then decide
    // sequentially, in a fixed order, which nodes split. Each network is a pure function of its
    // records and its stream, so the result does not depend on the thread count.
    while (!level.empty()) {
        std::vector<double> error(level.size(), std::numeric_limits<double>::quiet_NaN());
        auto train = [&](size_t k) {
            const NodeTask& task = level[k];
            const Job& job = jobs[task.job];
            const ObjectSamples& s = *job.samples;
            TreeBuild& b = builds[task.job];
            if (cancelled()) return;
            const int id = s.objectId;
            const std::string target = job.target;
            const std::string who = "object " + std::to_string(id) + " (" + target + ")" +
                                    (task.node ? " node " + std::to_string(task.node) : "");
            TrainObserver obs;
            obs.cancel = observer.cancel;
            const bool root = task.node == 0;
            if ((observer.onEpoch && root) || observer.onWork)
                obs.onEpoch = [&, id, target, root](const EpochRecord& r) {
                    if (observer.onEpoch && root && r.member == 0) observer.onEpoch(id, target, r);
                    if (observer.onWork && r.epoch > 0) observer.onWork(1, 0);  // epoch 0 is the initial network
                };
            if (observer.onMessage) obs.onMessage = [&, who](const std::string& m) { observer.onMessage(who + ": " + m); };
            const uint64_t stream = nodeStream(id, task.node);
            const bool all = task.records.size() == s.size();
            const MatX<float> x = all ? MatX<float>() : gatherColumns(s.inputMatrix(), task.records);
            const MatX<float> y = all ? MatX<float>() : gatherColumns(targetsOf[task.job], task.records);
            const Eigen::Index n = Eigen::Index(task.records.size());
            const Eigen::Map<const MatX<float>> xin(all ? s.inputs.data() : x.data(), s.numInputs, n);
            const Eigen::Map<const MatX<float>> yin(all ? targetsOf[task.job].data() : y.data(), targetsOf[task.job].rows(), n);
            const MatX<float>& vAll = variancesOf[task.job];
            const MatX<float> v = vAll.size() == 0 || all ? vAll : gatherColumns(vAll, task.records);
            const TrainerConfig& trainer = task.depth == 0 ? options.trainer : leafTrainer;
            NetworkModel net = fitNetwork(archFor(job), encodings[task.job], trainer, xin, yin, v, obs, stream, options.ensemble);
            // The epochs this network's members were budgeted but did not need count as done.
            const int64_t budget = members * trainer.maxEpochs();
            if (observer.onWork && net.training.memberEpochs < budget) observer.onWork(budget - net.training.memberEpochs, 0);
            net.objectId = id;
            net.objectName = s.name;
            net.target = target;
            // Validation split exactly as fitNetwork drew it (same n, seed and stream).
            const DataSplit split = splitSamples(size_t(xin.cols()), options.trainer.seed(), stream);
            // The split decision uses the noise-corrected validation error when the targets' noise is
            // known: a node whose remaining error is the records' own Monte Carlo noise gains nothing
            // from splitting (smaller leaves only fit the noise).
            if (std::isfinite(net.training.validationRelativeRmseCorrected))
                error[k] = net.training.validationRelativeRmseCorrected;
            else if (!split.validation.empty())
                error[k] = relativeRmse(net.predict(gatherColumns(xin, split.validation)), gatherColumns(yin, split.validation));
            b.nets[size_t(task.node)] = std::move(net);
            b.trained[size_t(task.node)] = 1;
        };
        if (options.parallel)
            tbb::parallel_for(size_t(0), level.size(), train);
        else
            for (size_t k = 0; k < level.size(); ++k) train(k);

        // Splits that did not help are undone: siblings are consecutive in `level` (pushed in pairs).
        std::vector<char> undone(level.size(), 0);
        for (size_t k = 0; k + 1 < level.size(); ++k) {
            const NodeTask& l = level[k];
            const NodeTask& r = level[k + 1];
            TreeBuild& b = builds[l.job];
            const int p = l.node > 0 ? b.parent[size_t(l.node)] : -1;
            if (p < 0 || r.job != l.job || b.parent[size_t(r.node)] != p || part.minSplitGain <= 0) continue;
            if (!b.trained[size_t(l.node)] || !b.trained[size_t(r.node)]) continue;  // cancelled: handled below
            const double nl = double(b.nets[size_t(l.node)].training.validationSamples);
            const double nr = double(b.nets[size_t(r.node)].training.validationSamples);
            const double parentError = b.tree.nodes[size_t(p)].error;
            if (!(nl + nr > 0) || std::isnan(error[k]) || std::isnan(error[k + 1]) || std::isnan(parentError)) continue;
            const double children = std::sqrt((nl * error[k] * error[k] + nr * error[k + 1] * error[k + 1]) / (nl + nr));
            ++k;  // the pair is decided
            if (children <= (1 - part.minSplitGain) * parentError) continue;
            PartitionNode& node = b.tree.nodes[size_t(p)];
            node.axis = -1;  // a leaf again, predicted by its own network (b.nets[p])
            node.left = node.right = -1;
            b.leaves -= 1;
            undone[k - 1] = undone[k] = 1;
            char line[200];
            std::snprintf(line, sizeof line, ": node %d kept as a leaf: its halves reach %.4f, not below %.4f (%.0f %% under its %.4f)",
                          p, children, (1 - part.minSplitGain) * parentError, 100 * part.minSplitGain, parentError);
            message("object " + std::to_string(jobs[l.job].samples->objectId) + " (" + jobs[l.job].target + ")" + line);
        }

        // Worst nodes first within each tree, so max_leaves goes where the error is.
        std::vector<size_t> order(level.size());
        for (size_t k = 0; k < order.size(); ++k) order[k] = k;
        auto key = [&](size_t k) { return std::isnan(error[k]) ? -1.0 : error[k]; };
        std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
            if (level[a].job != level[b].job) return level[a].job < level[b].job;
            if (key(a) != key(b)) return key(a) > key(b);
            return level[a].node < level[b].node;
        });
        std::vector<NodeTask> next;
        for (size_t k : order) {
            if (undone[k]) continue;
            NodeTask& task = level[k];
            TreeBuild& b = builds[task.job];
            const Job& job = jobs[task.job];
            if (!b.trained[size_t(task.node)]) {
                // Cancelled before this node started: its parent keeps its own network as a leaf.
                const int p = b.parent[size_t(task.node)];
                if (p >= 0 && !b.tree.nodes[size_t(p)].isLeaf()) {
                    b.tree.nodes[size_t(p)].axis = -1;
                    b.leaves -= 1;
                }
                continue;
            }
            PartitionNode& node = b.tree.nodes[size_t(task.node)];
            node.records = int64_t(task.records.size());
            node.error = error[k];
            const double minRecords = std::ceil(part.minRecordsPerWeight * double(archFor(job).numParams()));
            if (!part.enabled() || cancelled() || task.depth >= part.maxDepth || b.leaves >= part.maxLeaves ||
                !(error[k] > part.goal) || double(task.records.size()) < 2 * minRecords)
                continue;
            const ObjectSamples& s = *job.samples;
            const std::optional<SplitPlane> plane = splitNode(s.inputs.data(), s.numInputs, task.records, part.axes);
            if (!plane) continue;
            NodeTask left, right;
            for (uint32_t r : task.records)
                (s.inputs[size_t(r) * size_t(s.numInputs) + size_t(plane->axis)] < plane->split ? left : right)
                    .records.push_back(r);
            if (double(left.records.size()) < minRecords || double(right.records.size()) < minRecords) continue;
            const int li = int(b.tree.nodes.size()), ri = li + 1;
            node.axis = plane->axis;
            node.split = plane->split;
            node.left = li;
            node.right = ri;
            for (NodeTask* c : {&left, &right}) {
                PartitionNode leaf;
                leaf.records = int64_t(c->records.size());
                b.tree.nodes.push_back(leaf);
                b.nets.emplace_back();
                b.trained.push_back(0);
                b.parent.push_back(task.node);
                c->job = task.job;
                c->depth = task.depth + 1;
            }
            left.node = li;
            right.node = ri;
            b.leaves += 1;
            if (observer.onWork) observer.onWork(0, 2 * members * int64_t(leafTrainer.maxEpochs()));
            char line[200];
            std::snprintf(line, sizeof line, ": node %d (%lld records) has validation relative error %.4f > goal %.4g: split at %s < %.6g",
                          task.node, (long long)task.records.size(), error[k], part.goal, splitAxisName(plane->axis),
                          double(plane->split));
            message("object " + std::to_string(s.objectId) + " (" + job.target + ")" + line);
            next.push_back(std::move(left));
            next.push_back(std::move(right));
        }
        level = std::move(next);
    }

    for (size_t j = 0; j < jobs.size(); ++j) {
        ObjectModel& om = result[jobs[j].slot];
        if (!builds[j].trained[0]) {
            om.skipped = true;
            om.message = "object " + std::to_string(jobs[j].samples->objectId) + " (" + jobs[j].target +
                         "): cancelled before training";
            continue;
        }
        om.model = finishTree(builds[j]);
    }
    return result;
}

}  // namespace rrf
