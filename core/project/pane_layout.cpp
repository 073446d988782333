#include "core/project/pane_layout.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "core/util/error.h"

namespace rrf {

namespace {

PaneNode leaf(std::vector<std::string> tabs) {
    PaneNode n;
    n.active = tabs.front();
    n.tabs = std::move(tabs);
    return n;
}

PaneNode splitNode(PaneSplit split, float fraction, PaneNode first, PaneNode second) {
    PaneNode n;
    n.split = split;
    n.fraction = fraction;
    n.children.push_back(std::move(first));
    n.children.push_back(std::move(second));
    return n;
}

template <typename Node, typename Out>
void collectPanes(Node& n, Out& out) {
    if (n.isLeaf()) {
        out.push_back(&n);
        return;
    }
    for (auto& c : n.children) collectPanes(c, out);
}

/// Keeps a pane's shown tab one of its tabs (the first when it is not).
void fixActive(PaneNode& pane) {
    if (pane.tabs.empty()) pane.active.clear();
    else if (std::find(pane.tabs.begin(), pane.tabs.end(), pane.active) == pane.tabs.end()) pane.active = pane.tabs.front();
}

/// Replaces every split with an empty pane under it by its other child: a pane emptied by moving its
/// last tab away disappears and its sibling takes the space. The root may end up an empty leaf only
/// if the whole tree was empty.
void collapse(PaneNode& n) {
    if (n.isLeaf()) return;
    for (PaneNode& c : n.children) collapse(c);
    for (size_t i = 0; i < 2; ++i) {
        const PaneNode& c = n.children[i];
        if (c.isLeaf() && c.tabs.empty()) {
            PaneNode keep = std::move(n.children[1 - i]);
            n = std::move(keep);
            return;
        }
    }
}

}  // namespace

// Makes the tree hold every panel exactly once (see the declaration).
void PaneLayout::normalise(PaneNode& root, std::vector<FloatingPanel>& floating, const std::string& file,
                           const std::string& pointer, std::vector<std::string>& warnings) {
    const std::vector<std::string>& known = PaneLayout::panels();
    std::set<std::string> seen;
    std::vector<PaneNode*> panes;
    collectPanes(root, panes);
    for (PaneNode* p : panes) {
        std::vector<std::string> kept;
        for (const std::string& t : p->tabs) {
            if (std::find(known.begin(), known.end(), t) == known.end())
                warnings.push_back(InputError(file, pointer, "unknown panel '" + t + "' dropped").what());
            else if (!seen.insert(t).second)
                warnings.push_back(InputError(file, pointer, "panel '" + t + "' is in two panes; the second is dropped").what());
            else
                kept.push_back(t);
        }
        p->tabs = std::move(kept);
    }
    // Floating windows after the panes: a panel a pane holds stays there.
    std::vector<FloatingPanel> floats;
    for (FloatingPanel& f : floating) {
        if (std::find(known.begin(), known.end(), f.tab) == known.end())
            warnings.push_back(InputError(file, pointer, "unknown floating panel '" + f.tab + "' dropped").what());
        else if (!seen.insert(f.tab).second)
            warnings.push_back(
                InputError(file, pointer, "panel '" + f.tab + "' floats but is also in a pane or window; the window is dropped")
                    .what());
        else
            floats.push_back(std::move(f));
    }
    floating = std::move(floats);
    collapse(root);
    // At least one panel stays in the panes.
    if (root.isLeaf() && root.tabs.empty() && !floating.empty()) {
        warnings.push_back(InputError(file, pointer, "every panel floats; '" + floating.front().tab + "' is docked").what());
        root.tabs.push_back(floating.front().tab);
        floating.erase(floating.begin());
    }
    std::vector<PaneNode*> first;
    collectPanes(root, first);
    for (const std::string& t : known)
        if (!seen.count(t)) {
            warnings.push_back(InputError(file, pointer, "panel '" + t + "' is in no pane; it is added to the first").what());
            first.front()->tabs.push_back(t);
        }
    std::vector<PaneNode*> all;
    collectPanes(root, all);
    for (PaneNode* p : all) fixActive(*p);
}

bool PaneNode::operator==(const PaneNode& o) const {
    return split == o.split && children == o.children && tabs == o.tabs && active == o.active &&
           (isLeaf() || fraction == o.fraction);
}

const std::vector<std::string>& PaneLayout::panels() {
    static const std::vector<std::string> names = {"Project",  "Scene",   "Sampling", "Network", "Views",         "Training",
                                                   "Objects",  "Cost",    "Leaves",   "Light region", "Log"};
    return names;
}

PaneNode PaneLayout::defaultRoot(float left, float bottom) {
    // Training first in the bottom pane: the loss plot is what a user watches while networks learn.
    return splitNode(PaneSplit::Row, left, leaf({"Project", "Scene", "Sampling", "Network"}),
                     splitNode(PaneSplit::Column, 1.f - bottom, leaf({"Views"}),
                               leaf({"Training", "Objects", "Cost", "Leaves", "Light region", "Log"})));
}

float PaneLayout::clampFraction(float f, float fallback) {
    if (!std::isfinite(f)) return fallback;
    return std::clamp(f, kMinFraction, kMaxFraction);
}

PaneNode* PaneLayout::paneOf(const std::string& tab) {
    std::vector<PaneNode*> all;
    collectPanes(root, all);
    for (PaneNode* p : all)
        if (std::find(p->tabs.begin(), p->tabs.end(), tab) != p->tabs.end()) return p;
    return nullptr;
}

const PaneNode* PaneLayout::paneOf(const std::string& tab) const { return const_cast<PaneLayout*>(this)->paneOf(tab); }

std::vector<const PaneNode*> PaneLayout::panes() const {
    std::vector<const PaneNode*> all;
    collectPanes(root, all);
    return all;
}

bool PaneLayout::moveTab(const std::string& tab, const std::string& target, DropSide side) {
    PaneNode* from = paneOf(tab);
    PaneNode* to = paneOf(target);
    FloatingPanel* floats = floatingPanel(tab);
    if ((!from && !floats) || !to) return false;
    if (side == DropSide::Centre && from == to) return false;
    if (side != DropSide::Centre && from == to && from->tabs.size() == 1) return false;
    // Take the tab out first (the pane may become empty but stays in place, so `to` stays valid).
    if (floats) {
        floating.erase(floating.begin() + (floats - floating.data()));
    } else {
        from->tabs.erase(std::find(from->tabs.begin(), from->tabs.end(), tab));
        fixActive(*from);
    }
    if (side == DropSide::Centre) {
        to->tabs.push_back(tab);
        to->active = tab;
    } else {
        const bool row = side == DropSide::Left || side == DropSide::Right;
        const bool before = side == DropSide::Left || side == DropSide::Top;
        PaneNode old = std::move(*to);
        PaneNode moved = leaf({tab});
        *to = before ? splitNode(row ? PaneSplit::Row : PaneSplit::Column, 0.5f, std::move(moved), std::move(old))
                     : splitNode(row ? PaneSplit::Row : PaneSplit::Column, 0.5f, std::move(old), std::move(moved));
    }
    collapse(root);
    return true;
}

bool PaneLayout::floatTab(const std::string& tab, float x, float y, float width, float height) {
    PaneNode* from = paneOf(tab);
    if (!from) return false;
    size_t docked = 0;
    for (const PaneNode* p : panes()) docked += p->tabs.size();
    if (docked <= 1) return false;
    FloatingPanel f{tab, x, y, width, height, {}};
    for (const std::string& other : from->tabs)
        if (other != tab) f.home = other;
    from->tabs.erase(std::find(from->tabs.begin(), from->tabs.end(), tab));
    fixActive(*from);
    collapse(root);
    floating.push_back(std::move(f));
    return true;
}

bool PaneLayout::dockTab(const std::string& tab) {
    const FloatingPanel* f = floatingPanel(tab);
    if (!f) return false;
    const std::string home = paneOf(f->home) ? f->home : panes().front()->tabs.front();
    return moveTab(tab, home, DropSide::Centre);
}

FloatingPanel* PaneLayout::floatingPanel(const std::string& tab) {
    for (FloatingPanel& f : floating)
        if (f.tab == tab) return &f;
    return nullptr;
}

bool PaneLayout::reorderPane(const std::vector<std::string>& order) {
    if (order.empty()) return false;
    PaneNode* pane = paneOf(order.front());
    if (!pane || order == pane->tabs) return false;
    std::vector<std::string> a = order, b = pane->tabs;
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    if (a != b) return false;
    pane->tabs = order;
    return true;
}

bool PaneLayout::showTab(const std::string& tab) {
    PaneNode* pane = paneOf(tab);
    if (!pane || pane->active == tab) return false;
    pane->active = tab;
    return true;
}


}  // namespace rrf
