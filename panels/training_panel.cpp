// Training panel: start and stop the training job, its epoch / time / μ or learning rate, and the
// live loss plot — train and validation loss on a log10 y axis with a decade grid, one curve per
// network (colour per network, legend) or their mean, and a hover read-out of the nearest point.
// Without a running or finished job in this session it shows the project's last training run.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <imgui.h>

#include "panels/figure_text.h"
#include "panels/panels.h"
#include "panels/layout.h"
#include "panels/plot.h"
#include "panels/status_text.h"

namespace rrf::panels {

namespace training_panel_detail {
namespace {
struct Shown {
    const std::vector<LossCurve>* curves = nullptr;
    std::string source;  ///< where the curves come from, for the header line
};

Shown shownCurves(const TrainingPanelView& panel) {
    if (!panel.training.curves.empty() || panel.training.running)
        return {&panel.training.curves, panel.training.running ? "live" : "this session"};
    for (auto it = panel.runs.rbegin(); it != panel.runs.rend(); ++it)
        if (it->kind == "train" && !it->curves.empty()) return {&it->curves, "run '" + it->name + "'"};
    return {&panel.training.curves, ""};
}

void drawToolbar(const TrainingPanelView& panel) {
    const TrainingInfo& t = panel.training;
    if (!t.running) {
        ImGui::BeginDisabled(!panel.hasProject);
        if (ImGui::Button("Train")) panel.actions.request(Command::Train);
        ImGui::EndDisabled();
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
            ImGui::SetTooltip("trains the Network panel's networks on the Sampling panel's dataset");
    } else if (ImGui::Button("Stop")) {
        panel.actions.request(Command::CancelTrain);
    }
    ImGui::SameLine();
    ImGui::BeginDisabled(t.running || t.modelsDir.empty());
    if (ImGui::Button("Evaluate")) panel.actions.request(Command::Evaluate);
    ImGui::EndDisabled();
    if (t.running || t.epoch > 0) {
        const std::string overlay = trainingProgressText(t);
        const float barW = std::max(ImGui::GetFontSize() * 8, ImGui::CalcTextSize(overlay.c_str()).x + ImGui::GetFontSize());
        sameLineIfFits(barW);
        ImGui::ProgressBar(float(t.progress), ImVec2(barW, 0), overlay.c_str());
        const bool lm = t.trainer != "adam";
        char line[96];
        std::snprintf(line, sizeof line, "epoch %d  %.1f s  %s %.3g", t.epoch, t.seconds, lm ? "mu" : "learning rate", t.step);
        sameLineIfFits(ImGui::CalcTextSize(line).x);
        ImGui::TextUnformatted(line);
    }
    // The toolbar wraps in a narrow pane instead of cutting the checkboxes off.
    const float box = ImGui::GetFrameHeight();
    sameLineIfFits(labelledWidth(box, "mean of all networks"));
    ImGui::Checkbox("mean of all networks", &panel.trainingView.aggregate);
    sameLineIfFits(labelledWidth(box, "train"));
    ImGui::Checkbox("train", &panel.trainingView.showTrain);
    sameLineIfFits(labelledWidth(box, "validation"));
    ImGui::Checkbox("validation", &panel.trainingView.showValidation);
}

/// Finds the displayed point nearest to the mouse (within a few pixels) and shows its values.
void hoverReadout(TrainingView& v, const std::vector<LossCurve>& curves, const PlotAxis& x, const PlotAxis& y) {
    const ImVec2 m = ImGui::GetIO().MousePos;
    float best = ImGui::GetFontSize() * 0.75f;
    best *= best;
    for (size_t c = 0; c < curves.size(); ++c)
        if (!seriesHidden(v.hidden, curves[c].label()))
            for (const LossPoint& p : curves[c].points)
                for (double value : {v.showTrain ? p.train : NAN, v.showValidation ? p.validation : NAN}) {
                const float py = y.toPixel(value);
                if (!std::isfinite(py)) continue;
                const float dx = x.toPixel(p.epoch) - m.x, dy = py - m.y;
                if (dx * dx + dy * dy < best) {
                    best = dx * dx + dy * dy;
                    v.hoverCurve = int(c);
                    v.hoverEpoch = p.epoch;
                }
            }
    if (v.hoverCurve < 0) return;
    for (const LossPoint& p : curves[size_t(v.hoverCurve)].points)
        if (p.epoch == v.hoverEpoch)
            ImGui::SetTooltip("%s\nepoch %d\ntrain %.4g\nvalidation %.4g\n%.2f s", curves[size_t(v.hoverCurve)].label().c_str(),
                              p.epoch, p.train, p.validation, p.seconds);
}

void drawCurve(ImDrawList* dl, const std::vector<LossPoint>& pts, bool validation, const PlotAxis& x, const PlotAxis& y,
               ImU32 colour, float thickness) {
    std::vector<ImVec2> line;
    auto flush = [&] {
        if (line.size() >= 2) dl->AddPolyline(line.data(), int(line.size()), colour, 0, thickness);
        else if (line.size() == 1) dl->AddCircleFilled(line[0], thickness + 1.f, colour);
        line.clear();
    };
    for (const LossPoint& p : pts) {
        const float py = y.toPixel(validation ? p.validation : p.train);
        if (!std::isfinite(py)) {  // NaN (no validation set) or a zero loss: a gap in the line
            flush();
            continue;
        }
        line.emplace_back(x.toPixel(p.epoch), py);
    }
    flush();
}

/// After a stop: what the prediction shows, and the choice of the partial models.
void drawStoppedChoice(const TrainingPanelView& panel) {
    const TrainingInfo& t = panel.training;
    if (t.running || !t.stopped || t.partialRun < 0 || t.partialRun >= int(panel.runs.size())) return;
    figureTextColored(ImVec4(1.f, 0.8f, 0.3f, 1.f), "Training %s.", trainingProgressText(t).c_str());
    ImGui::SameLine();
    ImGui::TextDisabled(t.modelsDir.empty() ? "No prediction is shown." : "The prediction keeps the last complete models.");
    ImGui::SameLine();
    if (ImGui::SmallButton("Use the partial models")) panel.actions.request(Command::CompareRun, {}, t.partialRun);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("show the stopped run's networks; objects without one are drawn hatched magenta");
}

void drawTrainingBody(const TrainingPanelView& panel) {
    TrainingView& v = panel.trainingView;
    v.hoverCurve = v.hoverEpoch = -1;
    const Shown shown = shownCurves(panel);
    std::vector<LossCurve> mean;
    if (v.aggregate && !shown.curves->empty()) {
        LossCurve c;
        c.object = "mean of";
        c.target = std::to_string(shown.curves->size()) + " networks";
        c.points = aggregateLoss(*shown.curves);
        mean.push_back(std::move(c));
    }
    const std::vector<LossCurve>& curves = v.aggregate ? mean : *shown.curves;

    double lo = INFINITY, hi = 0;
    int lastEpoch = 1;
    for (const LossCurve& c : curves)
        if (!seriesHidden(v.hidden, c.label()))
            for (const LossPoint& p : c.points) {
            lastEpoch = std::max(lastEpoch, p.epoch);
            for (double value : {v.showTrain ? p.train : NAN, v.showValidation ? p.validation : NAN})
                if (value > 0 && std::isfinite(value)) lo = std::min(lo, value), hi = std::max(hi, value);
        }

    // A network with a constant target (a surface no direct light reaches) drives its loss to
    // 1e-20 and below; eight decades under the largest loss is all a user can read, the rest is clipped.
    lo = std::max(lo, hi * 1e-8);

    const float font = ImGui::GetFontSize();
    // The legend is as wide as its widest line (colour box, network, last train / validation loss).
    std::vector<std::string> legend;
    for (const LossCurve& c : curves) {
        char line[160];
        const LossPoint* last = c.points.empty() ? nullptr : &c.points.back();
        if (last) std::snprintf(line, sizeof line, "%s  %.3g / %.3g", c.label().c_str(), last->train, last->validation);
        else std::snprintf(line, sizeof line, "%s", c.label().c_str());
        legend.emplace_back(line);
    }
    float legendW = 0.f;
    if (!curves.empty()) {
        legendW = std::max(ImGui::CalcTextSize(shown.source.c_str()).x, ImGui::CalcTextSize("thick: train, thin: validation").x);
        for (const std::string& line : legend)
            legendW = std::max(legendW, font * 0.8f + ImGui::GetStyle().ItemSpacing.x + ImGui::CalcTextSize(line.c_str()).x);
        legendW += 2 * ImGui::GetStyle().ItemSpacing.x;
    }
    const PlotArea area = plotArea("##loss-plot", legendW);
    const bool hovered = area.hovered;
    const ImVec2 pmin = area.min, pmax = area.max;
    PlotAxis x = linearAxis(0, lastEpoch, pmin.x, pmax.x);
    PlotAxis y = logAxis(lo, hi, pmax.y, pmin.y);
    interactPlot(v.plot, area, x, y);  // wheel zooms, drag pans, double-click fits the data again
    v.plotMinX = pmin.x, v.plotMinY = pmin.y, v.plotMaxX = pmax.x, v.plotMaxY = pmax.y;
    v.yLo = y.lo, v.yHi = y.hi;

    ImDrawList* dl = ImGui::GetWindowDrawList();
    drawAxes(dl, pmin, pmax, x, y, "epoch", "loss (normalised units)");
    if (curves.empty()) {
        dl->AddText(ImVec2(pmin.x + font, pmin.y + font * 1.5f), IM_COL32(170, 170, 170, 255),
                    panel.hasProject ? "No training yet: generate a dataset, then press Train." : "No project is open.");
        return;
    }
    dl->PushClipRect(pmin, pmax, true);
    for (size_t c = 0; c < curves.size(); ++c) {
        if (seriesHidden(v.hidden, curves[c].label())) continue;
        if (v.showTrain) drawCurve(dl, curves[c].points, false, x, y, seriesColour(int(c)), 2.f);
        if (v.showValidation) drawCurve(dl, curves[c].points, true, x, y, seriesColour(int(c), 0.55f), 1.f);
    }
    dl->PopClipRect();
    if (hovered) hoverReadout(v, curves, x, y);

    // Legend: colour, network, last train / validation loss.
    ImGui::SameLine();
    ImGui::BeginGroup();
    figureTextDisabled("%s", shown.source.c_str());
    ImGui::TextDisabled("thick: train, thin: validation");
    for (size_t c = 0; c < curves.size(); ++c) legendEntry(curves[c].label(), legend[c].c_str(), seriesColour(int(c)), v.hidden);
    if (!v.plot.autoFit && ImGui::SmallButton("fit the data")) v.plot.autoFit = true;
    ImGui::TextDisabled("wheel: zoom, drag: pan,\ndouble-click: fit");
    ImGui::EndGroup();
}
}  // namespace
}  // namespace training_panel_detail

void drawTrainingPanel(const TrainingPanelView& panel) {
    training_panel_detail::drawToolbar(panel);
    if (panel.actions.notice && panel.actions.notice->panel == "Training") drawNotice(panel.actions.notice);
    training_panel_detail::drawStoppedChoice(panel);
    training_panel_detail::drawTrainingBody(panel);
}

}  // namespace rrf::panels
