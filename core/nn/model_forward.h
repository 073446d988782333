#pragma once
/// The forward pass of a NetworkModel over raw record inputs, shared by its prediction
/// (NetworkModel::predict) and its members' (NetworkModel::predictMembers): derived inputs, input
/// scaler, encoding and the MLP (member by member for a merged ensemble, nn/block_forward.h), in
/// fixed chunks, so the result depends only on the stored bits and the inputs.

#include <algorithm>
#include <vector>

#include "core/nn/block_forward.h"
#include "core/nn/model.h"

namespace rrf {

/// Inference chunk: 20-10 activations of 2048 samples stay in L2, which beats one huge GEMM.
constexpr Eigen::Index kPredictChunk = 2048;

/// Runs `m` over the columns of `raw` (m.rawInputs() rows, checked by the caller) chunk by chunk
/// and calls use(first column, columns, activations) for each (acts as mlpForward leaves them,
/// normalised outputs last).
template <typename S, typename Use>
void forwardChunks(const NetworkModel& m, const Eigen::Ref<const MatX<S>>& raw, Use use) {
    const VecX<S> w = m.params.cast<S>();
    const VecX<S> e = m.encodingParams.cast<S>();
    const bool encoded = !m.encoding.isIdentity();
    // A merged ensemble (nn/ensemble.h) runs member by member: K·h² per hidden layer, not K²·h².
    const int members = blockMembers<S>(m.arch, w.data());
    MatX<S> x, features;
    std::vector<MatX<S>> acts;
    const DerivedInputs& derived = m.encoding.derived;
    for (Eigen::Index c = 0; c < raw.cols(); c += kPredictChunk) {
        const Eigen::Index nc = std::min(kPredictChunk, raw.cols() - c);
        if (derived.any()) derived.append<S>(raw.middleCols(c, nc), x);  // from the raw unit vectors
        else x = raw.middleCols(c, nc);
        m.inputScaler.apply(x);
        if (encoded) m.encoding.forward<S>(e.data(), x, features);
        blockForward<S>(m.arch, members, w.data(), encoded ? features : x, acts);
        use(c, nc, acts);
    }
}

}  // namespace rrf
