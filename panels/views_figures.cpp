// The Views panel's figures under its views (views_figures.h).
#include "panels/views_figures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <imgui.h>

#include "core/scene/camera_rays.h"
#include "panels/figure_text.h"
#include "panels/plot.h"
#include "panels/status_text.h"
#include "panels/view_model.h"

namespace rrf::panels::views_figures {

bool flipShown(const ViewsPanelView& panel) {
    return panel.view.flip && panel.view.flipMap.matches(panel.reference().revision, panel.compared().revision, panel.view.term);
}

float histogramHeight() { return ImGui::GetFontSize() * 9.f; }

/// The error view's log histogram (ViewState::errorHistogram): bars of the kept pixels' count per
/// bin over |value| from 1e-5 to 10 on a log axis, the counts outside beside it.
void drawHistogram(const ViewState& v, float width) {
    const ErrorHistogram& h = v.errorHistogram;
    const float font = ImGui::GetFontSize();
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    const float height = histogramHeight() - ImGui::GetTextLineHeightWithSpacing();
    ImGui::Dummy(ImVec2(width, height));
    const ImVec2 min(origin.x + font * 3.5f, origin.y + font * 1.5f), max(origin.x + width - font * 0.5f, origin.y + height - font * 2.6f);
    if (h.counts.empty() || max.x <= min.x || max.y <= min.y) return;
    uint64_t top = 1;
    for (uint64_t c : h.counts) top = std::max(top, c);
    const PlotAxis x{true, h.lo, h.lo + double(h.counts.size()) / h.perDecade, min.x, max.x};
    const PlotAxis y = linearAxis(0.0, double(top), max.y, min.y);
    ImDrawList* dl = ImGui::GetWindowDrawList();
    drawAxes(dl, min, max, x, y, v.flip ? "FLIP" : "|error|", "pixels");
    for (size_t i = 0; i < h.counts.size(); ++i) {
        if (!h.counts[i]) continue;
        const double e0 = std::pow(10.0, h.lo + double(i) / h.perDecade), e1 = std::pow(10.0, h.lo + double(i + 1) / h.perDecade);
        dl->AddRectFilled(ImVec2(x.toPixel(e0) + 1.f, y.toPixel(double(h.counts[i]))), ImVec2(x.toPixel(e1) - 1.f, max.y),
                          IM_COL32(120, 170, 230, 220));
    }
    figureTextDisabled("%llu pixels: %llu under 1e-5 (zeros included), %llu at 10 or over%s", (unsigned long long)h.total(),
                        (unsigned long long)h.below, (unsigned long long)h.above,
                        h.negative ? (", " + std::to_string(h.negative) + " negative (binned by |value|)").c_str() : "");
}

namespace {
/// The region of interest's figures (every metric over its kept pixels) and a button to clear it.
void drawRegionFigures(const ViewsPanelView& panel) {
    ViewState& v = panel.view;
    if (v.region.empty()) return;
    const ViewRegion& g = v.region;
    figureText("region (%d, %d)-(%d, %d):", g.x0, g.y0, g.x1 - 1, g.y1 - 1);
    ImGui::SameLine();
    if (ImGui::SmallButton("clear region")) v.region = {};
    const ViewErrorStats& f = v.regionStats;
    if (!f.valid) {
        figureTextDisabled("  no compared pixel inside (background, emitter or left out)");
        return;
    }
    const ErrorStats& e = f.stats;
    figureText("  %llu pixels: rel. RMSE %.4g (noise floor %s, corrected %s)  RMSE %.4g (corrected %s)  bias %+.4g  "
                "relMSE %.4g  SMAPE %.4g  MAE %.4g",
                (unsigned long long)e.pixels, e.relativeRmse, noiseFigureText(e.relativeRmseNoiseFloor).c_str(),
                noiseFigureText(e.relativeRmseCorrected).c_str(), e.rmse, noiseFigureText(e.rmseCorrected).c_str(),
                e.signedRelativeMean, e.relMse, e.smape, e.mae);
    if (v.flip && v.regionFlip.pixels)
        figureText("  HDR-FLIP mean %.4g, weighted median %.4g", v.regionFlip.mean, v.regionFlip.weightedMedian);
}
}  // namespace

/// The figures of the error map: `rrf evaluate`'s overall row for the term, and what it leaves out.
void drawErrorFigures(const ViewsPanelView& panel) {
    const ViewErrorStats& f = panel.view.errorStats;
    if (!f.valid && panel.view.compareSource == CompareSource::RunPair) {
        figureTextDisabled("Run pair: the error map is |B - A|, prediction against prediction (no noise floor).");
        return;
    }
    if (!f.waiting.empty()) {
        figureText("Error figures: %s.", f.waiting.c_str());
        return;
    }
    if (!f.valid) {
        figureTextDisabled(panel.images.groundTruth.footprint ? "Error figures: need a compared image of the ground truth's size."
                                                        : "Error figures: need the ground truth's footprint mask (render it).");
        return;
    }
    const ErrorStats& e = f.stats;
    figureText("%s term, %llu pixels: rel. RMSE %.4g (noise floor %s, corrected (noise subtracted) %s)  RMSE %.4g "
                "(noise floor %s, corrected %s)  MAE %.4g",
                termName(panel.view.term), (unsigned long long)e.pixels, e.relativeRmse,
                noiseFigureText(e.relativeRmseNoiseFloor).c_str(), noiseFigureText(e.relativeRmseCorrected).c_str(), e.rmse,
                noiseFigureText(e.rmseNoiseFloor).c_str(), noiseFigureText(e.rmseCorrected).c_str(), e.mae);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("the figures rrf evaluate reports for all objects (per channel, footprint mask's pixels);\n"
                          "noise floor: what the ground truth's own noise gives; corrected: that noise subtracted");
    figureTextDisabled("hatched: %s", f.left.describe().c_str());
    drawRegionFigures(panel);
    if (!panel.view.flip) return;
    const FlipViewMap& m = panel.view.flipMap;
    if (!flipShown(panel)) {
        figureTextDisabled("FLIP: computing the map of these images...");
        return;
    }
    figureText("HDR-FLIP %llu pixels: mean %.4g, weighted median %.4g (quartiles %.4g, %.4g), max %.4g",
                (unsigned long long)m.stats.pixels, m.stats.mean, m.stats.weightedMedian, m.stats.weightedFirstQuartile,
                m.stats.weightedThirdQuartile, m.stats.max);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%d exposures from %.2f to %.2f stops (from the ground truth alone, so runs compare);\n"
                          "the ground truth's own noise is in this figure: rrf evaluate and the Objects table give its floor",
                          m.range.count, m.range.start, m.range.stop);
}

