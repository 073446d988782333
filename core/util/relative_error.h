#pragma once
/// The one definition of the relative error's denominator offset, d / (|ref| + ε) with ε = 0.01
/// (Ren et al. 2013; docs/design.md §14). It lives in the lowest stage because three stages use it:
/// the error metrics (eval), the trainers' error goal and relative L2 loss (nn), and the data
/// generator's per-record relative noise (data).

namespace rrf {

/// Denominator offset of the relative error: it keeps black pixels and records finite.
constexpr double kRelativeEpsilon = 0.01;

}  // namespace rrf
