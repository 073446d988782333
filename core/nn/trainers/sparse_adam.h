#pragma once
/// Adam for an input encoding's parameters, updated sparsely as instant-NGP does: only the entries a
/// batch touched see a step, each once, and their gradient is cleared afterwards; an untouched entry
/// keeps its value, its moments and its step count. No weight decay (it would shrink unvisited table
/// cells).
///
/// Each entry has its own step count (tiny-cuda-nn does the same: "some parameters might see fewer
/// steps than others"), and the bias corrections 1 − β₁ᵗ, 1 − β₂ᵗ use it. With the trainer's global
/// step instead, an entry first touched late would take a first step of up to ~3× the learning rate.
/// An entry's first step is therefore always lr·g/(|g| + ε), as dense Adam's first step.
///
/// Each entry's step depends on its own gradient, moments and count only, so the visiting order does
/// not matter (no sort: a batch touches ~10⁵ entries with repeats, and sorting them cost more than
/// training).

#include <cstdint>
#include <vector>

#include "core/nn/mlp.h"

namespace rrf {

/// Gradient, moments and step counts of a sparse parameter vector (see the file comment).
struct SparseAdam {
    VecX<float> grad, m, v;           ///< accumulated gradient of this batch; first and second moments
    std::vector<uint32_t> steps;      ///< updates each entry has had
    std::vector<int64_t> touched;     ///< entries whose gradient this batch may be non-zero (repeats allowed)

    /// Zero moments and counts for `n` parameters.
    explicit SparseAdam(Eigen::Index n);

    /// One Adam step on every entry in `touched` (each once, in any order) of `params`; clears their
    /// gradients and `touched`.
    void step(VecX<float>& params, float beta1, float beta2, float learningRate, float epsilon);

private:
    std::vector<uint8_t> done_;  ///< entries stepped in this batch (reset after it)
};

}  // namespace rrf
