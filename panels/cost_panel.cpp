// Cost panel: what accuracy costs in time, comparably. Each sweep of this session (core/pipeline/sweep.h,
// run as a job) measures every point against one reference at one resolution, so its series compare:
//   - the path tracer: error against render time (one circle per spp, labelled with its spp);
//   - the models: error against the one-off cost (data + training; filled squares, connected) and
//     against the per-frame prediction time (hollow squares: CPU, triangles: GLSL).
// The error is the relative RMSE of the global term with the reference's noise subtracted
// (comparableError, core/eval/break_even.h), the figure `rrf evaluate` reports as "corrected"; the
// reference's noise floor is a dashed line. A GLSL frame is the GPU time of its passes (timer
// queries), a CPU frame its wall time; each series' legend entry names its resolution. For each model point the break-even — the spp and seconds
// the path tracer of the same sweep needs for the model's error — is a cross on the path tracer's
// line, joined by a dotted line to the model's per-frame time, and a sentence under the plot. Both
// axes are log10 with decade grids, so the path tracer's 1/sqrt(N) is a straight line. Colours come
// from the series' names (seriesColour(name)), so a series keeps its colour. The project's evaluated
// training runs can be shown too (diamonds, with their frame times), marked as what they are: each
// against its own ground truth, in the same corrected figure where their reference's noise was known.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "core/pipeline/sweep.h"
#include "core/util/text_format.h"
#include "panels/figure_text.h"
#include "panels/panels.h"
#include "panels/plot.h"

namespace rrf::panels {

namespace cost_panel_detail {
namespace {
void drawToolbar(const CostPanelView& panel) {
    CostView& v = panel.costView;
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 6);
    ImGui::Combo("sweep", &v.what, kSweepKinds, kSweepKindCount);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("spp: path tracer vs samples; grid: viewpoint grid; dirs: directions per viewpoint; hidden: network size; trainer: LM vs Adam\n"
                          "goal: error goal (trainer stop and kd-tree split); leaves: kd-tree leaf budget; record_spp: most paths per training record\n"
                          "encoding: the networks' input encoding (raw, frequency, hash grid), with parameters and model bytes per row\n"
                          "ensemble: networks averaged per leaf (merged into one wider network)\n"
                          "model sweeps also render the path tracer against the same reference, for the break-even");
    ImGui::SameLine();
    if (!panel.cost.running) {
        ImGui::BeginDisabled(!panel.hasProject);
        if (ImGui::Button("Run sweep"))
            panel.actions.request(Command::RunSweep, kSweepKinds[std::clamp(v.what, 0, kSweepKindCount - 1)]);
        ImGui::EndDisabled();
    } else {
        if (ImGui::Button("Stop sweep")) panel.actions.request(Command::CancelSweep);
        ImGui::SameLine();
        ImGui::ProgressBar(float(panel.cost.progress), ImVec2(ImGui::GetFontSize() * 8, 0));
    }
    ImGui::SameLine();
    ImGui::Checkbox("project runs", &v.showRuns);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("the project's evaluated training runs: each against its own ground truth (raw error),\n"
                          "so they do not compare with the sweeps' points");
    ImGui::SameLine();
    if (ImGui::Button("Clear sweeps")) panel.cost.sweeps.clear();
}

const CostSeries* findSeries(const std::vector<const CostSeries*>& series, const std::string& name) {
    for (const CostSeries* s : series)
        if (s->name == name) return s;
    return nullptr;
}

/// A triangle (GLSL frame time), a square (CPU frame time, one-off cost), a diamond (a project run's
/// one-off cost), a cross (break-even) or a circle (path tracer) around q.
/// A marker's code in CostView::shapesDrawn / keyShapes: the shape, then "F" (filled) or "h" (hollow).
std::string markerCode(char shape, bool filled) { return std::string(1, shape) + (filled ? "F" : "h"); }

void marker(ImDrawList* dl, const ImVec2& q, ImU32 colour, char shape, bool filled, std::string* drawn = nullptr) {
    if (drawn && drawn->find(markerCode(shape, filled)) == std::string::npos) *drawn += markerCode(shape, filled);
    const float r = 4.f;
    if (shape == 'd') {
        const ImVec2 a(q.x, q.y - r - 1), b(q.x + r + 1, q.y), c(q.x, q.y + r + 1), d(q.x - r - 1, q.y);
        if (filled) dl->AddQuadFilled(a, b, c, d, colour);
        else dl->AddQuad(a, b, c, d, colour, 1.5f);
    } else if (shape == 't') {
        const ImVec2 a(q.x, q.y - r), b(q.x + r, q.y + r * 0.8f), c(q.x - r, q.y + r * 0.8f);
        if (filled) dl->AddTriangleFilled(a, b, c, colour);
        else dl->AddTriangle(a, b, c, colour, 1.5f);
    } else if (shape == 's') {
        if (filled) dl->AddRectFilled(ImVec2(q.x - r, q.y - r), ImVec2(q.x + r, q.y + r), colour);
        else dl->AddRect(ImVec2(q.x - r, q.y - r), ImVec2(q.x + r, q.y + r), colour, 0.f, 0, 1.5f);
    } else if (shape == 'x') {
        dl->AddLine(ImVec2(q.x - r, q.y - r), ImVec2(q.x + r, q.y + r), colour, 2.f);
        dl->AddLine(ImVec2(q.x - r, q.y + r), ImVec2(q.x + r, q.y - r), colour, 2.f);
    } else {
        dl->AddCircleFilled(q, r * 0.9f, colour);
    }
}
}  // namespace
}  // namespace cost_panel_detail

