#pragma once
/// The three radiance terms the renderer produces and everything downstream predicts, compares and
/// shows: direct light (one bounce from the light, plus emission seen directly), indirect light (all
/// longer paths) and global = direct + indirect (docs/design.md §2: both parts are kept as
/// separate images because both are training targets).
///
/// This is the one Term of the project: images, reports, tables, the CPU and GLSL predictors (the
/// shader's output locations are int(Term)), the workbench views and scripts all use it. The
/// numbering is the storage order (index arrays with int(t)); a user interface that lists the terms
/// in another order keeps that order as its own list of Terms.

#include <optional>
#include <string_view>

namespace rrf {

enum class Term { Direct = 0, Indirect = 1, Global = 2 };
constexpr int kTermCount = 3;
/// Every term in storage order (loop with `for (Term t : kTerms)`).
constexpr Term kTerms[kTermCount] = {Term::Direct, Term::Indirect, Term::Global};

/// "direct" | "indirect" | "global": the spelling of project files, scripts, file names and reports.
constexpr const char* termName(Term t) {
    switch (t) {
    case Term::Direct: return "direct";
    case Term::Indirect: return "indirect";
    case Term::Global: return "global";
    }
    return "?";
}

/// The term spelled `name` (as termName writes it); nullopt for anything else, so each front end
/// reports the bad value in its own terms (script step, flag, setting).
inline std::optional<Term> parseTerm(std::string_view name) {
    for (Term t : kTerms)
        if (name == termName(t)) return t;
    return std::nullopt;
}

}  // namespace rrf
