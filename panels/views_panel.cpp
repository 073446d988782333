// Views panel: ground truth | compared image | error map side by side. The three views share one
// zoom/pan (wheel zooms about the cursor, drag pans), one exposure and one hover read-out. The error
// map is what `rrf evaluate` reports: core's per-pixel metric, with the pixels the footprint mask
// leaves out drawn hatched (panels/view_model.h), and under it the figures of evaluate()'s overall
// row (raw, noise floor, corrected) with the counts of the pixels left out.
#include <algorithm>
#include <array>
#include <iterator>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <imgui.h>

#include "core/scene/camera_rays.h"
#include "core/project/scene_edits.h"
#include "core/scene/light_drag.h"
#include "panels/clip_check.h"
#include "panels/figure_text.h"
#include "panels/layout.h"
#include "panels/panels.h"
#include "panels/plot.h"
#include "panels/status_text.h"
#include "panels/view_model.h"
#include "panels/views_figures.h"

namespace rrf::panels {

namespace views_panel_detail {
namespace {
constexpr float kMinZoom = 0.25f, kMaxZoom = 64.f;
/// The term combo lists global first (what one looks at most); its entries map to core's Term here.
constexpr Term kTermMenu[] = {Term::Global, Term::Direct, Term::Indirect};

/// Combo over `items` (names from `name`); returns true and sets `value` when the user picked another.
template <typename T, size_t N, typename Name>
bool enumCombo(const char* label, T& value, const T (&items)[N], Name name) {
    bool changed = false;
    if (ImGui::BeginCombo(label, name(value))) {
        for (const T& item : items) {
            const bool selected = item == value;
            if (ImGui::Selectable(name(item), selected) && !selected) value = item, changed = true;
            if (selected) ImGui::SetItemDefaultFocus();
        }
        ImGui::EndCombo();
    }
    return changed;
}

/// "relative: mean_c |d_c| / (|ref_c| + 0.01)", the label of an error map kind in the views.
const char* errorMapLabel(ErrorMapKind k) {
    static const auto labels = [] {
        std::array<std::string, std::size(kErrorMapKinds)> l;
        for (ErrorMapKind e : kErrorMapKinds) l[size_t(e)] = std::string(errorMapName(e)) + ": " + errorMapFormula(e);
        return l;
    }();
    return labels[size_t(k)].c_str();
}

/// The error combo's entry for the FLIP map.
constexpr const char* kFlipLabel = "FLIP: HDR-FLIP, perceived difference in [0, 1]";

/// The label of the error view's map: FLIP or the per-pixel metric.
const char* errorViewLabel(const ViewState& v) { return v.flip ? kFlipLabel : errorMapLabel(v.metric); }

/// Screen mapping of one view: image pixel q ↦ centre + (q − imageCentre − pan) · scale.
struct ViewRect {
    ImVec2 min, max, centre;
    float scale = 1.f;
    ImVec2 imageCentre;
    ImVec2 toScreen(float qx, float qy, const ViewState& v) const {
        return ImVec2(centre.x + (qx - imageCentre.x - v.panX) * scale, centre.y + (qy - imageCentre.y - v.panY) * scale);
    }
    ImVec2 toImage(const ImVec2& p, const ViewState& v) const {
        return ImVec2((p.x - centre.x) / scale + imageCentre.x + v.panX, (p.y - centre.y) / scale + imageCentre.y + v.panY);
    }
};

/// The image pixel under screen point `p` in view `r`, clamped into the image.
void pixelAt(const ViewRect& r, const ViewState& v, const Image& image, const ImVec2& p, int& x, int& y) {
    const ImVec2 q = r.toImage(p, v);
    x = std::clamp(int(std::floor(q.x)), 0, image.width - 1);
    y = std::clamp(int(std::floor(q.y)), 0, image.height - 1);
}

/// The right-button drag that draws the region of interest: pressed over a view it anchors at the
/// pixel there, dragged it spans the anchor and the pixel under the mouse (both included), and a
/// click without a drag clears the region.
void dragRegion(ViewState& v, int index, const ViewRect& r, const Image& image, bool hovered) {
    const ImGuiIO& io = ImGui::GetIO();
    if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Right)) {
        v.regionDragView = index;
        pixelAt(r, v, image, io.MousePos, v.regionAnchorX, v.regionAnchorY);
    }
    if (v.regionDragView != index) return;
    if (ImGui::IsMouseDragging(ImGuiMouseButton_Right)) {
        int x = 0, y = 0;
        pixelAt(r, v, image, io.MousePos, x, y);
        v.region = {std::min(x, v.regionAnchorX), std::min(y, v.regionAnchorY), std::max(x, v.regionAnchorX) + 1,
                    std::max(y, v.regionAnchorY) + 1};
    }
    if (!ImGui::IsMouseDown(ImGuiMouseButton_Right)) {
        const float t = io.MouseDragThreshold;
        if (ImGui::IsMouseReleased(ImGuiMouseButton_Right) && io.MouseDragMaxDistanceSqr[ImGuiMouseButton_Right] < t * t)
            v.region = {};
        v.regionDragView = -1;
    }
}

/// The controls above the views: render, save run, reset view and the display settings of `v`;
/// `r` for the render's progress; the buttons' requests go to `requests`.
void drawToolbar(ViewState& v, const RenderProgress& r, std::vector<Request>& requests) {
    auto request = [&](Command c) { requests.push_back({c, {}, -1}); };
    if (!r.running) {
        if (ImGui::Button("Render")) request(Command::StartRender);
    } else if (ImGui::Button("Stop render")) {
        request(Command::CancelRender);
    }
    if (r.running || r.spp > 0) {
        char overlay[128];
        std::snprintf(overlay, sizeof overlay, "%s  noise (rel. RMSE of the mean) %s", renderProgressText(r).c_str(),
                      noiseFigureText(r.relativeNoise).c_str());
        // As wide as its text (at least 24 em), on the next line when this one has no room for it.
        const float barW = std::max(ImGui::GetFontSize() * 24,
                                    ImGui::CalcTextSize(overlay).x + 2 * ImGui::GetStyle().FramePadding.x);
        sameLineIfFits(barW);
        fittedProgressBar(r.targetSpp > 0 ? float(r.spp) / float(r.targetSpp) : 0.f, barW, overlay);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("%.2f s, %.3g samples/s%s\nnoise (rel. RMSE of the mean): the image's relative RMSE noise floor,\n"
                              "sqrt(mean Var(mean) / (|image| + 0.01)^2) over the footprint mask's pixels (global term):\n"
                              "the error a perfect prediction would show against this image",
                              r.seconds, r.samplesPerSecond,
                              r.etaSeconds >= 0 ? (", ETA " + std::to_string(int(r.etaSeconds + 0.5)) + " s").c_str() : "");
    }
    sameLineIfFits(ImGui::CalcTextSize("Save run").x + 2 * ImGui::GetStyle().FramePadding.x);
    if (ImGui::Button("Save run")) request(Command::SaveRun);
    ImGui::SameLine();
    if (ImGui::Button("Reset view")) {
        v.zoom = 1.f;
        v.panX = v.panY = 0.f;
    }

    const float w = ImGui::GetFontSize() * 7;
    const float box = ImGui::GetFrameHeight();  // a checkbox's square
    // Each item goes on the line when it fits, else the toolbar wraps (nothing is cut off).
    ImGui::SetNextItemWidth(w);
    enumCombo("term", v.term, kTermMenu, termName);
    sameLineIfFits(labelledWidth(w, "exposure"));
    ImGui::SetNextItemWidth(w);
    ImGui::SliderFloat("exposure", &v.exposure, -8.f, 8.f, "%+.1f EV");
    // The error combo is as wide as its longest entry's preview needs, so the metric is readable.
    const float metricW = ImGui::CalcTextSize(errorViewLabel(v)).x + ImGui::GetFrameHeight() +
                          2 * ImGui::GetStyle().FramePadding.x;
    sameLineIfFits(labelledWidth(metricW, "error"));
    ImGui::SetNextItemWidth(metricW);
    // The per-pixel metrics, then FLIP (a map of the whole image, computed on a worker).
    if (ImGui::BeginCombo("error", errorViewLabel(v))) {
        for (ErrorMapKind k : kErrorMapKinds) {
            const bool selected = !v.flip && k == v.metric;
            if (ImGui::Selectable(errorMapLabel(k), selected)) v.metric = k, v.flip = false;
        }
        if (ImGui::Selectable(kFlipLabel, v.flip)) v.flip = true;
        ImGui::EndCombo();
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(v.flip ? "HDR-FLIP (Andersson et al. 2020, 2021): the perceived difference, max over the ground truth's\n"
                                   "exposure range, in magma over [0, 1]; the FLIP rrf evaluate reports"
                                 : "per channel, averaged over R, G, B (d = compared - ground truth):\nthe metric rrf evaluate and the Objects table report");
    sameLineIfFits(labelledWidth(w, "scale max"));
    ImGui::SetNextItemWidth(w);
    ImGui::BeginDisabled(v.flip);  // FLIP has its own scale, [0, 1]
    ImGui::DragFloat("scale max", &v.errorMax, v.errorMax * 0.01f + 1e-6f, 1e-6f, 1e6f, "%.3g",
                     ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
    ImGui::EndDisabled();
    sameLineIfFits(labelledWidth(box, "highlight"));
    ImGui::Checkbox("highlight", &v.highlight);
    sameLineIfFits(labelledWidth(box, "leaves"));
    ImGui::Checkbox("leaves", &v.leafOverlay);  // tint the compared view by kd-tree leaf
    sameLineIfFits(labelledWidth(box, "spread"));
    ImGui::Checkbox("spread", &v.spread);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("the middle view shows the ensemble members' relative spread, mean_c sd_c / (|pred_c| + 0.01):\n"
                          "where the members disagree, without a reference (also for a moved light);\n"
                          "the Objects panel gives its rank correlation with the error");
    sameLineIfFits(labelledWidth(box, "histogram"));
    ImGui::Checkbox("histogram", &v.histogram);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("the error map's values over the compared pixels, on a log axis");
    int source = int(v.compareSource);
    sameLineIfFits(labelledWidth(w * 1.3f, "middle view"));
    ImGui::SetNextItemWidth(w * 1.3f);
    if (ImGui::Combo("middle view", &source, "prediction\0compared run\0run pair (A | B)\0")) v.compareSource = CompareSource(source);
}

/// The movable light's handle where its centre projects into view `r`: a drag moves the light in the
/// plane facing the camera (Shift: the horizontal plane, keeping its height) within the light region,
/// as the Scene panel's sliders do.
void lightHandle(const ViewsPanelView& panel, int index, const ViewRect& r, const Image& image, bool activated, bool active) {
    ViewState& v = panel.view;
    const Scene& scene = panel.project.scene;
    v.lightHandle[index] = ImVec2(NAN, NAN);
    if (scene.lights.empty() || scene.lightRegion.empty()) return;
    const ImGuiIO& io = ImGui::GetIO();
    if (v.lightDragView == index && active) {
        const ImVec2 q = r.toImage(io.MousePos, v);
        const LightDragPlane plane = io.KeyShift ? LightDragPlane::Horizontal : LightDragPlane::Facing;
        const Vec3 p = lightUnderPointer(scene.camera, image.width, image.height, q.x, q.y, v.lightDragStart, plane,
                                         scene.lightRange());
        if (p != scene.lightPosition()) {
            moveLight(panel.project, p);
            panel.actions.markDirty();
            panel.actions.request(Command::SceneChanged);
        }
    } else if (v.lightDragView == index) {
        v.lightDragView = -1;
    }
    float x = 0.f, y = 0.f;
    if (!projectToImage(scene.camera, image.width, image.height, scene.lightPosition(), x, y)) return;
    const ImVec2 c = r.toScreen(x, y, v);
    v.lightHandle[index] = c;
    const float radius = std::max(5.f, ImGui::GetFontSize() * 0.45f);
    const float dx = io.MousePos.x - c.x, dy = io.MousePos.y - c.y;
    const bool onHandle = dx * dx + dy * dy <= 4.f * radius * radius && ImGui::IsItemHovered();
    if (activated && onHandle && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
        v.lightDragView = index;
        v.lightDragStart = scene.lightPosition();
    }
    const bool held = v.lightDragView == index;
    if (onHandle && !held) ImGui::SetTooltip("Drag to move the light (Shift: keep its height)");
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->PushClipRect(r.min, r.max, true);
    dl->AddCircleFilled(c, held || onHandle ? radius * 1.3f : radius, IM_COL32(255, 220, 60, 230));
    dl->AddCircle(c, held || onHandle ? radius * 1.3f : radius, IM_COL32(20, 20, 20, 255), 0, 1.5f);
    dl->PopClipRect();
}

/// Draws one view and handles zoom/pan on it; returns true while the mouse is over it.
bool drawView(const ViewsPanelView& panel, int index, const char* title, const Image& image, ImVec2 size, ImVec2& hoverPixel) {
    ViewState& v = panel.view;
    ImGui::PushID(index);
    ImGui::BeginGroup();
    // A long title wraps within its view rather than running under the next one.
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + size.x);
    textUnbroken(title);
    ImGui::PopTextWrapPos();
    const ImVec2 pos = ImGui::GetCursorScreenPos();
    // Left button: pan; right button: draw the region of interest.
    ImGui::InvisibleButton("##canvas", size, ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
    v.viewMin[index] = pos;
    v.viewMax[index] = ImVec2(pos.x + size.x, pos.y + size.y);
    const bool hovered = ImGui::IsItemHovered();
    const bool active = ImGui::IsItemActive();
    const bool activated = ImGui::IsItemActivated();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddRectFilled(pos, ImVec2(pos.x + size.x, pos.y + size.y), IM_COL32(24, 24, 28, 255));

    bool over = false;
    if (!image.empty()) {
        ViewRect r;
        r.min = pos;
        r.max = ImVec2(pos.x + size.x, pos.y + size.y);
        r.centre = ImVec2(pos.x + 0.5f * size.x, pos.y + 0.5f * size.y);
        r.scale = std::min(size.x / float(image.width), size.y / float(image.height)) * v.zoom;
        r.imageCentre = ImVec2(0.5f * float(image.width), 0.5f * float(image.height));
        const ImGuiIO& io = ImGui::GetIO();
        if (hovered && io.MouseWheel != 0.f) {
            // Zoom about the cursor: the image point under the mouse stays under the mouse.
            const ImVec2 q = r.toImage(io.MousePos, v);
            v.zoom = std::clamp(v.zoom * std::pow(1.2f, io.MouseWheel), kMinZoom, kMaxZoom);
            r.scale = std::min(size.x / float(image.width), size.y / float(image.height)) * v.zoom;
            v.panX = q.x - r.imageCentre.x - (io.MousePos.x - r.centre.x) / r.scale;
            v.panY = q.y - r.imageCentre.y - (io.MousePos.y - r.centre.y) / r.scale;
        }
        // A left drag pans, unless it started on the light's handle (lightHandle, below).
        if (v.lightDragView != index && active && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 0.f)) {
            v.panX -= io.MouseDelta.x / r.scale;
            v.panY -= io.MouseDelta.y / r.scale;
        }
        dragRegion(v, index, r, image, hovered);
        const ImVec2 a = r.toScreen(0.f, 0.f, v);
        const ImVec2 b = r.toScreen(float(image.width), float(image.height), v);
        dl->PushClipRect(r.min, r.max, true);
        if (panel.viewTextures[index]) dl->AddImage(panel.viewTextures[index], a, b);
        else dl->AddRect(a, b, IM_COL32(200, 200, 200, 255));  // no GL (tests): outline only
        if (!v.region.empty())
            dl->AddRect(r.toScreen(float(v.region.x0), float(v.region.y0), v), r.toScreen(float(v.region.x1), float(v.region.y1), v),
                        IM_COL32(255, 220, 60, 255), 0.f, 0, 2.f);
        dl->PopClipRect();
        lightHandle(panel, index, r, image, activated, active);
        if (hovered) {
            const ImVec2 q = r.toImage(io.MousePos, v);
            if (q.x >= 0.f && q.y >= 0.f && q.x < float(image.width) && q.y < float(image.height)) {
                hoverPixel = ImVec2(std::floor(q.x), std::floor(q.y));
                over = true;
            }
        }
    } else {
        const Image& gt = panel.reference().term(v.term);
        const Image& cmp = panel.compared().term(v.term);
        const bool flipPending = v.flip && !gt.empty() && cmp.width == gt.width && cmp.height == gt.height;
        const char* msg = index == ViewModel::kCompared
                              ? (panel.view.compareSource == CompareSource::Prediction
                                     ? "No prediction yet: generate a dataset\n(Sampling) and train (Training)."
                                     : "No run compared: \"Compare\" a run\nin the Project panel.")
                              : index == ViewModel::kError ? (flipPending ? "FLIP: computing the map\nof these images..."
                                                                          : "Error map: needs a compared image\nof the same size.")
                                                           : "No ground truth yet: press Render.";
        dl->AddText(ImVec2(pos.x + 8, pos.y + 8), IM_COL32(160, 160, 160, 255), msg);
    }
    ImGui::EndGroup();
    ImGui::PopID();
    return over;
}

}  // namespace
}  // namespace views_panel_detail

