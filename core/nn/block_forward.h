#pragma once
/// Forward passes of merged ensembles (nn/ensemble.h) member by member.
///
/// The mean of K networks merged into one has hidden-to-hidden weight matrices diag(W₁, …, W_K):
/// a dense forward pass multiplies K²·h_l·h_{l−1} weights per sample in each of them, of which only
/// K·h_l·h_{l−1} are not zero. blockForward multiplies each member's block with its own units (one
/// small GEMM per member and layer); the first layer (every member reads every input) and the output
/// layer (the members' mean) stay one dense GEMM each. Skipping exact zeros changes no sum but for
/// the order of rounding, so the activations are mlpForward's to float rounding.
///
/// The structure is read from the weights, not stored: blockMembers finds the largest K for which
/// every weight outside the diagonal blocks is exactly zero. That also makes it safe for any
/// network: a plain one has none (K = 1, the dense pass), and a network that happens to be block
/// diagonal is evaluated exactly as its zeros allow.

#include <vector>

#include "core/nn/mlp.h"

namespace rrf {

/// The number of diagonal blocks K ≥ 2 of every hidden-to-hidden weight matrix of `params` (layout
/// of `arch`), the largest that divides every hidden width; 1 when there is none or `arch` has
/// fewer than two hidden layers (there is then no such matrix, nothing to skip). O(P), returning at
/// the first weight that rules a K out.
template <typename S>
int blockMembers(const MlpArch& arch, const S* params);

/// mlpForward (nn/mlp.h) for a network whose hidden-to-hidden layers have `members` diagonal blocks
/// (blockMembers); `members` = 1 is mlpForward itself. Same activations to rounding.
template <typename S>
void blockForward(const MlpArch& arch, int members, const S* params, const Eigen::Ref<const MatX<S>>& x,
                  std::vector<MatX<S>>& acts);

}  // namespace rrf