void drawLegend(const ViewState& v, float width) {
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const float h = ImGui::GetFontSize() * 0.8f;
    const int steps = 32;
    // A signed map runs from -scale (blue: below the ground truth) through 0 to +scale (red: above).
    const bool isSigned = !v.flip && errorMapIsSigned(v.metric);
    auto colour = [&](float t) { return v.flip ? magma(t) : isSigned ? coolWarm(2 * t - 1) : viridis(t); };
    for (int i = 0; i < steps; ++i) {
        const float t0 = float(i) / steps, t1 = float(i + 1) / steps;
        const Vec3 c0 = colour(t0), c1 = colour(t1);
        auto col = [](const Vec3& c) {
            return ImGui::ColorConvertFloat4ToU32(ImVec4(linearToSrgb(c.x), linearToSrgb(c.y), linearToSrgb(c.z), 1.f));
        };
        const float x0 = p.x + width * t0, x1 = p.x + width * t1;
        dl->AddRectFilledMultiColor(ImVec2(x0, p.y), ImVec2(x1, p.y + h), col(c0), col(c1), col(c1), col(c0));
    }
    ImGui::Dummy(ImVec2(width, h));
    char lo[48], hi[48];
    if (isSigned) {
        std::snprintf(lo, sizeof lo, "-%.3g below", v.errorMax);
        std::snprintf(hi, sizeof hi, "above +%.3g", v.errorMax);
    } else {
        std::snprintf(lo, sizeof lo, "0");
        std::snprintf(hi, sizeof hi, "%.3g", v.flip ? 1.f : v.errorMax);
    }
    const float x = ImGui::GetCursorPosX();
    ImGui::TextUnformatted(lo);
    if (isSigned) {
        ImGui::SameLine(x + std::max(0.f, 0.5f * (width - ImGui::CalcTextSize("0").x)));
        ImGui::TextUnformatted("0");
    }
    ImGui::SameLine(x + std::max(0.f, width - ImGui::CalcTextSize(hi).x));
    ImGui::TextUnformatted(hi);
}