CostSeries runsCostSeries(const std::vector<Run>& runs) {
    CostSeries s;
    s.name = "project runs";
    s.kind = CostKind::Runs;
    std::string resolution;
    for (const Run& r : runs) {
        if (r.kind != "train") continue;
        const RunMetrics& m = r.metrics;
        const double raw = m.relativeRmse.value_or(NAN);
        // The cost of a training run is what it took to get there: data generation plus training.
        const double seconds = r.timings.train.value_or(NAN) + r.timings.generate.value_or(0.0);
        if (!(raw > 0) || !(seconds > 0)) continue;
        // The sweeps' figure (comparableError): corrected where the run's reference noise was known.
        const std::optional<double> corrected = finiteOrNone(m.relativeRmseCorrected);
        CostPoint p{seconds, corrected ? *corrected : raw, r.name};
        p.corrected = corrected.has_value();
        p.rawError = raw;
        p.frameSeconds = m.frameSeconds.value_or(NAN);
        p.glslFrameSeconds = m.glslFrameSeconds.value_or(NAN);
        const int w = m.evaluatedWidth.value_or(0), h = m.evaluatedHeight.value_or(0);
        if (w > 0 && h > 0) p.resolution = sizeText(w, h);
        if (s.points.empty()) resolution = p.resolution;
        else if (resolution != p.resolution) resolution.clear();
        s.points.push_back(p);
    }
    s.resolution = resolution;
    return s;
}

BreakEven costBreakEven(const CostSeries& pathTracer, const CostPoint& model) {
    std::vector<PathTracerPoint> points;
    for (const CostPoint& p : pathTracer.points) points.push_back({p.spp, p.seconds, p.error});
    return breakEven(points, model.error);
}

std::vector<std::string> costBreakEvenLines(const std::vector<const CostSeries*>& series) {
    std::vector<std::string> lines;
    for (const CostSeries* s : series) {
        if (s->kind != CostKind::Models) continue;
        const CostSeries* pt = cost_panel_detail::findSeries(series, s->pathTracer);
        for (const CostPoint& p : s->points) {
            const std::string head = s->name + " " + p.label + ": ";
            if (!pt) {
                lines.push_back(head + "no path-tracer series against the same reference");
                continue;
            }
            lines.push_back(head + breakEvenText(costBreakEven(*pt, p), p.error, p.corrected, p.frameSeconds, p.glslFrameSeconds));
        }
    }
    return lines;
}

