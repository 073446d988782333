#pragma once
/// How the ranks of an MPI job share one `rrf train` (docs/cluster.md): whole objects (with all their
/// targets and kd-tree nodes) go to ranks, each rank trains its objects exactly as a single process
/// would (trainObjects keys every split and initial weight by object id and node, never by position
/// or thread), and rank 0 joins the ranks' results (core/nn/training_part.h) into the run of one
/// process, weights bit for bit.
///
/// Load balance: longest processing time first (Graham's LPT rule) with an object's record count as
/// its cost — an epoch of either trainer costs time linear in the records, and the objects of a scene
/// differ by an order of magnitude (a floor against a small block's faces). The
/// objects are taken in decreasing cost and each goes to the rank with the least cost so far, which
/// keeps the largest rank within 4/3 of the optimum split. Epoch counts (early stops) and kd-tree
/// growth are not known in advance and are not modelled. The rule is deterministic, so every rank
/// computes the same assignment from the same dataset without a message.

#include <cstdint>
#include <vector>

#include "core/nn/object_training.h"

namespace rrf {

/// Rank of each item under the LPT rule: items in decreasing cost (equal costs: lower index first),
/// each to the rank with the least total cost so far (equal totals: the lower rank). Throws
/// std::invalid_argument unless ranks ≥ 1.
std::vector<int> assignLongestFirst(const std::vector<uint64_t>& costs, int ranks);

/// The object ids trainObjects trains for `samples` and `options`, in its order: options.objects, or
/// every sample's object id.
std::vector<int> trainingObjectOrder(const std::vector<ObjectSamples>& samples, const ObjectTrainingOptions& options);

/// The records of each object of `order` in `samples` (0 for an id without samples): the cost the
/// assignment balances.
std::vector<uint64_t> trainingCosts(const std::vector<ObjectSamples>& samples, const std::vector<int>& order);

/// Networks trainObjects makes per object for `options` (2 for separate targets, else 1).
int networksPerObject(const ObjectTrainingOptions& options);

}  // namespace rrf