namespace {
/// The object (or light) the camera ray through pixel (px, py) of a width x height image hits.
std::string objectUnder(const ViewsPanelView& panel, int px, int py, int width, int height) {
    if (!panel.pickAccel) return "?";
    const Scene& scene = panel.project.scene;
    CameraRays camera(scene.camera, width, height);
    Hit hit;
    if (!panel.pickAccel->intersect(camera.generate(px, py, 0.5f, 0.5f), hit)) return "(background)";
    if (hit.light >= 0 && hit.light < int(scene.lights.size())) return "light '" + scene.lights[size_t(hit.light)].name + "'";
    if (hit.object >= 0 && hit.object < int(scene.objects.size()))
        return "#" + std::to_string(hit.object) + " " + scene.objects[size_t(hit.object)].name;
    return "?";
}
}  // namespace

void drawReadout(const ViewsPanelView& panel, const Image& ref, const Image& cmp) {
    const ViewState& v = panel.view;
    if (v.hoverX < 0 || ref.empty() || v.hoverX >= ref.width || v.hoverY >= ref.height) {
        figureTextDisabled("Hover a view for pixel values; wheel zooms, drag pans, right-drag marks a region.");
        return;
    }
    const Vec3 r = ref.at(v.hoverX, v.hoverY);
    figureText("pixel (%d, %d)  %s", v.hoverX, v.hoverY, objectUnder(panel, v.hoverX, v.hoverY, ref.width, ref.height).c_str());
    figureText("%s (%.4g, %.4g, %.4g)", v.compareSource == CompareSource::RunPair ? "A" : "ground truth", r.x, r.y, r.z);
    if (!cmp.empty() && v.hoverX < cmp.width && v.hoverY < cmp.height) {
        const Vec3 c = cmp.at(v.hoverX, v.hoverY);
        ImGui::SameLine();
        figureText("  compared (%.4g, %.4g, %.4g)", c.x, c.y, c.z);
        if (spreadShown(panel.view, panel.images.prediction) && v.hoverX < panel.view.spreadMap.map.width &&
            v.hoverY < panel.view.spreadMap.map.height) {
            ImGui::SameLine();
            figureText("  spread %.4g", panel.view.spreadMap.map.at(v.hoverX, v.hoverY).x);
        }
        if (cmp.width == ref.width && cmp.height == ref.height) {
            ImGui::SameLine();
            if (!v.flip) figureText("  error %.4g", pixelError(c, r, v.metric));
            else if (flipShown(panel) && v.hoverX < panel.view.flipMap.map.width && v.hoverY < panel.view.flipMap.map.height)
                figureText("  FLIP %.4g", panel.view.flipMap.map.at(v.hoverX, v.hoverY).x);
            else figureTextDisabled("  FLIP computing");
            const FootprintMask* mask = panel.images.groundTruth.footprint.get();
            const size_t i = size_t(v.hoverY) * size_t(ref.width) + size_t(v.hoverX);
            if (mask && mask->width == ref.width && mask->height == ref.height && !mask->isKept(i)) {
                ImGui::SameLine();
                figureTextDisabled("  left out (%s)", footprintName(mask->pixel[i]));
            }
        }
    }
}
}  // namespace rrf::panels::views_figures
