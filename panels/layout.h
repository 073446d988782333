#pragma once
/// The "docked" workspace without ImGui's docking branch: the host window's content is split into a
/// left column (full height) and, to its right, a centre pane above a bottom pane. Both splits are
/// draggable (ImGui::SplitterBehavior) and kept as fractions in the project's PaneLayout
/// (core/project/pane_layout.h), so they survive window resizes and DPI changes and are saved with
/// the project.

#include <functional>

#include "core/project/pane_layout.h"

namespace rrf::panels {

/// Draws the split workspace into the remaining content region of the current window, calling the
/// three functions inside child windows ("##left", "##centre", "##bottom").
void drawWorkspace(PaneLayout& layout, const std::function<void()>& left, const std::function<void()>& centre,
                   const std::function<void()>& bottom);

/// Puts the next item on the current line when `width` pixels still fit in the window's content
/// region, else starts a new line: toolbars wrap instead of cutting items off in a narrow pane.
void sameLineIfFits(float width);
/// The width a widget with frame width `frameWidth` and `label` after it takes (the label's "##"
/// part is not shown and not counted).
float labelledWidth(float frameWidth, const char* label);

}  // namespace rrf::panels
