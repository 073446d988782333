#pragma once
/// Docking without ImGui's docking branch: the workspace is drawn from the project's pane tree
/// (core/project/pane_layout.h). Each split has a draggable splitter (ImGui::SplitterBehavior); each
/// pane is a child window with a reorderable tab bar. A tab can be dragged onto another pane (its
/// centre or its tab bar: join that pane; an edge zone: split it and take that side), or moved and split from its
/// context menu (right click), which also floats it in a window of its own (Dock, closing the
/// window or dragging its handle onto a pane puts it back). Changes are applied to the PaneLayout after the frame's panes are
/// drawn, so the tree is never edited while it is walked.

#include <functional>
#include <string>

#include "core/project/pane_layout.h"

namespace rrf::panels {

struct WorkbenchState;

/// The drag-and-drop payload type of a dragged tab (its panel's name, NUL-terminated).
inline constexpr const char* kTabPayload = "RRF_TAB";

/// Draws the pane tree into the remaining content region of the current window, calling
/// `drawPanel(name)` for the shown tab of each pane inside the pane's child window. `focusTab`, when
/// it names a panel, brings that tab to the front once and is cleared. Returns true when the user
/// changed the arrangement (moved, split or reordered tabs; splitter drags only resize).
bool drawWorkspace(PaneLayout& layout, const std::function<void(const std::string&)>& drawPanel,
                   std::string& focusTab);

/// The gap between two panes, all of which takes the mouse as the splitter (at least 10 px, so it
/// is easy to hit; a thinner line is drawn in its middle).
float splitterWidth();

/// Draws the panel `name` (one of PaneLayout::panels()) with the view its builder makes from `state`
/// (panels/panel_views.h); an unknown name draws nothing.
void drawPanel(WorkbenchState& state, const std::string& name);

/// Which part of a pane a drop at `(u, v)` (the pointer's position in the pane, each 0 … 1) lands
/// in: the outer quarter along each edge splits the pane on that side, the middle joins it.
DropSide dropSideAt(float u, float v);

/// Puts the next item on the current line when `width` pixels still fit in the window's content
/// region, else starts a new line: toolbars wrap instead of cutting items off in a narrow pane.
void sameLineIfFits(float width);
/// The width a widget with frame width `frameWidth` and `label` after it takes (the label's "##"
/// part is not shown and not counted).
float labelledWidth(float frameWidth, const char* label);
/// The frame width for a widget with `label` after it: `preferred`, narrower when the label would
/// otherwise run past the window's edge (but at least 4 em), so labels are not cut off.
float fieldWidth(float preferred, const char* label);

}  // namespace rrf::panels
