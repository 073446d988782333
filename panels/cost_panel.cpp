// Cost panel: what accuracy costs in time. Each sweep of this session (core/eval/sweep.h, run as a job)
// is one line of points (setting's wall time, relative RMSE of the global term), and the project's
// evaluated training runs are one more series; both axes are log10 with decade grids, so the path
// tracer's 1/sqrt(N) shows as a straight line. Hovering a point names its setting and values.
// Every error is core's relative RMSE (core/eval/error_metrics.h: sweeps compute it in core, a run's
// "relative_rmse" comes from rrf::evaluate), the figure `rrf evaluate` reports for the global term.
#include <algorithm>
#include <cmath>

#include <imgui.h>

#include "core/eval/sweep.h"
#include "panels/panels.h"
#include "panels/plot.h"

namespace rrf::panels {

namespace {
void drawToolbar(WorkbenchState& state) {
    CostView& v = state.costView;
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 6);
    ImGui::Combo("sweep", &v.what, kSweepKinds, kSweepKindCount);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("spp: path tracer vs samples; grid: viewpoint grid; dirs: directions per viewpoint; hidden: network size; trainer: LM vs Adam");
    ImGui::SameLine();
    if (!state.cost.running) {
        ImGui::BeginDisabled(!state.hasProject);
        if (ImGui::Button("Run sweep")) state.request(Command::RunSweep, kSweepKinds[std::clamp(v.what, 0, kSweepKindCount - 1)]);
        ImGui::EndDisabled();
    } else {
        if (ImGui::Button("Stop sweep")) state.request(Command::CancelSweep);
        ImGui::SameLine();
        ImGui::ProgressBar(float(state.cost.progress), ImVec2(ImGui::GetFontSize() * 8, 0));
    }
    ImGui::SameLine();
    ImGui::Checkbox("project runs", &v.showRuns);
    ImGui::SameLine();
    if (ImGui::Button("Clear sweeps")) state.cost.sweeps.clear();
}
}  // namespace

CostSeries runsCostSeries(const std::vector<Run>& runs) {
    CostSeries s;
    s.name = "project runs";
    for (const Run& r : runs) {
        if (r.kind != "train") continue;
        const double error = r.metric("relative_rmse").value_or(NAN);
        // The cost of a training run is what it took to get there: data generation plus training.
        const double seconds = r.timing("train").value_or(NAN) + r.timing("generate").value_or(0.0);
        if (!(error > 0) || !(seconds > 0)) continue;
        s.points.push_back({seconds, error, r.name});
    }
    return s;
}

void drawCostPanel(WorkbenchState& state) {
    drawToolbar(state);
    CostView& v = state.costView;
    std::vector<const CostSeries*> series;
    for (const CostSeries& s : state.cost.sweeps) series.push_back(&s);
    const CostSeries runs = runsCostSeries(state.project.runs);
    if (v.showRuns && !runs.points.empty()) series.push_back(&runs);

    double xlo = INFINITY, xhi = 0, ylo = INFINITY, yhi = 0;
    for (const CostSeries* s : series)
        for (const CostPoint& p : s->points)
            if (p.seconds > 0 && p.error > 0) {
                xlo = std::min(xlo, p.seconds), xhi = std::max(xhi, p.seconds);
                ylo = std::min(ylo, p.error), yhi = std::max(yhi, p.error);
            }
    const float font = ImGui::GetFontSize();
    const float legendW = series.empty() ? 0.f : font * 12;
    const PlotArea area = plotArea("##cost-plot", legendW);
    const bool hovered = area.hovered;
    const ImVec2 pmin = area.min, pmax = area.max;
    const PlotAxis x = logAxis(xlo, xhi, pmin.x, pmax.x);
    const PlotAxis y = logAxis(ylo, yhi, pmax.y, pmin.y);
    ImDrawList* dl = ImGui::GetWindowDrawList();
    drawAxes(dl, pmin, pmax, x, y, "wall time (s)", "relative RMSE (global term)");
    v.hoverSeries = v.hoverPoint = -1;
    if (series.empty()) {
        dl->AddText(ImVec2(pmin.x + font, pmin.y + font * 1.5f), IM_COL32(170, 170, 170, 255),
                    "No data yet: run a sweep, or train and evaluate (each evaluated run adds a point).");
        return;
    }
    float best = font * font;
    const ImVec2 m = ImGui::GetIO().MousePos;
    dl->PushClipRect(pmin, pmax, true);
    for (size_t i = 0; i < series.size(); ++i) {
        std::vector<ImVec2> pts;
        for (size_t k = 0; k < series[i]->points.size(); ++k) {
            const CostPoint& p = series[i]->points[k];
            const ImVec2 q(x.toPixel(p.seconds), y.toPixel(p.error));
            if (!std::isfinite(q.x) || !std::isfinite(q.y)) continue;
            pts.push_back(q);
            const float d = (q.x - m.x) * (q.x - m.x) + (q.y - m.y) * (q.y - m.y);
            if (hovered && d < best) best = d, v.hoverSeries = int(i), v.hoverPoint = int(k);
        }
        // Sweep settings are ordered (more samples, bigger grids), so a line shows the trend;
        // project runs are independent experiments and stay unconnected.
        const bool line = series[i] != &runs;
        if (line && pts.size() >= 2) dl->AddPolyline(pts.data(), int(pts.size()), seriesColour(int(i)), 0, 1.5f);
        for (const ImVec2& q : pts) dl->AddCircleFilled(q, 3.5f, seriesColour(int(i)));
    }
    dl->PopClipRect();
    if (v.hoverSeries >= 0) {
        const CostSeries& s = *series[size_t(v.hoverSeries)];
        const CostPoint& p = s.points[size_t(v.hoverPoint)];
        ImGui::SetTooltip("%s: %s\n%.3g s\nrelative RMSE %.4g", s.name.c_str(), p.label.c_str(), p.seconds, p.error);
    }
    ImGui::SameLine();
    ImGui::BeginGroup();
    for (size_t i = 0; i < series.size(); ++i) {
        const ImVec2 p = ImGui::GetCursorScreenPos();
        dl->AddRectFilled(ImVec2(p.x, p.y + font * 0.3f), ImVec2(p.x + font * 0.7f, p.y + font), seriesColour(int(i)));
        ImGui::Dummy(ImVec2(font * 0.8f, font));
        ImGui::SameLine();
        ImGui::Text("%s (%zu)", series[i]->name.c_str(), series[i]->points.size());
    }
    ImGui::EndGroup();
}

}  // namespace rrf::panels
