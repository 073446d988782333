#pragma once
/// Finds text the user cannot read because the window, table column or widget showing it is too
/// narrow (issue 14 item 6: nothing may be cut off at 1280×720 or 1600×1000). ImGui cuts such text
/// silently; this makes it a test failure instead.
///
/// Two sources, both read after the frame's windows are submitted (before ImGui::Render):
///  - the frame's windows and tables: a window without a horizontal scrollbar whose items reach
///    past its clipping edge, or a table column whose cells or header reach past the column;
///  - text drawn inside a fixed frame (combo previews, progress-bar overlays) that ImGui clips to
///    the frame without growing the item: the panels draw it through fittedComboWidth() and
///    fittedProgressBar(), which size the frame to the text and report what still does not fit.

#include <string>
#include <vector>

namespace rrf::panels {

/// One piece of content wider than the space it is shown in.
struct ClippedContent {
    std::string where;  ///< the window (and table column, or widget text)
    float needed = 0, available = 0;  ///< pixels
    std::string describe() const;
};

/// The clipped content of the current frame: the windows and tables ImGui drew in it, and what the
/// fitted widgets reported. Call once per frame after the windows were submitted.
std::vector<ClippedContent> findClippedContent();

/// The width a combo needs to show the longest of `items` (zero-separated, ending with an empty
/// string, as ImGui::Combo takes them) without cutting it, capped at the space left on the line.
float fittedComboWidth(const char* items);

/// A progress bar `width` pixels wide (wider when the overlay needs it, up to the space left on the
/// line). An overlay that still does not fit is reported by findClippedContent().
void fittedProgressBar(float fraction, float width, const char* overlay);

}  // namespace rrf::panels
