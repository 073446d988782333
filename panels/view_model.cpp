#include "panels/view_model.h"

#include <algorithm>
#include <cmath>

namespace rrf::panels {

namespace view_model_detail {
namespace {
uint8_t encode(float linear) {
    if (!(linear > 0.f)) return 0;  // also maps NaN to black; the renderer never publishes NaN
    return uint8_t(std::lround(linearToSrgb(std::min(linear, 1.f)) * 255.f));
}

bool dimmed(const std::vector<int>* ids, int selected, size_t i) {
    return ids && selected >= 0 && i < ids->size() && (*ids)[i] != selected;
}

/// The error view's RGBA: `fc` (the map in false colour), dimmed outside the selected object, with
/// the pixels the footprint mask leaves out drawn as leftOutColour.
void falseColourRgba(const Image& error, const Image& fc, const std::vector<int>* ids, int selected,
                     const FootprintMask* mask, std::vector<uint8_t>& rgba) {
    toneMapRgba(fc, 0.f, ids, selected, rgba);
    if (!mask || mask->width != error.width || mask->height != error.height) return;
    for (int y = 0; y < error.height; ++y)
        for (int x = 0; x < error.width; ++x) {
            const size_t i = size_t(y) * size_t(error.width) + size_t(x);
            if (!mask->isKept(i)) leftOutColour(mask->pixel[i], x, y, &rgba[4 * i]);
        }
}
}  // namespace
}  // namespace view_model_detail

void leftOutColour(Footprint reason, int x, int y, uint8_t rgba[4]) {
    const bool object = reason != Footprint::Background && reason != Footprint::Emitter;
    const uint8_t v = object ? (((x + y) / 2) % 2 ? 150 : 90) : 40;
    rgba[0] = rgba[1] = rgba[2] = v;
    rgba[3] = 255;
}

std::string comparisonBlocked(const ImageSet& groundTruth, const ImageSet& compared) {
    if (!groundTruth.stamp || !compared.stamp || *groundTruth.stamp == *compared.stamp) return "";
    const ImageStamp& g = *groundTruth.stamp;
    const ImageStamp& c = *compared.stamp;
    char buf[256];
    if (g.sceneHash != c.sceneHash) return "waiting for the ground truth of the edited scene";
    if (!(g.light == c.light)) {
        std::snprintf(buf, sizeof buf, "waiting for the ground truth of the light at (%.3f, %.3f, %.3f): the one shown is of (%.3f, %.3f, %.3f)",
                      double(c.light.x), double(c.light.y), double(c.light.z), double(g.light.x), double(g.light.y),
                      double(g.light.z));
        return buf;
    }
    std::snprintf(buf, sizeof buf, "waiting for a ground truth of %dx%d: the one shown is %dx%d", c.width, c.height, g.width,
                  g.height);
    return buf;
}

ViewErrorStats viewErrorStats(const ImageSet& groundTruth, const ImageSet& compared, Term t) {
    ViewErrorStats out;
    out.waiting = comparisonBlocked(groundTruth, compared);
    if (!out.waiting.empty()) return out;
    const Image& ref = groundTruth.term(t);
    const Image& cmp = compared.term(t);
    const FootprintMask* mask = groundTruth.footprint.get();
    if (!mask || ref.empty() || cmp.width != ref.width || cmp.height != ref.height || mask->width != ref.width ||
        mask->height != ref.height)
        return out;
    out.valid = true;
    out.stats = errorStatsWithNoise(cmp, ref, groundTruth.variance(t), mask->kept);
    out.left = mask->counts;
    return out;
}

ErrorHistogram errorHistogram(const Image& map, const std::vector<uint32_t>* pixels) {
    ErrorHistogram h;
    const int bins = 6 * h.perDecade;  // 1e-5 ... 10
    h.counts.assign(size_t(bins), 0);
    auto add = [&](float v) {
        if (!std::isfinite(v)) return;
        if (v < 0.f) ++h.negative;
        const double a = std::fabs(double(v));
        if (!(a > 0.0)) {
            ++h.below;
            return;
        }
        const double b = std::floor((std::log10(a) - h.lo) * h.perDecade);
        if (b < 0) ++h.below;
        else if (b >= bins) ++h.above;
        else ++h.counts[size_t(b)];
    };
    if (pixels) {
        for (uint32_t i : *pixels)
            if (size_t(i) < map.pixelCount()) add(map.data[3 * size_t(i)]);
    } else {
        for (size_t i = 0; i < map.pixelCount(); ++i) add(map.data[3 * i]);
    }
    return h;
}

uint64_t ErrorHistogram::total() const {
    uint64_t n = below + above;
    for (uint64_t c : counts) n += c;
    return n;
}

std::vector<uint32_t> regionPixels(const FootprintMask& mask, const ViewRegion& region) {
    std::vector<uint32_t> out;
    if (region.empty() || mask.width <= 0) return out;
    for (uint32_t i : mask.kept)
        if (region.contains(int(i % uint32_t(mask.width)), int(i / uint32_t(mask.width)))) out.push_back(i);
    return out;
}

ViewErrorStats viewRegionStats(const ImageSet& groundTruth, const ImageSet& compared, Term t, const ViewRegion& region) {
    ViewErrorStats out = viewErrorStats(groundTruth, compared, t);
    if (!out.valid) return out;
    const std::vector<uint32_t> px = regionPixels(*groundTruth.footprint, region);
    if (px.empty()) {
        out.valid = false;
        out.stats = {};
        return out;
    }
    out.stats = errorStatsWithNoise(compared.term(t), groundTruth.term(t), groundTruth.variance(t), px);
    return out;
}

Image viewErrorMap(const Image& groundTruth, const Image& compared, ErrorMapKind kind) {
    if (groundTruth.empty() || groundTruth.width != compared.width || groundTruth.height != compared.height) return {};
    return errorMap(compared, groundTruth, kind);
}

void toneMapRgba(const Image& image, float exposure, const std::vector<int>* ids, int selected,
                 std::vector<uint8_t>& rgba) {
    const size_t n = image.pixelCount();
    rgba.resize(4 * n);
    const float scale = std::exp2(exposure);
    for (size_t i = 0; i < n; ++i) {
        // Dimming to a quarter keeps the context visible while the selected object stands out.
        const float k = view_model_detail::dimmed(ids, selected, i) ? 0.25f * scale : scale;
        for (int c = 0; c < 3; ++c) rgba[4 * i + size_t(c)] = view_model_detail::encode(image.data[3 * i + size_t(c)] * k);
        rgba[4 * i + 3] = 255;
    }
}

void tintByLeaf(const std::vector<int>& ids, const std::vector<int>& leaf, std::vector<uint8_t>& rgba) {
    if (leaf.size() != ids.size() || 4 * leaf.size() != rgba.size()) return;
    for (size_t i = 0; i < leaf.size(); ++i) {
        if (leaf[i] < 0 || ids[i] < 0) continue;
        // Consecutive leaves of one object take consecutive palette entries, so neighbours differ.
        static const uint8_t palette[12][3] = {{230, 25, 75},  {60, 180, 75},   {255, 225, 25}, {0, 130, 200},
                                               {245, 130, 48}, {145, 30, 180},  {70, 240, 240}, {240, 50, 230},
                                               {210, 245, 60}, {250, 190, 212}, {0, 128, 128},  {170, 110, 40}};
        const uint8_t* c = palette[size_t(ids[i] * 5 + leaf[i]) % 12];
        for (int k = 0; k < 3; ++k) rgba[4 * i + size_t(k)] = uint8_t((int(rgba[4 * i + size_t(k)]) + int(c[k])) / 2);
    }
}

std::vector<int> objectsWithoutNetwork(const std::vector<int>& objectIds, const ModelSet& models,
                                       const PredictionSettings& prediction) {
    std::vector<bool> seen;
    for (int id : objectIds) {
        if (id < 0) continue;
        if (size_t(id) >= seen.size()) seen.resize(size_t(id) + 1, false);
        seen[size_t(id)] = true;
    }
    const bool learnedDirect = prediction.direct == PredictionSettings::Direct::Network;
    std::vector<int> out;
    for (int id = 0; id < int(seen.size()); ++id) {
        if (!seen[size_t(id)]) continue;
        const ObjectNetworks* n = models.find(id);
        const bool whole = n && (n->has("global") || n->has("joint"));
        const bool predicted = whole || (n && n->has("indirect") && (!learnedDirect || n->has("direct")));
        if (!predicted) out.push_back(id);
    }
    return out;
}

void hatchWithoutNetwork(const std::vector<int>& ids, const std::vector<int>& without, int width, std::vector<uint8_t>& rgba) {
    if (without.empty() || width <= 0 || 4 * ids.size() != rgba.size()) return;
    for (size_t i = 0; i < ids.size(); ++i) {
        if (ids[i] < 0 || std::find(without.begin(), without.end(), ids[i]) == without.end()) continue;
        const int x = int(i % size_t(width)), y = int(i / size_t(width));
        if ((x + y) % 4 >= 2) continue;
        rgba[4 * i] = 255;
        rgba[4 * i + 1] = 0;
        rgba[4 * i + 2] = 255;
        rgba[4 * i + 3] = 255;
    }
}

ViewsLayout viewsLayout(ImVec2 avail, ImVec2 spacing, float line, const Image& image) {
    const float aspect = image.empty() ? 1.f : float(image.width) / float(image.height);
    // Row: three views side by side, the figures (about 6.5 lines) below them.
    const float rowW = std::max(16.f, (avail.x - 2 * spacing.x) / 3.f);
    const float rowH = std::max(16.f, avail.y - 6.5f * line - line);
    // Grid: two views over two, the figures in the fourth cell; each cell has its title line.
    const float gridW = std::max(16.f, (avail.x - spacing.x) / 2.f);
    const float gridH = std::max(16.f, (avail.y - spacing.y) / 2.f - line);
    // The image is fitted inside the view keeping its aspect: compare the image heights shown.
    auto shown = [&](float w, float h) { return std::min(h, w / aspect); };
    ViewsLayout l;
    l.grid = shown(gridW, gridH) > shown(rowW, rowH);
    const float w = l.grid ? gridW : rowW, h = l.grid ? gridH : rowH;
    l.view = ImVec2(w, shown(w, h));
    // Single: the whole width under the selector and title lines; the figures below it, where the
    // pane scrolls to them. Never under kMinViewSide while the width allows it.
    const float singleW = std::max(16.f, avail.x), singleH = std::max(16.f, avail.y - 2 * line);
    // The image's smaller side as shown: what decides whether it can be read.
    auto side = [&](float vw, float vh) { return std::min(shown(vw, vh), shown(vw, vh) * aspect); };
    const float minH = std::min(ViewsLayout::kMinViewSide / std::min(1.f, aspect), singleW / aspect);
    const float singleViewH = std::max(shown(singleW, singleH), minH);
    if (side(w, h) < ViewsLayout::kMinViewSide && side(singleW, singleViewH) > side(w, h)) {
        l.grid = false;
        l.single = true;
        l.view = ImVec2(singleW, singleViewH);
    }
    return l;
}

bool spreadShown(const ViewState& view, const ImageSet& prediction) {
    return view.spread && view.compareSource == CompareSource::Prediction && view.spreadMap.matches(prediction.revision) &&
           !view.spreadMap.map.empty();
}

bool spreadShown(const WorkbenchState& s) { return spreadShown(s.view, s.prediction); }

void ViewModel::update(WorkbenchState& s) {
    Key k;
    k.gt = s.reference().revision;
    k.cmp = s.compared().revision;
    k.source = s.view.compareSource;
    k.term = s.view.term;
    k.metric = s.view.metric;
    k.exposure = s.view.exposure;
    k.errorMax = s.view.errorMax;
    k.selected = s.view.highlight ? s.view.selectedObject : -1;
    k.ids = s.objectIds.size();
    k.idsRevision = s.idsRevision;
    k.leaves = s.view.leafOverlay ? s.leaves.revision : 0;
    k.flip = s.view.flip;
    k.flipRevision = s.view.flip ? s.view.flipMap.revision : 0;
    k.region = s.view.region;
    k.spreadRevision = spreadShown(s) ? s.view.spreadMap.revision : 0;
    if (k == key_) {
        s.view.errorStats = stats_;
        s.view.regionStats = regionStats_;
        s.view.regionFlip = regionFlip_;
        s.view.errorHistogram = histogram_;
        return;
    }
    const bool regionChanged = !(k.region == key_.region);
    const bool sourcesChanged = k.gt != key_.gt || k.cmp != key_.cmp || k.source != key_.source || k.term != key_.term;
    const bool errorChanged = sourcesChanged || k.metric != key_.metric || k.flip != key_.flip || k.flipRevision != key_.flipRevision;
    key_ = k;

    const Image& ref = s.reference().term(s.view.term);
    const Image& cmp = s.compared().term(s.view.term);
    // Highlighting needs the id buffer to match the image; a render at another size is shown undimmed.
    auto idsFor = [&](const Image& img) -> const std::vector<int>* {
        return (img.width == s.idWidth && img.height == s.idHeight && !s.objectIds.empty()) ? &s.objectIds : nullptr;
    };
    auto fill = [&](DisplayImage& d, const Image& img, bool error) {
        d.width = img.width;
        d.height = img.height;
        d.revision = ++counter_;
        if (img.empty()) d.rgba.clear();
        else if (error)
            view_model_detail::falseColourRgba(
                img, s.view.flip ? flipColour(img) : errorMapColour(img, s.view.metric, s.view.errorMax), idsFor(img), k.selected,
                s.reference().footprint.get(), d.rgba);
        else toneMapRgba(img, s.view.exposure, idsFor(img), k.selected, d.rgba);
    };
    // Never an error map against the ground truth of another light, scene or size.
    const bool blocked = !comparisonBlocked(s.reference(), s.compared()).empty();
    // FLIP is computed on a worker (panels/workbench_state.h, FlipViewMap): shown only when it was
    // made from exactly the images on screen.
    if (errorChanged)
        error_ = blocked ? Image()
                 : s.view.flip ? (s.view.flipMap.matches(k.gt, k.cmp, k.term) ? s.view.flipMap.map : Image())
                               : viewErrorMap(ref, cmp, s.view.metric);
    if (sourcesChanged) stats_ = viewErrorStats(s.reference(), s.compared(), s.view.term);
    s.view.errorStats = stats_;
    if (sourcesChanged || regionChanged) regionStats_ = viewRegionStats(s.reference(), s.compared(), s.view.term, k.region);
    s.view.regionStats = regionStats_;
    if (errorChanged) {
        // Over the pixels the figures are over (the mask's kept ones), else every pixel.
        const FootprintMask* mask = s.reference().footprint.get();
        const bool masked = mask && mask->width == error_.width && mask->height == error_.height;
        histogram_ = error_.empty() ? ErrorHistogram{} : errorHistogram(error_, masked ? &mask->kept : nullptr);
    }
    s.view.errorHistogram = histogram_;
    if (errorChanged || regionChanged) {
        regionFlip_ = {};
        const FootprintMask* mask = s.reference().footprint.get();
        if (s.view.flip && !error_.empty() && !k.region.empty() && mask && mask->width == error_.width && mask->height == error_.height)
            regionFlip_ = flipStats(error_, regionPixels(*mask, k.region));
    }
    s.view.regionFlip = regionFlip_;
    fill(views_[kReference], ref, false);
    if (k.spreadRevision) {
        // The members' relative spread on viridis over [0, p99], where the prediction would be.
        const Image& m = s.view.spreadMap.map;
        views_[kCompared].width = m.width;
        views_[kCompared].height = m.height;
        views_[kCompared].revision = ++counter_;
        toneMapRgba(falseColor(m, 0.f, std::max(s.view.spreadMap.scale, 1e-6f)), 0.f, idsFor(m), k.selected,
                    views_[kCompared].rgba);
    } else fill(views_[kCompared], cmp, false);
    if (k.leaves && cmp.width == s.leaves.width && cmp.height == s.leaves.height && idsFor(cmp))
        tintByLeaf(s.objectIds, s.leaves.pixelLeaf, views_[kCompared].rgba);
    if (idsFor(cmp)) hatchWithoutNetwork(s.objectIds, s.compared().withoutNetwork, cmp.width, views_[kCompared].rgba);
    fill(views_[kError], error_, true);
}

}  // namespace rrf::panels
