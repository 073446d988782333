#pragma once
/// The project's "layout" section: how the workbench's panels are arranged in panes. The workspace
/// is a tree: a split divides its area between two children (side by side or one above the other,
/// the first child's share as a fraction so it survives window resizes and DPI changes); a leaf is a
/// pane of tabs, one per panel, one of them shown. Tabs move between panes, a pane splits in two,
/// and a pane left without tabs collapses into its sibling, so every panel is always in exactly one
/// pane and can be reached.
///
///     "layout": {"root": {"split": "row", "fraction": 0.27, "panes": [
///                   {"tabs": ["Project", "Scene", "Sampling", "Network"], "active": "Project"},
///                   {"split": "column", "fraction": 0.68, "panes": [
///                       {"tabs": ["Views"]},
///                       {"tabs": ["Training", "Objects", "Cost", "Leaves", "Light region", "Log"]}]}]}}
///
/// Files of earlier versions have {"left": 0.27, "bottom": 0.32} (the two splitters of the fixed
/// three-pane arrangement) and still load as that arrangement. Only data lives here; panels/layout
/// draws the workspace from it.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/util/json_reader.h"

namespace rrf {

/// How a pane node divides its area.
enum class PaneSplit {
    None,    ///< a leaf: a pane of tabs
    Row,     ///< two children side by side (first on the left)
    Column,  ///< two children one above the other (first on top)
};

/// Where a tab dropped on a pane goes: into the pane (Centre) or into a new pane on that side of it.
enum class DropSide { Centre, Left, Right, Top, Bottom };

/// One node of the pane tree.
struct PaneNode {
    PaneSplit split = PaneSplit::None;
    float fraction = 0.5f;           ///< splits: the first child's share of the area
    std::vector<PaneNode> children;  ///< splits: exactly two
    std::vector<std::string> tabs;   ///< leaves: the panels' names in tab order
    std::string active;              ///< leaves: the tab shown (one of `tabs`)

    bool isLeaf() const { return split == PaneSplit::None; }
    bool operator==(const PaneNode& o) const;
    bool operator!=(const PaneNode& o) const { return !(*this == o); }
};

struct PaneLayout {
    static constexpr float kDefaultLeft = 0.27f;    ///< left column width / workspace width
    static constexpr float kDefaultBottom = 0.32f;  ///< bottom pane height / right side's height
    /// Split fractions are clamped to this range so no pane can be dragged out of existence.
    static constexpr float kMinFraction = 0.08f;
    static constexpr float kMaxFraction = 0.92f;
    /// Nesting deeper than this in a file is damage, not a layout (it also bounds the recursion).
    static constexpr int kMaxDepth = 12;

    PaneNode root = defaultRoot();

    /// Every panel of the workbench in its default order; each is in exactly one pane.
    static const std::vector<std::string>& panels();
    /// The default arrangement: a left column (Project … Network), right of it the Views above the
    /// bottom pane (Training … Log), with the given left width and bottom height fractions.
    static PaneNode defaultRoot(float left = kDefaultLeft, float bottom = kDefaultBottom);

    void reset() { *this = PaneLayout(); }
    bool operator==(const PaneLayout& o) const { return root == o.root; }
    bool operator!=(const PaneLayout& o) const { return !(*this == o); }

    /// `f` clamped to [kMinFraction, kMaxFraction]; `fallback` when it is not finite.
    static float clampFraction(float f, float fallback);

    /// The pane (leaf) that holds `tab`; nullptr if no pane does.
    PaneNode* paneOf(const std::string& tab);
    const PaneNode* paneOf(const std::string& tab) const;
    /// The panes (leaves) in drawing order: depth first, first child first.
    std::vector<const PaneNode*> panes() const;

    /// Moves `tab` to the pane holding `target`: into it (Centre, appended and shown) or into a new
    /// pane on `side` of it (the target pane is split in half). A pane left empty collapses. Returns
    /// false and changes nothing when the move is not possible or would change nothing (an unknown
    /// tab; Centre on its own pane; splitting a pane whose only tab is the one moved).
    bool moveTab(const std::string& tab, const std::string& target, DropSide side);
    /// Puts the tabs of one pane in the order given (the tab bar was reordered by dragging). `order`
    /// must name exactly that pane's tabs; returns false and changes nothing otherwise or when the
    /// order is the same.
    bool reorderPane(const std::vector<std::string>& order);
    /// Makes `tab` the shown tab of its pane; false if no pane holds it or it is shown already.
    bool showTab(const std::string& tab);

    /// {"root": node}; nodes as in the header comment.
    nlohmann::json toJson() const;
    /// Reads the section. A damaged layout must never make the workspace unusable (nor the project
    /// unopenable): a damaged tree is replaced by the default arrangement, an unknown or repeated tab
    /// is dropped, a panel no pane holds is added to the first pane, an out-of-range fraction is
    /// clamped, and each repair is described in `warnings` (file, JSON pointer, what was expected).
    /// The old form {"left", "bottom"} is read as the default arrangement with those fractions.
    static PaneLayout fromJson(const JsonReader& section, std::vector<std::string>& warnings);
};

}  // namespace rrf
