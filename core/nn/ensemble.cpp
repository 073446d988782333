#include "core/nn/ensemble.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/nn/training_loss.h"
#include "core/util/rng.h"

namespace rrf {

MlpArch ensembleArch(const MlpArch& member, int members) {
    if (members < 1) throw std::invalid_argument("ensembleArch: " + std::to_string(members) + " members (at least 1)");
    MlpArch a = member;
    for (int& h : a.hidden) h *= members;
    return a;
}

VecX<double> mergeEnsemble(const MlpArch& member, const std::vector<VecX<double>>& params) {
    if (params.empty()) throw std::invalid_argument("mergeEnsemble: no members");
    for (const VecX<double>& p : params)
        if (p.size() != member.numParams())
            throw std::invalid_argument("mergeEnsemble: a member has " + std::to_string(p.size()) + " parameters, the " +
                                        member.describe() + " network " + std::to_string(member.numParams()));
    const int k = int(params.size());
    const MlpArch merged = ensembleArch(member, k);
    VecX<double> out = VecX<double>::Zero(merged.numParams());
    const int last = member.numLayers() - 1;
    for (int l = 0; l <= last; ++l) {
        const Eigen::Index in = member.layerInputs(l), outs = member.layerOutputs(l);
        const Eigen::Index mIn = merged.layerInputs(l), mOut = merged.layerOutputs(l);
        Eigen::Map<MatX<double>> W(out.data() + merged.weightOffset(l), mOut, mIn);
        Eigen::Map<VecX<double>> b(out.data() + merged.biasOffset(l), mOut);
        for (int m = 0; m < k; ++m) {
            const Eigen::Map<const MatX<double>> w(params[size_t(m)].data() + member.weightOffset(l), outs, in);
            const Eigen::Map<const VecX<double>> bias(params[size_t(m)].data() + member.biasOffset(l), outs);
            // Rows: member m's units (all outputs in the last layer). Columns: all inputs in the first
            // layer, member m's units of the layer below otherwise.
            const Eigen::Index row = l == last ? 0 : m * outs;
            const Eigen::Index col = l == 0 ? 0 : m * in;
            if (l == last) {
                // += : with no hidden layers the last layer is also the first, whose columns all members share.
                W.block(row, col, outs, in) += w / double(k);
                b += bias / double(k);
            } else {
                W.block(row, col, outs, in) = w;
                b.segment(row, outs) = bias;
            }
        }
    }
    return out;
}

VecX<double> memberOutputBiases(const MlpArch& member, const std::vector<VecX<double>>& params) {
    const int last = member.numLayers() - 1;
    const Eigen::Index outs = member.outputs;
    VecX<double> out(Eigen::Index(params.size()) * outs);
    for (size_t m = 0; m < params.size(); ++m) {
        if (params[m].size() != member.numParams())
            throw std::invalid_argument("memberOutputBiases: a member has " + std::to_string(params[m].size()) +
                                        " parameters, the " + member.describe() + " network " +
                                        std::to_string(member.numParams()));
        out.segment(Eigen::Index(m) * outs, outs) = params[m].segment(member.biasOffset(last), outs);
    }
    return out;
}

std::string ensembleEncodingRefusal(const std::string& encodingDescription, int members) {
    return "the encoding " + encodingDescription + " has trainable parameters, which the " + std::to_string(members) +
           " members of an ensemble cannot share (they merge into one network only over one fixed input map); use "
           "ensemble 1 or a fixed encoding";
}

uint64_t ensembleMemberSeed(uint64_t seed, int member) {
    constexpr uint64_t kEnsembleStream = 0x454E53454D424C45ULL;  // "ENSEMBLE"
    return member == 0 ? seed : Rng(seed, kEnsembleStream, uint64_t(member)).nextU64();
}

namespace {

/// `cfg` with every trainer's seed replaced by `seed` (the split is drawn before, by the caller).
TrainerConfig withSeed(TrainerConfig cfg, uint64_t seed) {
    for (TrainerCommon* c : cfg.everyTrainer()) c->seed = seed;
    return cfg;
}

/// Normalised outputs of the network on `x` in double, in chunks (the validation monitor's input).
MatX<double> outputs(const MlpArch& arch, const VecX<float>& w, const MatX<float>& x) {
    constexpr Eigen::Index kChunk = 4096;
    MatX<double> out(arch.outputs, x.cols());
    std::vector<MatX<float>> acts;
    for (Eigen::Index c = 0; c < x.cols(); c += kChunk) {
        const Eigen::Index n = std::min(kChunk, x.cols() - c);
        mlpForward<float>(arch, w.data(), x.middleCols(c, n), acts);
        out.middleCols(c, n) = acts.back().cast<double>();
    }
    return out;
}

/// Mean loss per entry of normalised outputs `p` against `y` (NaN for an empty set), as the trainers report it.
double mergedLoss(const TrainingLoss<double>& loss, const MatX<double>& p, const MatX<float>& y) {
    if (y.cols() == 0) return std::numeric_limits<double>::quiet_NaN();
    return loss.evaluate(p, y.cast<double>(), nullptr, 1.0) / (double(y.cols()) * double(y.rows()));
}

/// Overwrites the losses and validation figures of `res` with those of the network (arch, params).
void scoreMerged(TrainResult& res, const MlpArch& arch, const VecX<double>& params, const TrainerConfig& cfg,
                 const TrainingData& data, const MinMaxScaler& outputScaler) {
    // Levenberg–Marquardt minimises and reports the normalised MSE; Adam its configured loss.
    const AdamLoss kind = cfg.type == TrainerType::Adam ? cfg.adam.loss : AdamLoss::Mse;
    const TrainingLoss<double> loss(kind, outputScaler);
    const VecX<float> w = params.cast<float>();
    res.trainLoss = mergedLoss(loss, outputs(arch, w, data.xTrain), data.yTrain);
    res.testLoss = mergedLoss(loss, outputs(arch, w, data.xTest), data.yTest);
    const MatX<double> p = outputs(arch, w, data.xValidation);
    res.validationLoss = mergedLoss(loss, p, data.yValidation);
    recordValidation(res, kind, outputScaler, data, cfg.errorGoal(), p);
}

}  // namespace

TrainResult trainEnsemble(MlpArch& arch, const TrainerConfig& cfg, const TrainingData& data,
                          const MinMaxScaler& outputScaler, VecX<double>& params, int members, uint64_t stream,
                          const TrainObserver& observer, VecX<double>* memberBiases) {
    if (memberBiases) memberBiases->resize(0);
    if (members < 1) throw std::invalid_argument("trainEnsemble: " + std::to_string(members) + " members (at least 1)");
    std::vector<VecX<double>> kept;
    std::vector<double> figures;
    TrainResult first;
    int64_t epochs = 0;
    for (int m = 0; m < members; ++m) {
        if (m > 0 && observer.cancelled()) break;
        const uint64_t seed = ensembleMemberSeed(cfg.seed(), m);
        VecX<double> p = m == 0 ? params : initialParams(arch, seed, stream);
        TrainObserver memberObserver = observer;
        if (observer.onEpoch)
            memberObserver.onEpoch = [&observer, m](const EpochRecord& r) {
                EpochRecord marked = r;
                marked.member = m;
                observer.onEpoch(marked);
            };
        TrainResult r = trainNetwork(arch, withSeed(cfg, seed), data, outputScaler, p, memberObserver);
        epochs += r.epochs;
        if (m > 0 && r.cancelled) break;
        figures.push_back(r.judgedValidationError());
        kept.push_back(std::move(p));
        if (m == 0) first = std::move(r);
        else first.seconds += r.seconds;
    }
    first.members = int(kept.size());
    first.memberEpochs = epochs;
    if (int(kept.size()) < members && !first.cancelled) {
        // Cancelled after the first member: the kept ensemble is smaller than asked, and says so.
        first.cancelled = true;
        first.stopReason = "cancelled";
        first.messages.push_back("cancelled: " + std::to_string(kept.size()) + " of " + std::to_string(members) +
                                 " ensemble members trained");
        if (observer.onMessage) observer.onMessage(first.messages.back());
    }
    if (kept.size() == 1) {
        params = std::move(kept.front());
        return first;
    }
    const MlpArch member = arch;
    arch = ensembleArch(member, int(kept.size()));
    params = mergeEnsemble(member, kept);
    // Without hidden layers the members merge into one linear map and cannot be told apart.
    if (memberBiases && !member.hidden.empty()) *memberBiases = memberOutputBiases(member, kept);
    scoreMerged(first, arch, params, cfg, data, outputScaler);
    std::string line = "ensemble of " + std::to_string(kept.size()) + " " + member.describe() + " networks: members' validation error";
    for (double f : figures) {
        char buf[32];
        std::snprintf(buf, sizeof buf, " %.4g", f);
        line += buf;
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, ", their mean's %.4g", first.judgedValidationError());
    first.messages.push_back(line + buf);
    if (observer.onMessage) observer.onMessage(first.messages.back());
    return first;
}

}  // namespace rrf
