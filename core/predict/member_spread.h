#pragma once
/// The spread of an ensemble's members over what the networks give a pixel (docs/design.md §14d).
///
/// A merged ensemble (core/nn/ensemble.h) predicts the mean of K networks trained from different
/// initial weights and mini-batch orders; where they disagree the mean is less certain (the "deep
/// ensembles" of Lakshminarayanan et al. 2017). A pixel's network part is one or two terms, each a
/// network's three output rows: the global network's, or the direct and indirect networks' (only
/// the indirect one with exact direct light). Its spread is, per channel,
///     one network for both (joint)   the standard deviation over the members of their sum,
///     two networks                   sqrt(var₁ + var₂): they were trained apart, so independently,
/// each standard deviation over the K members with 1/K (the members' own spread, not the standard
/// error of their mean). It needs no reference, so it also answers for lights that have none;
/// core/eval/uncertainty.h measures how well it ranks the true error.

#include <vector>

#include "core/nn/model.h"

namespace rrf {

/// One term of a pixel's network part: a network and the first of its three output rows.
struct SpreadTerm {
    const PartitionedNetwork* net = nullptr;
    int row = 0;
};

/// Per column of `rawInputs` (inputs × N) the members' standard deviation of the sum of `terms`
/// (3 × N, radiance units) into `sd`. Returns false (leaving `sd` untouched) when `terms` is empty
/// or one of its networks has no members' outputs (PartitionedNetwork::spreadMembers() = 0: a single
/// network, or an ensemble saved before its members' biases were stored).
bool memberSpread(const std::vector<SpreadTerm>& terms, const Eigen::Ref<const MatX<float>>& rawInputs, MatX<float>& sd);

}  // namespace rrf
