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
/// A panel can also float: undocked from its pane into a window of its own that the user moves and
/// sizes, and docked back (into the pane it came from, or dragged onto any pane). Every panel is
/// always in exactly one pane or one floating window, and at least one panel stays in the panes:
///
///     "floating": [{"tab": "Log", "rect": [900, 80, 480, 360], "home": "Training"}]
///
/// ("rect": the window's position and size in pixels; "home": a panel of the pane it left).
///
/// Files of earlier versions have {"left": 0.27, "bottom": 0.32} (the two splitters of the fixed
/// three-pane arrangement) and still load as that arrangement. Only data lives here; panels/layout
/// draws the workspace from it;
/// core/project/pane_layout_json.h reads and writes the section.

#include <string>
#include <vector>

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

/// A panel in a window of its own (undocked from the panes).
struct FloatingPanel {
    std::string tab;
    float x = 0.f, y = 0.f, width = 0.f, height = 0.f;  ///< the window's position and size, pixels
    std::string home;  ///< a panel of the pane it was undocked from (where Dock puts it back)
    bool operator==(const FloatingPanel& o) const {
        return tab == o.tab && x == o.x && y == o.y && width == o.width && height == o.height && home == o.home;
    }
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
    std::vector<FloatingPanel> floating;  ///< panels undocked into windows of their own

    /// Every panel of the workbench in its default order; each is in exactly one pane.
    static const std::vector<std::string>& panels();
    /// The default arrangement: a left column (Project … Network), right of it the Views above the
    /// bottom pane (Training … Log), with the given left width and bottom height fractions.
    static PaneNode defaultRoot(float left = kDefaultLeft, float bottom = kDefaultBottom);

    void reset() { *this = PaneLayout(); }
    bool operator==(const PaneLayout& o) const { return root == o.root && floating == o.floating; }
    bool operator!=(const PaneLayout& o) const { return !(*this == o); }

    /// `f` clamped to [kMinFraction, kMaxFraction]; `fallback` when it is not finite.
    static float clampFraction(float f, float fallback);

    /// The pane (leaf) that holds `tab`; nullptr if no pane does.
    PaneNode* paneOf(const std::string& tab);
    const PaneNode* paneOf(const std::string& tab) const;
    /// The panes (leaves) in drawing order: depth first, first child first.
    std::vector<const PaneNode*> panes() const;

    /// Moves `tab` (in a pane or floating) to the pane holding `target`: into it (Centre, appended
    /// and shown) or into a new pane on `side` of it (the target pane is split in half). A pane left
    /// empty collapses. Returns false and changes nothing when the move is not possible or would
    /// change nothing (an unknown tab; Centre on its own pane; splitting a pane whose only tab is the
    /// one moved).
    bool moveTab(const std::string& tab, const std::string& target, DropSide side);
    /// Undocks `tab` from its pane into a floating window at (x, y) of size (width, height). False
    /// and nothing changed when no pane holds it or it is the last panel left in the panes.
    bool floatTab(const std::string& tab, float x, float y, float width, float height);
    /// Docks a floating `tab` back into the pane of its home panel (the first pane when its home
    /// floats too or is gone). False when `tab` does not float.
    bool dockTab(const std::string& tab);
    /// The floating window of `tab`; nullptr when it is in a pane.
    FloatingPanel* floatingPanel(const std::string& tab);
    /// Puts the tabs of one pane in the order given (the tab bar was reordered by dragging). `order`
    /// must name exactly that pane's tabs; returns false and changes nothing otherwise or when the
    /// order is the same.
    bool reorderPane(const std::vector<std::string>& order);
    /// Makes `tab` the shown tab of its pane; false if no pane holds it or it is shown already.
    bool showTab(const std::string& tab);

    /// Makes the tree `root` and the windows `floating` hold every panel exactly once: unknown and
    /// repeated tabs are dropped, missing panels join the first pane, empty panes collapse, and each
    /// pane shows one of its tabs. Each repair is described in `warnings`, naming `file` and the JSON
    /// `pointer` of the layout it was read from.
    static void normalise(PaneNode& root, std::vector<FloatingPanel>& floating, const std::string& file,
                          const std::string& pointer, std::vector<std::string>& warnings);
};

}  // namespace rrf
