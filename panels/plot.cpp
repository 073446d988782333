#include "panels/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

namespace rrf::panels {

float PlotAxis::toPixel(double value) const {
    double v = value;
    if (log) {
        if (!(value > 0.0)) return std::numeric_limits<float>::quiet_NaN();
        v = std::log10(value);
    }
    const double t = hi != lo ? (v - lo) / (hi - lo) : 0.0;
    return float(double(p0) + t * double(p1 - p0));
}

double PlotAxis::toValue(float pixel) const {
    const double t = p1 != p0 ? double(pixel - p0) / double(p1 - p0) : 0.0;
    const double v = lo + t * (hi - lo);
    return log ? std::pow(10.0, v) : v;
}

PlotAxis logAxis(double minValue, double maxValue, float p0, float p1) {
    PlotAxis a;
    a.log = true;
    a.p0 = p0;
    a.p1 = p1;
    if (!(minValue > 0.0) || !std::isfinite(minValue) || !std::isfinite(maxValue) || maxValue < minValue) {
        a.lo = -3.0;
        a.hi = 0.0;
        return a;
    }
    a.lo = std::floor(std::log10(minValue));
    a.hi = std::ceil(std::log10(maxValue));
    if (a.hi <= a.lo) a.hi = a.lo + 1.0;
    return a;
}

PlotAxis linearAxis(double minValue, double maxValue, float p0, float p1) {
    PlotAxis a;
    a.p0 = p0;
    a.p1 = p1;
    if (!std::isfinite(minValue) || !std::isfinite(maxValue) || maxValue < minValue) minValue = 0.0, maxValue = 1.0;
    if (maxValue == minValue) maxValue = minValue + 1.0;
    a.lo = minValue;
    a.hi = maxValue;
    return a;
}

std::string tickLabel(double value) {
    char buf[32];
    const double l = value > 0 ? std::log10(value) : 0.0;
    if (value > 0 && std::fabs(l - std::round(l)) < 1e-9 && (l < -2 || l > 3))
        std::snprintf(buf, sizeof buf, "1e%d", int(std::lround(l)));
    else std::snprintf(buf, sizeof buf, "%.3g", value);
    return buf;
}

ImU32 seriesColour(const std::string& name, float alpha) {
    uint32_t h = 2166136261u;  // FNV-1a, 32 bit
    for (unsigned char c : name) h = (h ^ c) * 16777619u;
    // A final mix, chosen so that each standard model sweep ("sweep grid", …) and its path tracer
    // ("path tracer (sweep grid)") land on clearly different palette entries (not red and pink).
    h *= 13u;
    h ^= h >> 13;
    return seriesColour(int(h % 10u), alpha);
}

void drawDashedLine(ImDrawList* dl, const ImVec2& a, const ImVec2& b, ImU32 colour, float dash, float thickness) {
    const float dx = b.x - a.x, dy = b.y - a.y;
    const float length = std::sqrt(dx * dx + dy * dy);
    if (!(length > 0.f) || !(dash > 0.f)) return;
    for (float t = 0.f; t < length; t += 2.f * dash) {
        const float u = t / length, v = std::min(t + dash, length) / length;
        dl->AddLine(ImVec2(a.x + u * dx, a.y + u * dy), ImVec2(a.x + v * dx, a.y + v * dy), colour, thickness);
    }
}

ImU32 seriesColour(int i, float alpha) {
    // Tableau 10: distinguishable on a dark background and for common colour-vision deficiencies.
    static const unsigned char rgb[10][3] = {{78, 121, 167}, {242, 142, 43}, {225, 87, 89}, {118, 183, 178},
                                             {89, 161, 79},  {237, 201, 72}, {176, 122, 161}, {255, 157, 167},
                                             {156, 117, 95}, {186, 176, 172}};
    const unsigned char* c = rgb[((i % 10) + 10) % 10];
    return IM_COL32(c[0], c[1], c[2], int(255 * std::clamp(alpha, 0.f, 1.f)));
}

void drawAxes(ImDrawList* dl, const ImVec2& min, const ImVec2& max, const PlotAxis& x, const PlotAxis& y,
              const char* xLabel, const char* yLabel) {
    const ImU32 major = IM_COL32(110, 110, 120, 160), minor = IM_COL32(80, 80, 90, 90), text = IM_COL32(190, 190, 190, 255);
    dl->AddRectFilled(min, max, IM_COL32(20, 20, 24, 255));
    auto ticks = [&](const PlotAxis& a, bool vertical) {
        auto line = [&](double v, ImU32 col, bool label) {
            const float p = a.toPixel(v);
            if (!std::isfinite(p)) return;
            if (vertical) {
                if (p < min.y - 0.5f || p > max.y + 0.5f) return;
                dl->AddLine(ImVec2(min.x, p), ImVec2(max.x, p), col);
                if (label) {
                    const std::string s = tickLabel(v);
                    const ImVec2 ts = ImGui::CalcTextSize(s.c_str());
                    dl->AddText(ImVec2(min.x - ts.x - 4, p - 0.5f * ts.y), text, s.c_str());
                }
            } else {
                if (p < min.x - 0.5f || p > max.x + 0.5f) return;
                dl->AddLine(ImVec2(p, min.y), ImVec2(p, max.y), col);
                if (label) {
                    const std::string s = tickLabel(v);
                    const ImVec2 ts = ImGui::CalcTextSize(s.c_str());
                    dl->AddText(ImVec2(p - 0.5f * ts.x, max.y + 2), text, s.c_str());
                }
            }
        };
        if (a.log) {
            // Label every decade, or every second/third one when there are many.
            // Decades from below the range to above it (a zoomed axis need not start on one); the
            // lines outside the plot are skipped.
            const int first = int(std::floor(a.lo + 1e-9)), last = int(std::ceil(a.hi - 1e-9));
            const int decades = last - first;
            const int every = decades > 12 ? 3 : decades > 6 ? 2 : 1;
            for (int d = first; d <= last; ++d) {
                const double base = std::pow(10.0, d);
                line(base, major, (d - first) % every == 0);
                if (d < last && decades <= 8)
                    for (int m = 2; m <= 9; ++m) line(base * m, minor, false);
            }
        } else {
            const double span = a.hi - a.lo;
            const double raw = span / 5.0;
            const double mag = std::pow(10.0, std::floor(std::log10(raw)));
            const double step = raw / mag >= 5 ? 5 * mag : raw / mag >= 2 ? 2 * mag : mag;
            for (double v = std::ceil(a.lo / step) * step; v <= a.hi + 1e-9 * span; v += step) line(v, major, true);
        }
    };
    ticks(y, true);
    ticks(x, false);
    dl->AddRect(min, max, IM_COL32(140, 140, 150, 255));
    if (xLabel) {
        const ImVec2 ts = ImGui::CalcTextSize(xLabel);
        dl->AddText(ImVec2(max.x - ts.x, max.y + ts.y + 4), text, xLabel);
    }
    if (yLabel) dl->AddText(ImVec2(min.x, min.y - ImGui::GetFontSize() - 2), text, yLabel);
}

PlotArea plotArea(const char* id, float legendWidth, float reserveBelow) {
    const float font = ImGui::GetFontSize();
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const ImVec2 size(std::max(avail.x - legendWidth, font * 10), std::max(avail.y - reserveBelow, font * 6));
    ImGui::InvisibleButton(id, size);
    PlotArea a;
    a.hovered = ImGui::IsItemHovered();
    a.active = ImGui::IsItemActive();
    // Margins for the tick labels (left) and the x labels (below).
    a.min = ImVec2(origin.x + font * 3.5f, origin.y + font * 1.5f);
    a.max = ImVec2(origin.x + size.x - font * 0.5f, origin.y + size.y - font * 2.6f);
    return a;
}

void zoomPanPlot(PlotView& view, PlotAxis& x, PlotAxis& y, const ImVec2& mouse, float wheel, const ImVec2& drag,
                 bool doubleClicked) {
    if (doubleClicked) view.autoFit = true;
    if (view.autoFit) {
        view.xlo = x.lo, view.xhi = x.hi, view.ylo = y.lo, view.yhi = y.hi;
        if (wheel == 0.f && drag.x == 0.f && drag.y == 0.f) return;
    }
    // Axis units under a pixel, and the axis span a pixel covers.
    auto unitsAt = [](double lo, double hi, float p0, float p1, float p) {
        return p1 != p0 ? lo + double(p - p0) / double(p1 - p0) * (hi - lo) : lo;
    };
    auto perPixel = [](double lo, double hi, float p0, float p1) { return p1 != p0 ? (hi - lo) / double(p1 - p0) : 0.0; };
    if (wheel != 0.f) {
        // One notch shows 80 % of the span, centred so the point under the cursor stays there.
        const double f = std::pow(0.8, double(wheel));
        const double cx = unitsAt(view.xlo, view.xhi, x.p0, x.p1, mouse.x), cy = unitsAt(view.ylo, view.yhi, y.p0, y.p1, mouse.y);
        view.xlo = cx - (cx - view.xlo) * f, view.xhi = cx + (view.xhi - cx) * f;
        view.ylo = cy - (cy - view.ylo) * f, view.yhi = cy + (view.yhi - cy) * f;
    }
    if (drag.x != 0.f || drag.y != 0.f) {
        const double dx = perPixel(view.xlo, view.xhi, x.p0, x.p1) * double(drag.x);
        const double dy = perPixel(view.ylo, view.yhi, y.p0, y.p1) * double(drag.y);
        view.xlo -= dx, view.xhi -= dx, view.ylo -= dy, view.yhi -= dy;
    }
    view.autoFit = false;
    // A span too small for a double's resolution (many notches in) stops the zoom there.
    const double minSpan = 1e-9;
    if (view.xhi - view.xlo < minSpan) view.xhi = view.xlo + minSpan;
    if (view.yhi - view.ylo < minSpan) view.yhi = view.ylo + minSpan;
    x.lo = view.xlo, x.hi = view.xhi, y.lo = view.ylo, y.hi = view.yhi;
}

bool seriesHidden(const std::vector<std::string>& hidden, const std::string& name) {
    return std::find(hidden.begin(), hidden.end(), name) != hidden.end();
}

bool legendEntry(const std::string& name, const char* text, ImU32 colour, std::vector<std::string>& hidden) {
    const float font = ImGui::GetFontSize();
    const bool off = seriesHidden(hidden, name);
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const ImU32 box = off ? IM_COL32(90, 90, 90, 255) : colour;
    dl->AddRectFilled(ImVec2(p.x, p.y + font * 0.3f), ImVec2(p.x + font * 0.7f, p.y + font), box);
    ImGui::Dummy(ImVec2(font * 0.8f, font));
    ImGui::SameLine();
    ImGui::PushID(name.c_str());
    if (off) ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    // As wide as its text: the legend column keeps its width, and a click lands on this entry only.
    const bool clicked = ImGui::Selectable(text, false, 0, ImGui::CalcTextSize(text));
    if (off) ImGui::PopStyleColor();
    ImGui::PopID();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip(off ? "click to show this series" : "click to hide this series");
    if (clicked) {
        if (off) hidden.erase(std::find(hidden.begin(), hidden.end(), name));
        else hidden.push_back(name);
    }
    return clicked;
}

void interactPlot(PlotView& view, const PlotArea& area, PlotAxis& x, PlotAxis& y) {
    const ImGuiIO& io = ImGui::GetIO();
    const float wheel = area.hovered ? io.MouseWheel : 0.f;
    const bool dragging = area.active && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 0.f);
    const ImVec2 drag = dragging ? io.MouseDelta : ImVec2(0.f, 0.f);
    const bool doubleClicked = area.hovered && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left);
    zoomPanPlot(view, x, y, io.MousePos, wheel, drag, doubleClicked);
    if (!view.autoFit) x.lo = view.xlo, x.hi = view.xhi, y.lo = view.ylo, y.hi = view.yhi;
}

}  // namespace rrf::panels
