// The members of a merged ensemble, recovered from its weights and stored output biases
// (nn/ensemble.h, NetworkModel::predictMembers).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/nn/model.h"
#include "core/nn/model_forward.h"

namespace rrf {

void checkMemberBiases(const NetworkModel& m) {
    if (m.memberOutputBias.size() == 0) return;
    const Eigen::Index outs = m.arch.outputs;
    if (m.arch.hidden.empty())
        throw std::invalid_argument("member output biases are stored for a network without hidden layers, "
                                    "whose members cannot be told apart");
    if (outs < 1 || m.memberOutputBias.size() % outs != 0)
        throw std::invalid_argument("there are " + std::to_string(m.memberOutputBias.size()) +
                                    " member output biases, not a multiple of the " + std::to_string(outs) + " outputs");
    const int k = int(m.memberOutputBias.size() / outs);
    if (k < 2 || k != m.training.members)
        throw std::invalid_argument("member output biases for " + std::to_string(k) + " members, the training record says " +
                                    std::to_string(m.training.members) + " (at least 2)");
    for (int h : m.arch.hidden)
        if (h % k != 0)
            throw std::invalid_argument("a hidden layer of " + std::to_string(h) + " units cannot hold " +
                                        std::to_string(k) + " members");
    const int last = m.arch.numLayers() - 1;
    for (Eigen::Index o = 0; o < outs; ++o) {
        double mean = 0;
        for (int j = 0; j < k; ++j) {
            const double b = m.memberOutputBias[Eigen::Index(j) * outs + o];
            if (!std::isfinite(b)) throw std::invalid_argument("non-finite member output bias of member " + std::to_string(j));
            mean += b;
        }
        mean /= double(k);
        const double merged = m.params[m.arch.biasOffset(last) + o];
        // The merged bias is their mean (nn/ensemble.h): anything else is not these members' biases.
        if (std::abs(mean - merged) > 1e-9 * (1.0 + std::abs(merged)))
            throw std::invalid_argument("the member output biases average to " + std::to_string(mean) + " at output " +
                                        std::to_string(o) + ", the network's output bias is " + std::to_string(merged));
    }
}

std::vector<MatX<float>> NetworkModel::predictMembers(const Eigen::Ref<const MatX<float>>& raw) const {
    const int k = spreadMembers();
    if (k == 0) return {};
    if (raw.rows() != rawInputs())
        throw std::invalid_argument("predictMembers: expected " + std::to_string(rawInputs()) + " input rows, got " +
                                    std::to_string(raw.rows()));
    const int last = arch.numLayers() - 1;
    const Eigen::Index outs = arch.outputs, width = arch.layerInputs(last), h = width / k;
    const VecX<float> wOut = params.segment(arch.weightOffset(last), outs * width).cast<float>();
    const Eigen::Map<const MatX<float>> W(wOut.data(), outs, width);
    std::vector<MatX<float>> out(size_t(k), MatX<float>(outs, raw.cols()));
    MatX<float> y;
    forwardChunks<float>(*this, raw, [&](Eigen::Index c, Eigen::Index nc, std::vector<MatX<float>>& acts) {
        const MatX<float>& hidden = acts[size_t(last) - 1];
        for (int m = 0; m < k; ++m) {
            // Member m: K·W'_m h_m + b_m, the output the merge divided by K and averaged.
            const VecX<float> b = memberOutputBias.segment(Eigen::Index(m) * outs, outs).cast<float>();
            y.noalias() = float(k) * (W.middleCols(Eigen::Index(m) * h, h) * hidden.middleRows(Eigen::Index(m) * h, h));
            y.colwise() += b;
            outputScaler.invert(y);
            out[size_t(m)].middleCols(c, nc) = y;
        }
    });
    return out;
}

int PartitionedNetwork::spreadMembers() const {
    int k = leaves.empty() ? 0 : leaves.front().spreadMembers();
    for (const NetworkModel& m : leaves) k = std::min(k, m.spreadMembers());
    return k;
}

std::vector<MatX<float>> PartitionedNetwork::predictMembers(const Eigen::Ref<const MatX<float>>& raw) const {
    const int k = spreadMembers();
    if (k == 0) return {};
    if (leaves.size() == 1) return leaves.front().predictMembers(raw);
    if (raw.rows() != rawInputs()) return leaves.front().predictMembers(raw);  // throws the size message
    const std::vector<int> leafOf = findLeaves(raw);
    std::vector<MatX<float>> out(size_t(k), MatX<float>(arch().outputs, raw.cols()));
    std::vector<std::vector<Eigen::Index>> cols(leaves.size());
    for (Eigen::Index c = 0; c < raw.cols(); ++c) cols[size_t(leafOf[size_t(c)])].push_back(c);
    for (size_t l = 0; l < cols.size(); ++l) {
        if (cols[l].empty()) continue;
        MatX<float> x(raw.rows(), Eigen::Index(cols[l].size()));
        for (size_t j = 0; j < cols[l].size(); ++j) x.col(Eigen::Index(j)) = raw.col(cols[l][j]);
        // A leaf with more members than another contributes its first k (each is a trained network).
        const std::vector<MatX<float>> y = leaves[l].predictMembers(x);
        for (int m = 0; m < k; ++m)
            for (size_t j = 0; j < cols[l].size(); ++j) out[size_t(m)].col(cols[l][j]) = y[size_t(m)].col(Eigen::Index(j));
    }
    return out;
}

}  // namespace rrf