void drawViewsPanel(const ViewsPanelView& panel) {
    ViewState& v = panel.view;
    v.drawnFrame = ImGui::GetFrameCount();
    for (int i = 0; i < 3; ++i) {
        v.viewMin[i] = v.viewMax[i] = ImVec2(0, 0);
        v.lightHandle[i] = ImVec2(NAN, NAN);  // a view not drawn (single view) has no handle on screen
    }
    ImGui::BeginGroup();
    views_panel_detail::drawToolbar(v, panel.render, panel.actions.requests);
    ImGui::EndGroup();
    v.toolbarMin = ImGui::GetItemRectMin();
    v.toolbarMax = ImGui::GetItemRectMax();
    if (panel.actions.notice && panel.actions.notice->panel == "Views") drawNotice(panel.actions.notice);
    const Image& ref = panel.reference().term(panel.view.term);
    const Image& cmp = panel.compared().term(panel.view.term);
    const bool pair = panel.view.compareSource == CompareSource::RunPair;
    if (pair) {
        figureTextColored(ImVec4(0.5f, 0.8f, 1.f, 1.f), "Comparing run A '%s' | run B '%s' | difference B - A",
                           panel.images.runPair.nameA.c_str(), panel.images.runPair.nameB.c_str());
        ImGui::SameLine();
        if (ImGui::SmallButton("Back to the ground truth")) panel.view.compareSource = CompareSource::Prediction;
    }
    const ImageSet& compared = panel.compared();
    // The histogram takes its height from the views (in a row it sits under them with the figures).
    ImVec2 avail = ImGui::GetContentRegionAvail();
    if (panel.view.histogram) avail.y -= views_figures::histogramHeight();
    const ViewsLayout layout = viewsLayout(avail, ImGui::GetStyle().ItemSpacing,
                                           ImGui::GetTextLineHeightWithSpacing(), ref.empty() ? cmp : ref);
    const ImVec2 size = layout.view;

    char gtTitle[160];
    if (pair) std::snprintf(gtTitle, sizeof gtTitle, "A: %s", panel.images.runPair.imagesA.label.c_str());
    else std::snprintf(gtTitle, sizeof gtTitle, "Ground truth (%s, %d spp)", termName(panel.view.term), panel.render.spp);
    std::string cmpTitle = compared.empty() ? std::string(panel.view.compareSource == CompareSource::Run ? "Compared run" : "Prediction")
                                            : compared.label;
    if (spreadShown(panel.view, panel.images.prediction)) {
        char t[160];
        std::snprintf(t, sizeof t, "Ensemble spread (global term, relative, 0 to %.3g)", panel.view.spreadMap.scale);
        cmpTitle = t;
    }
    const std::string errTitle =
        std::string(pair ? "Difference B vs A: " : "Error: ") + views_panel_detail::errorViewLabel(panel.view);

    ImVec2 hover(-1, -1);
    static const Image kNoImage;
    const bool comparable = !cmp.empty() && cmp.width == ref.width && cmp.height == ref.height;
    const bool errorShown = comparable && (!panel.view.flip || views_figures::flipShown(panel));
    bool over = false;
    if (layout.single) {
        // Too little room for three readable views: one at a time, the others a click away.
        const char* names[3] = {pair ? "A" : "ground truth", pair ? "B" : "compared", pair ? "difference" : "error"};
        for (int i = 0; i < 3; ++i) {
            if (i) sameLineIfFits(labelledWidth(ImGui::GetFrameHeight(), names[i]));
            ImGui::RadioButton(names[i], &v.singleView, i);
        }
        v.singleView = std::clamp(v.singleView, 0, 2);
        if (v.singleView == ViewModel::kReference)
            over = views_panel_detail::drawView(panel, ViewModel::kReference, gtTitle, ref, size, hover);
        else if (v.singleView == ViewModel::kCompared)
            over = views_panel_detail::drawView(panel, ViewModel::kCompared, cmpTitle.c_str(), cmp, size, hover);
        else
            over = views_panel_detail::drawView(panel, ViewModel::kError, errTitle.c_str(), errorShown ? ref : kNoImage, size,
                                                hover);
    } else {
        over = views_panel_detail::drawView(panel, ViewModel::kReference, gtTitle, ref, size, hover);
        ImGui::SameLine();
        over |= views_panel_detail::drawView(panel, ViewModel::kCompared, cmpTitle.c_str(), cmp, size, hover);
        if (!layout.grid) ImGui::SameLine();
        over |=
            views_panel_detail::drawView(panel, ViewModel::kError, errTitle.c_str(), errorShown ? ref : kNoImage, size, hover);
    }
    panel.view.hoverX = over ? int(hover.x) : -1;
    panel.view.hoverY = over ? int(hover.y) : -1;

    // In the grid the figures fill the cell beside the error map; in a row they go below.
    if (layout.grid) {
        ImGui::SameLine();
        ImGui::BeginGroup();
        ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + size.x);
    }
    views_figures::drawErrorFigures(panel);
    if (panel.view.spread) {
        const SpreadViewMap& m = panel.view.spreadMap;
        if (panel.view.compareSource != CompareSource::Prediction)
            figureTextDisabled("Spread: shown for the live prediction only (middle view: prediction).");
        else if (!m.matches(panel.images.prediction.revision)) figureTextDisabled("Spread: computing on the CPU...");
        else if (!m.why.empty()) figureTextColored(ImVec4(1.f, 0.8f, 0.3f, 1.f), "Spread: %s", m.why.c_str());
        else figureTextDisabled("Spread: %llu pixels, viridis over [0, %.3g] (p99); 0 where none is known",
                                 (unsigned long long)m.pixels, m.scale);
    }
    const std::string partial = withoutNetworkText(compared, panel.project.scene);
    if (!partial.empty()) figureTextColored(ImVec4(1.f, 0.3f, 1.f, 1.f), "%s", partial.c_str());
    views_figures::drawReadout(panel, ref, cmp);
    views_figures::drawLegend(panel.view, std::min(size.x, ImGui::GetFontSize() * 18));
    if (panel.view.histogram)
        views_figures::drawHistogram(panel.view,
                                          std::min(std::max(size.x, ImGui::GetFontSize() * 20), ImGui::GetFontSize() * 30));
    if (layout.grid) {
        ImGui::PopTextWrapPos();
        ImGui::EndGroup();
    }
}

}  // namespace rrf::panels
