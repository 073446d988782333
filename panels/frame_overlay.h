#pragma once
/// The frame-time overlay (F3): a small window of lines over the workspace that takes no input. It
/// goes over the Views' images (their top-right corner, below the toolbar and the views' titles),
/// where it covers no control: at the window's top-right it hid the Views' "Reset view" button
/// (issue 29 item 9).

#include <string>
#include <utility>
#include <vector>

#include <imgui.h>

#include "panels/workbench_state.h"

namespace rrf::panels {

/// Where the overlay's top-right corner goes: inside the top-right corner of the views' images
/// drawn in this frame (ViewState::viewMin/viewMax), else `fallback` (the Views are not shown).
ImVec2 frameOverlayCorner(const ViewState& view, ImVec2 fallback);

/// Draws the overlay with `lines` (the last one dimmed: what the figures are) at frameOverlayCorner and
/// returns the rectangle it covers (as ImGui sized it in the last frame: min, max).
std::pair<ImVec2, ImVec2> drawFrameOverlay(const std::vector<std::string>& lines, const ViewState& view, ImVec2 fallback);

}  // namespace rrf::panels
