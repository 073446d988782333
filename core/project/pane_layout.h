#pragma once
/// The project's "layout" section: where the workbench's two pane splitters sit, as fractions of the
/// workspace so they survive window resizes and DPI changes:
///
///     "layout": {"left": 0.27, "bottom": 0.32}
///
/// Only data lives here; panels/layout draws the workspace from it.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/util/json_reader.h"

namespace rrf {

struct PaneLayout {
    static constexpr float kDefaultLeft = 0.27f;    ///< left column width / workspace width
    static constexpr float kDefaultBottom = 0.32f;  ///< bottom pane height / workspace height
    /// Fractions are clamped to this range so no pane can be dragged out of existence.
    static constexpr float kMinFraction = 0.08f;
    static constexpr float kMaxFraction = 0.85f;

    float left = kDefaultLeft;
    float bottom = kDefaultBottom;

    void reset() { *this = PaneLayout(); }
    bool operator==(const PaneLayout& o) const { return left == o.left && bottom == o.bottom; }
    bool operator!=(const PaneLayout& o) const { return !(*this == o); }

    /// `f` clamped to [kMinFraction, kMaxFraction]; `fallback` when it is not finite.
    static float clampFraction(float f, float fallback);

    /// {"left": 0.27, "bottom": 0.32}
    nlohmann::json toJson() const;
    /// Reads the section. A damaged layout must never make the workspace unusable (nor the project
    /// unopenable), so a value of the wrong type keeps its default and is described in `warnings`
    /// (file, JSON pointer, what was expected); out-of-range fractions are clamped.
    static PaneLayout fromJson(const JsonReader& section, std::vector<std::string>& warnings);
};

}  // namespace rrf