void drawCostPanel(const CostPanelView& panel) {
    cost_panel_detail::drawToolbar(panel);
    CostView& v = panel.costView;
    std::vector<const CostSeries*> series;
    for (const CostSeries& s : panel.cost.sweeps) series.push_back(&s);
    const CostSeries runs = runsCostSeries(panel.runs);
    if (v.showRuns && !runs.points.empty()) series.push_back(&runs);
    v.breakEvenLines = costBreakEvenLines(series);

    // Every position a point, a break-even or a floor takes, for the axes' ranges.
    double xlo = INFINITY, xhi = 0, ylo = INFINITY, yhi = 0;
    auto extend = [&](double x, double y) {
        if (x > 0 && std::isfinite(x)) xlo = std::min(xlo, x), xhi = std::max(xhi, x);
        if (y > 0 && std::isfinite(y)) ylo = std::min(ylo, y), yhi = std::max(yhi, y);
    };
    // The series shown: all but those switched off in the legend (which still lists them).
    std::vector<const CostSeries*> shown;
    for (const CostSeries* s : series)
        if (!seriesHidden(v.hidden, s->name)) shown.push_back(s);
    for (const CostSeries* s : shown) {
        extend(NAN, s->noiseFloor);
        for (const CostPoint& p : s->points) {
            extend(p.seconds, p.error);
            extend(p.frameSeconds, p.error);
            extend(p.glslFrameSeconds, p.error);
        }
    }
    const float font = ImGui::GetFontSize();
    const float line = ImGui::GetTextLineHeightWithSpacing();
    const float legendW = series.empty() ? 0.f : font * 16;
    // Room under the plot for the break-even sentences, wrapped to the pane's width (at most 8 lines).
    const float wrap = ImGui::GetContentRegionAvail().x;
    float below = v.breakEvenLines.empty() ? 0.f : line;
    for (const std::string& l : v.breakEvenLines)
        below += ImGui::CalcTextSize(l.c_str(), nullptr, false, wrap).y + ImGui::GetStyle().ItemSpacing.y;
    below = std::min(below, line * 8.f);
    const PlotArea area = plotArea("##cost-plot", legendW, below);
    const bool hovered = area.hovered;
    const ImVec2 pmin = area.min, pmax = area.max;
    v.plotMinX = pmin.x, v.plotMinY = pmin.y, v.plotMaxX = pmax.x, v.plotMaxY = pmax.y;
    PlotAxis x = logAxis(xlo, xhi, pmin.x, pmax.x);
    PlotAxis y = logAxis(ylo, yhi, pmax.y, pmin.y);
    interactPlot(v.plot, area, x, y);  // wheel zooms, drag pans, double-click fits the data again
    ImDrawList* dl = ImGui::GetWindowDrawList();
    drawAxes(dl, pmin, pmax, x, y, "time (s): path tracer render, model data + training or one frame",
             "relative RMSE, global term, corrected (noise subtracted) where the noise is known");
    v.hoverSeries = v.hoverPoint = -1;
    v.shapesDrawn.clear();
    if (series.empty()) {
        dl->AddText(ImVec2(pmin.x + font, pmin.y + font * 1.5f), IM_COL32(170, 170, 170, 255),
                    "No data yet: run a sweep (model sweeps include the path tracer against the same reference).");
        return;
    }
    float best = font * font;
    const ImVec2 m = ImGui::GetIO().MousePos;
    auto hover = [&](const ImVec2& q, size_t i, size_t k) {
        const float d = (q.x - m.x) * (q.x - m.x) + (q.y - m.y) * (q.y - m.y);
        if (hovered && d < best) best = d, v.hoverSeries = int(i), v.hoverPoint = int(k);
    };
    auto at = [&](double seconds, double error) { return ImVec2(x.toPixel(seconds), y.toPixel(error)); };
    auto finite = [](const ImVec2& q) { return std::isfinite(q.x) && std::isfinite(q.y); };
    dl->PushClipRect(pmin, pmax, true);
    for (size_t i = 0; i < series.size(); ++i) {
        const CostSeries& s = *series[i];
        if (seriesHidden(v.hidden, s.name)) continue;
        const ImU32 colour = seriesColour(s.name);
        const CostSeries* pt = s.kind == CostKind::Models ? cost_panel_detail::findSeries(series, s.pathTracer) : nullptr;
        // One dashed line per reference: a model series shares its path tracer's.
        if (s.noiseFloor > 0 && !pt) {
            const float fy = y.toPixel(s.noiseFloor);
            drawDashedLine(dl, ImVec2(pmin.x, fy), ImVec2(pmax.x, fy), seriesColour(s.name, 0.7f));
            dl->AddText(ImVec2(pmin.x + 4, fy - font - 1), seriesColour(s.name, 0.8f), "noise floor");
        }
        std::vector<ImVec2> line;
        for (size_t k = 0; k < s.points.size(); ++k) {
            const CostPoint& p = s.points[k];
            const ImVec2 q = at(p.seconds, p.error);
            if (finite(q)) {
                line.push_back(q);
                hover(q, i, k);
                const char shape = s.kind == CostKind::Models ? 's' : s.kind == CostKind::Runs ? 'd' : 'o';
                cost_panel_detail::marker(dl, q, colour, shape, true, &v.shapesDrawn);
                if (s.kind == CostKind::PathTracer) {
                    char spp[32];
                    std::snprintf(spp, sizeof spp, "%g spp", p.spp);
                    dl->AddText(ImVec2(q.x + 5, q.y + 2), IM_COL32(190, 190, 190, 200), spp);
                }
            }
            if (s.kind == CostKind::PathTracer) continue;
            const ImVec2 cpu = at(p.frameSeconds, p.error), glsl = at(p.glslFrameSeconds, p.error);
            if (finite(cpu)) cost_panel_detail::marker(dl, cpu, colour, 's', false, &v.shapesDrawn), hover(cpu, i, k);
            if (finite(glsl)) cost_panel_detail::marker(dl, glsl, colour, 't', false, &v.shapesDrawn), hover(glsl, i, k);
            if (!pt) continue;
            const BreakEven b = costBreakEven(*pt, p);
            const ImVec2 e = at(b.seconds, p.error);
            if (!b.known || !finite(e)) continue;
            // The break-even: where the path tracer reaches this error, joined to the model's frame time.
            cost_panel_detail::marker(dl, e, seriesColour(pt->name), 'x', false, &v.shapesDrawn);
            const ImVec2 from = finite(glsl) ? glsl : finite(cpu) ? cpu : q;
            if (finite(from)) drawDashedLine(dl, from, e, seriesColour(s.name, 0.6f), 2.f);
        }
        // Sweep settings are ordered (more samples, bigger networks), so a line shows the trend;
        // project runs are independent experiments and stay unconnected.
        if (s.kind != CostKind::Runs && line.size() >= 2) dl->AddPolyline(line.data(), int(line.size()), colour, 0, 1.5f);
    }
    dl->PopClipRect();
    if (v.hoverSeries >= 0) {
        const CostSeries& s = *series[size_t(v.hoverSeries)];
        const CostPoint& p = s.points[size_t(v.hoverPoint)];
        const std::string err = noiseFigureText(p.error) + (p.corrected ? " (corrected)" : " (raw)");
        if (s.kind == CostKind::PathTracer)
            ImGui::SetTooltip("%s: %g spp\nrender %.3g s\nrelative RMSE %s, raw %s", s.name.c_str(), p.spp, p.seconds, err.c_str(),
                              noiseFigureText(p.rawError).c_str());
        else if (s.kind == CostKind::Models)
            ImGui::SetTooltip("%s: %s\ndata + training %.3g s\nper frame: CPU %s ms, GLSL %s ms\nrelative RMSE %s, raw %s\n%s",
                              s.name.c_str(), p.label.c_str(), p.seconds, noiseFigureText(1e3 * p.frameSeconds).c_str(),
                              noiseFigureText(1e3 * p.glslFrameSeconds).c_str(), err.c_str(),
                              noiseFigureText(p.rawError).c_str(), s.reference.c_str());
        else
            ImGui::SetTooltip("%s: %s\ndata + training %.3g s\nper frame: CPU %s ms, GLSL %s ms\nrelative RMSE %s, raw %s, "
                              "against its own ground truth%s%s",
                              s.name.c_str(), p.label.c_str(), p.seconds, noiseFigureText(1e3 * p.frameSeconds).c_str(),
                              noiseFigureText(1e3 * p.glslFrameSeconds).c_str(), err.c_str(),
                              noiseFigureText(p.rawError).c_str(), p.resolution.empty() ? "" : " at ",
                              p.resolution.c_str());
    }
    ImGui::SameLine();
    ImGui::BeginGroup();
    for (const CostSeries* s : series) {
        char text[160];
        // The resolution beside the name: points of different sizes share the axes only when said.
        std::string size = s->resolution;
        if (size.empty())
            size = std::any_of(s->points.begin(), s->points.end(), [](const CostPoint& p) { return !p.resolution.empty(); })
                       ? "sizes differ"
                       : "size not recorded";
        std::snprintf(text, sizeof text, "%s (%zu, %s)", s->name.c_str(), s->points.size(), size.c_str());
        legendEntry(s->name, text, seriesColour(s->name), v.hidden);
        if (!s->reference.empty() && ImGui::IsItemHovered())
            ImGui::SetTooltip("%s\nclick to %s this series", s->reference.c_str(), seriesHidden(v.hidden, s->name) ? "show" : "hide");
    }
    if (!v.plot.autoFit && ImGui::SmallButton("fit the data")) v.plot.autoFit = true;
    ImGui::Spacing();
    // The key draws each marker with the function the plot uses, so the two cannot disagree.
    struct KeyEntry {
        char shape;
        bool filled;
        const char* text;
    };
    static const KeyEntry kKey[] = {{'o', true, "path tracer (render time)"},
                                    {'s', true, "data + training"},
                                    {'d', true, "project run: data + training"},
                                    {'s', false, "CPU frame (wall time)"},
                                    {'t', false, "GLSL frame (GPU time)"},
                                    {'x', false, "break-even"}};
    v.keyShapes.clear();
    const ImU32 keyColour = ImGui::GetColorU32(ImGuiCol_TextDisabled);
    for (const KeyEntry& k : kKey) {
        const ImVec2 at = ImGui::GetCursorScreenPos();
        ImGui::Dummy(ImVec2(font, font));
        cost_panel_detail::marker(ImGui::GetWindowDrawList(), ImVec2(at.x + font * 0.5f, at.y + font * 0.5f), keyColour, k.shape,
                                  k.filled);
        ImGui::SameLine();
        figureTextDisabled("%s", k.text);
        v.keyShapes += cost_panel_detail::markerCode(k.shape, k.filled);
    }
    ImGui::TextDisabled("- - noise floor");
    ImGui::TextDisabled("wheel: zoom, drag: pan,\ndouble-click: fit");
    ImGui::EndGroup();
    if (!v.breakEvenLines.empty()) {
        ImGui::TextUnformatted("Break-even (the same reference and resolution for every point):");
        for (const std::string& l : v.breakEvenLines) figureText("%s", l.c_str());
    }
}

}  // namespace rrf::panels
