#pragma once
/// What the Views panel reports under its three views (panels/views_panel.cpp): the error map's
/// figures (`rrf evaluate`'s overall row and what it leaves out), the region of interest's figures,
/// the hovered pixel's read-out, the colour legend and the error histogram.

#include "panels/panel_views.h"

namespace rrf::panels::views_figures {

/// True when the FLIP map on hand was computed from the images on screen.
bool flipShown(const ViewsPanelView& panel);
/// Height of the error histogram's block (plot, tick labels, its line of counts).
float histogramHeight();
/// The error view's log histogram (ViewState::errorHistogram): bars of the kept pixels' count per
/// bin over |value| from 1e-5 to 10 on a log axis, the counts outside beside it.
void drawHistogram(const ViewState& v, float width);
/// The figures of the error map: `rrf evaluate`'s overall row for the term, what it leaves out, the
/// region of interest's figures and, with FLIP on, the FLIP map's.
void drawErrorFigures(const ViewsPanelView& panel);
/// The error map's colour scale, `width` wide, with its ends labelled.
void drawLegend(const ViewState& v, float width);
/// The hovered pixel's values in the reference `ref` and the compared image `cmp`, its object, its
/// error and whether the footprint mask leaves it out.
void drawReadout(const ViewsPanelView& panel, const Image& ref, const Image& cmp);

}  // namespace rrf::panels::views_figures
