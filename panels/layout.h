#pragma once
/// The "docked" workspace without ImGui's docking branch: the host window's content is split into a
/// left column (full height) and, to its right, a centre pane above a bottom pane. Both splits are
/// draggable (ImGui::SplitterBehavior) and stored as fractions of the workspace, so they survive
/// window resizes and DPI changes and can be saved in the project's "layout" section.

#include <functional>

#include <nlohmann/json.hpp>

namespace rrf::panels {

struct LayoutState {
    static constexpr float kDefaultLeft = 0.27f;    ///< left column width / workspace width
    static constexpr float kDefaultBottom = 0.32f;  ///< bottom pane height / workspace height

    float left = kDefaultLeft;
    float bottom = kDefaultBottom;

    void reset() { *this = LayoutState(); }
    bool operator==(const LayoutState& o) const { return left == o.left && bottom == o.bottom; }
    bool operator!=(const LayoutState& o) const { return !(*this == o); }

    /// {"left": 0.27, "bottom": 0.32}
    nlohmann::json toJson() const;
    /// Reads what it can from `j` and keeps defaults for missing or out-of-range values: a damaged
    /// layout section must never make the workspace unusable.
    static LayoutState fromJson(const nlohmann::json& j);
};

/// Fractions are clamped to this range so no pane can be dragged out of existence.
constexpr float kMinPaneFraction = 0.08f;
constexpr float kMaxPaneFraction = 0.85f;

/// Draws the split workspace into the remaining content region of the current window, calling the
/// three functions inside child windows ("##left", "##centre", "##bottom").
void drawWorkspace(LayoutState& layout, const std::function<void()>& left, const std::function<void()>& centre,
                   const std::function<void()>& bottom);

}  // namespace rrf::panels
