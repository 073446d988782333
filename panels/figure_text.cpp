#include "panels/figure_text.h"

#include <cstdarg>
#include <cstdio>

#include <imgui_internal.h>

namespace rrf::panels {

namespace figure_text_detail {
namespace {
/// What textUnbroken drew in frame `frame` (the UI thread's only; cleared per frame).
struct FrameLines {
    const ImGuiContext* context = nullptr;
    int frame = -1;
    std::vector<std::string> lines;
};

FrameLines& frameLines() {
    static FrameLines l;
    return l;
}

void remember(const std::string& text) {
    FrameLines& l = frameLines();
    if (l.frame != ImGui::GetFrameCount() || l.context != ImGui::GetCurrentContext()) {
        l.context = ImGui::GetCurrentContext();
        l.frame = ImGui::GetFrameCount();
        l.lines.clear();
    }
    size_t start = 0;
    for (size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1)
        l.lines.push_back(text.substr(start, end - start));
    l.lines.push_back(text.substr(start));
}

/// The end of the longest start of [word, end) no wider than `width` (at least one character; a
/// UTF-8 sequence is never cut).
const char* fittingPrefix(const char* word, const char* end, float width,
                          const std::function<float(const char*, const char*)>& measure) {
    auto next = [&](const char* p) {
        ++p;
        while (p < end && (static_cast<unsigned char>(*p) & 0xC0) == 0x80) ++p;
        return p;
    };
    const char* cut = next(word);
    while (cut < end && measure(word, next(cut)) <= width) cut = next(cut);
    return cut;
}

/// One paragraph (no '\n') of wrapAtSpaces.
void wrapParagraph(const char* begin, const char* end, float width,
                   const std::function<float(const char*, const char*)>& measure, std::string& out) {
    const char* line = begin;    // start of the current line
    const char* last = nullptr;  // end of the last word on it
    for (const char* p = begin; p < end;) {
        const char* word = p;
        while (word < end && *word == ' ') ++word;
        if (word == end) break;
        const char* wordEnd = word;
        while (wordEnd < end && *wordEnd != ' ') ++wordEnd;
        if (last && measure(line, wordEnd) > width) {
            out.append(line, last);
            out += '\n';
            line = word;
            last = nullptr;
        }
        // A word wider than a whole line (a long path; never a figure in a pane that shows any) is
        // cut where it must be, as ImGui would, rather than run past the pane's edge.
        while (!last && measure(word, wordEnd) > width) {
            const char* cut = fittingPrefix(word, wordEnd, width, measure);
            if (cut >= wordEnd) break;
            out.append(word, cut);
            out += '\n';
            word = line = cut;
        }
        last = wordEnd;
        p = wordEnd;
    }
    out.append(line, last ? last : line);
}

void drawUnbroken(const ImVec4* colour, const char* fmt, va_list args) {
    va_list again;
    va_copy(again, args);
    const int n = std::vsnprintf(nullptr, 0, fmt, args);
    std::string text(size_t(n > 0 ? n : 0) + 1, '\0');
    std::vsnprintf(text.data(), text.size(), fmt, again);
    va_end(again);
    text.pop_back();
    if (colour) ImGui::PushStyleColor(ImGuiCol_Text, *colour);
    textUnbroken(text.c_str());
    if (colour) ImGui::PopStyleColor();
}
}  // namespace
}  // namespace figure_text_detail

std::string wrapAtSpaces(const std::string& text, float width, const std::function<float(const char*, const char*)>& measure) {
    std::string out;
    size_t start = 0;
    for (size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1) {
        figure_text_detail::wrapParagraph(text.data() + start, text.data() + end, width, measure, out);
        out += '\n';
    }
    figure_text_detail::wrapParagraph(text.data() + start, text.data() + text.size(), width, measure, out);
    return out;
}

void textUnbroken(const char* text) {
    ImGuiWindow* window = ImGui::GetCurrentWindow();
    const float wrapPos = window->DC.TextWrapPos;
    std::string shown = text;
    if (wrapPos >= 0.f) {
        // The width ImGui's own wrap would use at the cursor (a pane's edge, or a pushed position).
        const float width = ImGui::CalcWrapWidthForPos(window->DC.CursorPos, wrapPos);
        shown = wrapAtSpaces(text, width, [](const char* b, const char* e) { return ImGui::CalcTextSize(b, e).x; });
    }
    figure_text_detail::remember(shown);
    // The breaks are made: ImGui must not add its own.
    ImGui::PushTextWrapPos(-1.f);
    ImGui::TextUnformatted(shown.c_str());
    ImGui::PopTextWrapPos();
}

void figureText(const char* fmt, ...) {
    va_list args;
    va_start(args, fmt);
    figure_text_detail::drawUnbroken(nullptr, fmt, args);
    va_end(args);
}

void figureTextDisabled(const char* fmt, ...) {
    va_list args;
    va_start(args, fmt);
    const ImVec4 disabled = ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled);
    figure_text_detail::drawUnbroken(&disabled, fmt, args);
    va_end(args);
}

void figureTextColored(const ImVec4& colour, const char* fmt, ...) {
    va_list args;
    va_start(args, fmt);
    figure_text_detail::drawUnbroken(&colour, fmt, args);
    va_end(args);
}

std::vector<std::string> unbrokenLinesThisFrame() {
    const figure_text_detail::FrameLines& l = figure_text_detail::frameLines();
    return l.frame == ImGui::GetFrameCount() && l.context == ImGui::GetCurrentContext() ? l.lines : std::vector<std::string>{};
}

}  // namespace rrf::panels
