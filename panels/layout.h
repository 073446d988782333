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

}  // namespace rrf::panels
