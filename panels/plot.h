#pragma once
/// Small plotting helpers over ImDrawList, shared by the Training (loss) and Cost (error vs time)
/// panels: linear and log10 axes, decade grids with labels, series colours and the aggregate of
/// several loss curves. The mapping functions need no ImGui context, so tests check them directly.

#include <string>
#include <vector>

#include <imgui.h>

#include "core/project/runs.h"

namespace rrf::panels {

/// One plot axis mapping data [lo, hi] onto pixels [p0, p1]. On a log axis lo and hi are log10 of
/// the data range; values ≤ 0 have no position there (toPixel returns NaN).
struct PlotAxis {
    bool log = false;
    double lo = 0.0, hi = 1.0;
    float p0 = 0.f, p1 = 1.f;

    float toPixel(double value) const;
    double toValue(float pixel) const;
};

/// A log axis spanning whole decades around the positive values in [minValue, maxValue] (at least
/// one decade; a non-positive or non-finite range gives 1e-3 … 1).
PlotAxis logAxis(double minValue, double maxValue, float p0, float p1);
/// A linear axis over [minValue, maxValue] (widened to a non-zero span).
PlotAxis linearAxis(double minValue, double maxValue, float p0, float p1);

/// Draws the plot background, the grid (every decade on log axes with 2…9 minor lines, about five
/// ticks on linear ones) and the tick labels into `dl`. `min`/`max` is the plot rectangle; tick labels
/// go left of and below it, the y label one text line above it, the x label under the ticks.
void drawAxes(ImDrawList* dl, const ImVec2& min, const ImVec2& max, const PlotAxis& x, const PlotAxis& y,
              const char* xLabel, const char* yLabel);

/// The screen area of a plot: an invisible button filling the available space except a legend
/// column of `legendWidth` on the right, with margins for the tick labels (left) and the x labels
/// (below). Call where the plot goes; it advances the cursor like any item.
struct PlotArea {
    ImVec2 min, max;       ///< the data rectangle (inside the margins)
    bool hovered = false;  ///< the mouse is over the plot item
    bool active = false;   ///< the plot item is held (a drag)
};
/// `reserveBelow` pixels under the plot are left free (for text the caller adds there).
PlotArea plotArea(const char* id, float legendWidth, float reserveBelow = 0.f);

/// What the user did to a plot's axes, kept across frames: while `autoFit` the axes follow the data;
/// the wheel over the plot zooms about the cursor (both axes), a drag pans, a double-click fits the
/// data again. Ranges are in axis units (log10 on a log axis), as PlotAxis::lo and hi.
struct PlotView {
    bool autoFit = true;
    double xlo = 0.0, xhi = 1.0, ylo = 0.0, yhi = 1.0;
};

/// One frame of zoom and pan: `x` and `y` come in fitted to the data and leave as the view shows
/// them; `view` follows this frame's input over the plot (its invisible button, just submitted by
/// plotArea). `wheel` is the wheel notches over the plot, `drag` the mouse's movement while the
/// plot is dragged (pixels), `doubleClicked` a double-click on it; split out so tests drive it.
void zoomPanPlot(PlotView& view, PlotAxis& x, PlotAxis& y, const ImVec2& mouse, float wheel, const ImVec2& drag,
                 bool doubleClicked);
/// True when `name` is in `hidden` (a series switched off in its legend).
bool seriesHidden(const std::vector<std::string>& hidden, const std::string& name);
/// One legend entry: a colour box and `text`, clickable; a click hides the series `name` (adds it to
/// `hidden`) or shows it again. A hidden series' entry is drawn dimmed. Returns true on a click.
bool legendEntry(const std::string& name, const char* text, ImU32 colour, std::vector<std::string>& hidden);

/// zoomPanPlot with this frame's ImGui input over `area`.
void interactPlot(PlotView& view, const PlotArea& area, PlotAxis& x, PlotAxis& y);

/// A distinct colour for series i (cycles after 10).
ImU32 seriesColour(int i, float alpha = 1.f);
/// The colour of the series named `name`: a function of the name alone (a hash into the same
/// palette), so a series keeps its colour whatever other series are shown and in whatever order.
ImU32 seriesColour(const std::string& name, float alpha = 1.f);

/// A dashed line from a to b (dashes and gaps of `dash` pixels).
void drawDashedLine(ImDrawList* dl, const ImVec2& a, const ImVec2& b, ImU32 colour, float dash = 6.f, float thickness = 1.f);

/// "1e-3", "0.25", "40": a short tick label.
std::string tickLabel(double value);


}  // namespace rrf::panels
