#pragma once
/// Text with figures that wraps only between words (issue 29 item 9: "RMSE 0." on one line and
/// "02267" on the next). ImGui's own word wrap may break a line after '.', ',', ';', '!', '?' or '"',
/// so a figure like 0.02267 splits at its decimal point whenever the pane is narrow. These draw text
/// like ImGui::Text under the window's current wrap position (the panes push one at their edge), but
/// break lines at spaces only, so every figure, written without spaces, stays one token.

#include <functional>
#include <string>
#include <vector>

#include <imgui.h>

namespace rrf::panels {

/// `text` with line breaks put at spaces only, each line as wide as `width` allows by `measure`
/// (the pixel width of [begin, end)). Only a word wider than a whole line (a long path) is cut inside,
/// as ImGui would cut it. Spaces at a break are dropped; line breaks already in `text` are kept.
std::string wrapAtSpaces(const std::string& text, float width, const std::function<float(const char*, const char*)>& measure);

/// ImGui::TextUnformatted wrapped by wrapAtSpaces at the current wrap position (none: one line).
void textUnbroken(const char* text);
/// printf-style forms of textUnbroken: plain, disabled and coloured text.
void figureText(const char* fmt, ...) IM_FMTARGS(1);
void figureTextDisabled(const char* fmt, ...) IM_FMTARGS(1);
void figureTextColored(const ImVec4& colour, const char* fmt, ...) IM_FMTARGS(2);

/// The lines textUnbroken drew in the current frame, in order (tests read what reached the screen).
std::vector<std::string> unbrokenLinesThisFrame();

}  // namespace rrf::panels
