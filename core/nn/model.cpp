#include "core/nn/model.h"

#include "core/nn/block_forward.h"
#include "core/nn/ensemble.h"
#include "core/nn/model_forward.h"
#include "core/nn/training_loss.h"
#include "core/util/error.h"
#include "core/util/relative_error.h"

#include <cmath>
#include <stdexcept>
#include <type_traits>

namespace rrf {

namespace {


MatX<float> gather(const Eigen::Ref<const MatX<float>>& m, const std::vector<uint32_t>& idx) {
    MatX<float> out(m.rows(), Eigen::Index(idx.size()));
    for (size_t j = 0; j < idx.size(); ++j) out.col(Eigen::Index(j)) = m.col(idx[j]);
    return out;
}

/// RMSE in raw units of the model on the columns `idx`.
double rawRmse(const NetworkModel& model, const Eigen::Ref<const MatX<float>>& x,
               const Eigen::Ref<const MatX<float>>& y, const std::vector<uint32_t>& idx) {
    if (idx.empty()) return std::numeric_limits<double>::quiet_NaN();
    const MatX<float> pred = model.predict(gather(x, idx));
    const MatX<float> ref = gather(y, idx);
    return std::sqrt((pred - ref).cast<double>().squaredNorm() / double(pred.size()));
}

}  // namespace

template <typename S>
static MatX<S> predictImpl(const NetworkModel& m, const Eigen::Ref<const MatX<S>>& raw) {
    if (raw.rows() != m.rawInputs())
        throw std::invalid_argument("predict: expected " + std::to_string(m.rawInputs()) + " input rows, got " +
                                    std::to_string(raw.rows()));
    MatX<S> out(m.arch.outputs, raw.cols());
    forwardChunks<S>(m, raw, [&](Eigen::Index c, Eigen::Index nc, std::vector<MatX<S>>& acts) {
        m.outputScaler.invert(acts.back());
        out.middleCols(c, nc) = acts.back();
    });
    return out;
}

MatX<float> NetworkModel::predict(const Eigen::Ref<const MatX<float>>& rawInputs) const {
    return predictImpl<float>(*this, rawInputs);
}

MatX<double> NetworkModel::predictDouble(const Eigen::Ref<const MatX<double>>& rawInputs) const {
    return predictImpl<double>(*this, rawInputs);
}

void NetworkModel::validate() const {
    arch.validate();
    if (params.size() != arch.numParams())
        throw std::invalid_argument("model has " + std::to_string(params.size()) + " parameters, the " +
                                    arch.describe() + " architecture needs " + std::to_string(arch.numParams()));
    if (encoding.isIdentity()) {
        if (encodingParams.size() != 0)
            throw std::invalid_argument("model has " + std::to_string(encodingParams.size()) +
                                        " encoding parameters but no input encoding");
    } else {
        if (encoding.outputs() != arch.inputs)
            throw std::invalid_argument("the input encoding " + encoding.describe() + " writes " +
                                        std::to_string(encoding.outputs()) + " features, the " + arch.describe() +
                                        " network reads " + std::to_string(arch.inputs));
        if (encodingParams.size() != encoding.numParams())
            throw std::invalid_argument("model has " + std::to_string(encodingParams.size()) +
                                        " encoding parameters, the encoding " + encoding.describe() + " needs " +
                                        std::to_string(encoding.numParams()));
        for (Eigen::Index i = 0; i < encodingParams.size(); ++i)
            if (!std::isfinite(encodingParams[i]))
                throw std::invalid_argument("non-finite encoding parameter at index " + std::to_string(i));
    }
    if (encoding.isIdentity() && encoding.derived.any() && encoding.inputs > 0 && encoding.scaledInputs() != arch.inputs)
        throw std::invalid_argument("the network reads " + std::to_string(arch.inputs) + " inputs, its " +
                                    std::to_string(encoding.inputs) + " record inputs and " +
                                    std::to_string(encoding.derived.count()) + " derived inputs are " +
                                    std::to_string(encoding.scaledInputs()));
    if (rawInputs() < 1) throw std::invalid_argument("the network reads no record inputs");
    const int in = scaledInputs();
    if (inputScaler.offset.size() != in || inputScaler.scale.size() != in ||
        outputScaler.offset.size() != arch.outputs || outputScaler.scale.size() != arch.outputs)
        throw std::invalid_argument("model normalisation sizes do not match the architecture");
    for (Eigen::Index i = 0; i < params.size(); ++i)
        if (!std::isfinite(params[i])) throw std::invalid_argument("non-finite weight at index " + std::to_string(i));
    auto checkScaler = [](const MinMaxScaler& s, const char* what) {
        for (Eigen::Index i = 0; i < s.size(); ++i)
            if (!std::isfinite(s.offset[i]) || !std::isfinite(s.scale[i]) || s.scale[i] == 0.0)
                throw std::invalid_argument(std::string("invalid ") + what + " normalisation at feature " +
                                            std::to_string(i));
    };
    checkScaler(inputScaler, "input");
    checkScaler(outputScaler, "output");
    checkMemberBiases(*this);
}

PartitionedNetwork::PartitionedNetwork(NetworkModel single)
    : tree(PartitionTree::singleLeaf(single.training.trainSamples + single.training.validationSamples +
                                     single.training.testSamples)) {
    leaves.push_back(std::move(single));
}

int64_t modelPayloadBytes(const NetworkModel& model) {
    const int64_t encoding = model.encoding.isIdentity() ? 0 : model.encoding.numParams();
    return int64_t(sizeof(double)) *
           (int64_t(model.arch.numParams()) + 2 * int64_t(model.scaledInputs()) + 2 * int64_t(model.arch.outputs) + encoding);
}

int64_t PartitionedNetwork::numParams() const {
    int64_t n = 0;
    for (const NetworkModel& m : leaves) n += m.numParams();
    return n;
}

std::vector<int> PartitionedNetwork::findLeaves(const Eigen::Ref<const MatX<float>>& raw) const {
    std::vector<int> leaf(size_t(raw.cols()), 0);
    if (tree.nodes.size() <= 1) return leaf;
    VecX<float> col(raw.rows());
    for (Eigen::Index c = 0; c < raw.cols(); ++c) {
        col = raw.col(c);
        leaf[size_t(c)] = tree.findLeaf(col.data());
    }
    return leaf;
}

namespace {

/// Columns of `raw` grouped by leaf (ascending within each leaf), predicted leaf by leaf.
template <typename S>
MatX<S> predictPartitioned(const PartitionedNetwork& p, const Eigen::Ref<const MatX<S>>& raw,
                           const std::vector<int>& leafOf) {
    const MlpArch& a = p.arch();
    MatX<S> out(a.outputs, raw.cols());
    std::vector<std::vector<Eigen::Index>> cols(p.leaves.size());
    for (Eigen::Index c = 0; c < raw.cols(); ++c) cols[size_t(leafOf[size_t(c)])].push_back(c);
    for (size_t l = 0; l < cols.size(); ++l) {
        if (cols[l].empty()) continue;
        MatX<S> x(raw.rows(), Eigen::Index(cols[l].size()));
        for (size_t k = 0; k < cols[l].size(); ++k) x.col(Eigen::Index(k)) = raw.col(cols[l][k]);
        MatX<S> y;
        if constexpr (std::is_same_v<S, float>) y = p.leaves[l].predict(x);
        else y = p.leaves[l].predictDouble(x);
        for (size_t k = 0; k < cols[l].size(); ++k) out.col(cols[l][k]) = y.col(Eigen::Index(k));
    }
    return out;
}

}  // namespace

MatX<float> PartitionedNetwork::predict(const Eigen::Ref<const MatX<float>>& raw) const {
    if (leaves.size() == 1) return leaves.front().predict(raw);
    if (raw.rows() != rawInputs()) return leaves.front().predict(raw);  // throws the size message
    return predictPartitioned<float>(*this, raw, findLeaves(raw));
}

MatX<double> PartitionedNetwork::predictDouble(const Eigen::Ref<const MatX<double>>& raw) const {
    if (leaves.size() == 1) return leaves.front().predictDouble(raw);
    if (raw.rows() != rawInputs()) return leaves.front().predictDouble(raw);
    const MatX<float> asFloat = raw.cast<float>();
    return predictPartitioned<double>(*this, raw, findLeaves(asFloat));
}

void PartitionedNetwork::validate() const {
    if (leaves.empty()) throw std::invalid_argument("partitioned network has no leaf networks");
    tree.validate(rawInputs());
    if (int(leaves.size()) != tree.leafCount())
        throw std::invalid_argument("partition tree has " + std::to_string(tree.leafCount()) + " leaves but " +
                                    std::to_string(leaves.size()) + " networks");
    for (size_t l = 0; l < leaves.size(); ++l) {
        const NetworkModel& m = leaves[l];
        m.validate();
        if (!(m.arch == leaves.front().arch) || m.encoding != leaves.front().encoding ||
            m.objectId != leaves.front().objectId || m.target != leaves.front().target)
            throw std::invalid_argument("leaf " + std::to_string(l) +
                                        " differs from leaf 0 in architecture, input encoding, object or target");
    }
}

double seamJump(const PartitionedNetwork& model, const Eigen::Ref<const MatX<float>>& raw) {
    const PartitionTree& t = model.tree;
    std::vector<Eigen::Index> column;
    std::vector<std::pair<int, float>> plane;  // (axis, split) per projected point
    for (Eigen::Index c = 0; c < raw.cols(); ++c) {
        VecX<float> x = raw.col(c);
        int i = 0;
        while (!t.nodes[size_t(i)].isLeaf()) {
            const PartitionNode& n = t.nodes[size_t(i)];
            column.push_back(c);
            plane.emplace_back(n.axis, n.split);
            i = x[n.axis] < n.split ? n.left : n.right;
        }
    }
    if (column.empty()) return 0.0;
    MatX<float> below(raw.rows(), Eigen::Index(column.size())), on(raw.rows(), Eigen::Index(column.size()));
    for (size_t k = 0; k < column.size(); ++k) {
        below.col(Eigen::Index(k)) = raw.col(column[k]);
        on.col(Eigen::Index(k)) = raw.col(column[k]);
        below(plane[k].first, Eigen::Index(k)) = std::nextafter(plane[k].second, -INFINITY);
        on(plane[k].first, Eigen::Index(k)) = plane[k].second;
    }
    return relativeRmse(model.predict(below), model.predict(on));
}

double relativeRmse(const Eigen::Ref<const MatX<float>>& p, const Eigen::Ref<const MatX<float>>& t) {
    if (p.size() == 0) return std::numeric_limits<double>::quiet_NaN();
    double sum = 0;
    for (Eigen::Index c = 0; c < p.cols(); ++c)
        for (Eigen::Index r = 0; r < p.rows(); ++r) {
            const double d = (double(p(r, c)) - double(t(r, c))) / (std::fabs(double(t(r, c))) + kRelativeEpsilon);
            sum += d * d;
        }
    return std::sqrt(sum / double(p.size()));
}

NetworkModel fitNetwork(const MlpArch& arch, const TrainerConfig& cfg, const Eigen::Ref<const MatX<float>>& inputs,
                        const Eigen::Ref<const MatX<float>>& targets, const TrainObserver& observer, uint64_t stream) {
    return fitNetwork(arch, cfg, inputs, targets, MatX<float>(), observer, stream);
}

NetworkModel fitNetwork(const MlpArch& arch, const TrainerConfig& cfg, const Eigen::Ref<const MatX<float>>& inputs,
                        const Eigen::Ref<const MatX<float>>& targets, const MatX<float>& targetVariance,
                        const TrainObserver& observer, uint64_t stream) {
    return fitNetwork(arch, InputEncoding(), cfg, inputs, targets, targetVariance, observer, stream);
}

NetworkModel fitNetwork(const MlpArch& arch, const InputEncoding& encoding, const TrainerConfig& cfg,
                        const Eigen::Ref<const MatX<float>>& inputs, const Eigen::Ref<const MatX<float>>& targets,
                        const MatX<float>& targetVariance, const TrainObserver& observer, uint64_t stream,
                        int members) {
    arch.validate();
    if (targetVariance.size() > 0 && (targetVariance.rows() != targets.rows() || targetVariance.cols() != targets.cols()))
        throw std::invalid_argument("fitNetwork: the target variance's shape differs from the targets'");
    const bool encoded = !encoding.isIdentity();
    if (encoded && (inputs.rows() != encoding.inputs || encoding.outputs() != arch.inputs))
        throw std::invalid_argument("fitNetwork: data has " + std::to_string(inputs.rows()) + " inputs, the encoding " +
                                    encoding.describe() + " reads " + std::to_string(encoding.inputs) + " and writes " +
                                    std::to_string(encoding.outputs()) + ", the network " + arch.describe());
    if (encoded && encoding.numParams() > 0 && cfg.type != TrainerType::Adam)
        throw SettingError("network.encoding", "the encoding " + encoding.describe() +
                                                   " has trainable parameters, which only the adam trainer trains "
                                                   "(trainer.type is " + cfg.typeName() + ")");
    if (encoded && encoding.numParams() > 0 && members > 1)
        throw SettingError("network.ensemble", ensembleEncodingRefusal(encoding.describe(), members));
    if ((!encoded && inputs.rows() + encoding.derived.count() != arch.inputs) || targets.rows() != arch.outputs)
        throw std::invalid_argument("fitNetwork: data has " + std::to_string(inputs.rows()) + " inputs" +
                                    (encoding.derived.any() ? " (+" + encoding.derived.describe() + ")" : std::string()) +
                                    " and " + std::to_string(targets.rows()) + " targets, the network " + arch.describe());
    if (inputs.cols() != targets.cols()) throw std::invalid_argument("fitNetwork: input and target counts differ");
    if (inputs.cols() == 0) throw std::invalid_argument("fitNetwork: no samples");
    if (!inputs.allFinite() || !targets.allFinite())
        throw std::invalid_argument("fitNetwork: non-finite values in the training data");

    NetworkModel model;
    model.arch = arch;
    model.encoding = encoding;
    model.encoding.inputs = int(inputs.rows());
    model.trainer = cfg;
    // Relative L2 weighs each record by its own noisy target, which pulls the fit low by about 2σ²;
    // the network trains on targets raised by that amount where the noise is known (training_loss.h).
    // The reported RMSEs below stay against the records as they are.
    const bool debias = cfg.type == TrainerType::Adam && cfg.adam.loss == AdamLoss::RelativeL2 && cfg.adam.debiasTargets &&
                        targetVariance.size() > 0;
    const MatX<float> debiased = debias ? debiasedRelativeL2Targets(targets, targetVariance) : MatX<float>();
    const Eigen::Ref<const MatX<float>> fitTargets = debias ? Eigen::Ref<const MatX<float>>(debiased) : targets;

    // Derived inputs come from the raw records (their unit view and normal), before the scaler that
    // then normalises them like any other input (nn/derived_inputs.h).
    MatX<float> withDerived;
    if (encoding.derived.any()) encoding.derived.append<float>(inputs, withDerived);
    const Eigen::Ref<const MatX<float>> xs = encoding.derived.any() ? Eigen::Ref<const MatX<float>>(withDerived) : inputs;
    model.inputScaler = MinMaxScaler::fit(xs);
    model.outputScaler = MinMaxScaler::fit(fitTargets);

    const DataSplit split = splitSamples(size_t(inputs.cols()), cfg.seed(), stream);
    TrainingData d;
    d.xTrain = gather(xs, split.train);
    d.yTrain = gather(fitTargets, split.train);
    d.xValidation = gather(xs, split.validation);
    d.yValidation = gather(fitTargets, split.validation);
    d.xTest = gather(xs, split.test);
    d.yTest = gather(fitTargets, split.test);
    for (MatX<float>* x : {&d.xTrain, &d.xValidation, &d.xTest}) model.inputScaler.apply(*x);
    for (MatX<float>* y : {&d.yTrain, &d.yValidation, &d.yTest}) model.outputScaler.apply(*y);
    if (targetVariance.size() > 0) d.vValidation = gather(targetVariance, split.validation);

    model.params = initialParams(arch, cfg.seed(), stream);
    if (encoded && encoding.numParams() > 0) {
        model.encodingParams = encoding.initialParams(cfg.seed(), stream);
        model.training = trainAdam(arch, model.encoding, cfg.adam, d, model.outputScaler, model.params, model.encodingParams, observer);
        model.training.memberEpochs = model.training.epochs;
    } else {
        // A fixed encoding is a function of the inputs alone: encode once, train the MLP on the features.
        if (encoded)
            for (MatX<float>* x : {&d.xTrain, &d.xValidation, &d.xTest}) {
                MatX<float> features;
                encoding.forward<float>(nullptr, *x, features);
                *x = std::move(features);
            }
        model.training = trainEnsemble(model.arch, cfg, d, model.outputScaler, model.params, members, stream, observer,
                                       &model.memberOutputBias);
    }

    model.errors.train = rawRmse(model, inputs, targets, split.train);
    model.errors.validation = rawRmse(model, inputs, targets, split.validation);
    model.errors.test = rawRmse(model, inputs, targets, split.test);
    return model;
}

}  // namespace rrf
