#pragma once
/// What the three views display, computed from the workbench state without any GL: the selected
/// term of the ground truth and of the compared image, tone-mapped with the exposure, and the
/// false-colour error map between them; all as 8-bit RGBA ready for texture upload. Results are
/// cached and recomputed only when an input changed, so calling update() every frame is cheap.
///
/// With ViewState::flip the error view shows the HDR-FLIP map the application computed for exactly
/// these images (ViewState::flipMap; nothing until it has), in magma over [0, 1].
/// The error map is core's errorMap(compared, groundTruth, kind) (core/eval/error_metrics.h: per
/// channel, averaged over R, G, B), so a pixel of the Views error is the value `rrf evaluate` and the
/// Objects table are built from. Object pixels the ground truth's footprint mask leaves out
/// (core/predict/footprint_mask.h) are drawn hatched grey, background and emitter pixels dark: they
/// are in no statistic. The figures under the map (viewErrorStats) are `rrf evaluate`'s "ALL
/// OBJECTS" row for the term: errorStatsWithNoise over the mask's kept pixels, with the ground
/// truth's noise floor and the corrected figure.

#include <cstdint>
#include <vector>

#include "core/eval/error_metrics.h"
#include "core/nn/model_set.h"
#include "core/predict/prediction_settings.h"
#include "core/util/image.h"
#include "panels/workbench_state.h"

namespace rrf::panels {

/// The Views error map: core's errorMap of `compared` against `groundTruth`; empty when either is
/// empty or their sizes differ (nothing to compare, which the view says instead of failing).
Image viewErrorMap(const Image& groundTruth, const Image& compared, ErrorMapKind kind);

/// The error statistics of `compared` against `groundTruth` for term `t` over the ground truth's
/// footprint mask (kept pixels), with its variance as the noise (unknown without it): the figures of
/// evaluate()'s overall row. `valid` is false (and the stats empty) without a mask or a compared
/// image of the ground truth's size.
ViewErrorStats viewErrorStats(const ImageSet& groundTruth, const ImageSet& compared, Term t);

/// viewErrorStats over the kept pixels inside `region` only (the region's figures under the map);
/// `valid` is false as there, and also for an empty region or one with no kept pixel.
ViewErrorStats viewRegionStats(const ImageSet& groundTruth, const ImageSet& compared, Term t, const ViewRegion& region);

/// The log histogram of the first channel of `map` over `pixels` (every pixel when null), bins of
/// ErrorHistogram's defaults from 1e-5 to 10; non-finite values are left out.
ErrorHistogram errorHistogram(const Image& map, const std::vector<uint32_t>* pixels);

/// The kept pixels of `mask` inside `region` (ascending), the pixels region figures are over.
std::vector<uint32_t> regionPixels(const FootprintMask& mask, const ViewRegion& region);

/// Why `compared` must not be measured against `groundTruth`: "" when they may be (same stamp, or
/// one of them unstamped), else what the view waits for, e.g. "waiting for the ground truth of the
/// light at (0.10, 0.87, -0.10): the one shown is of (0.00, 0.87, -0.10)".
std::string comparisonBlocked(const ImageSet& groundTruth, const ImageSet& compared);

/// Tints `rgba` (the compared view) half-way towards a colour per (object, leaf), so the kd-tree
/// cells show; pixels with leaf −1 stay as they are. Sizes must agree (else nothing changes).
void tintByLeaf(const std::vector<int>& objectIds, const std::vector<int>& pixelLeaf, std::vector<uint8_t>& rgba);

/// Marks the pixels of objects in `without` (ImageSet::withoutNetwork: no network predicts them) in
/// `rgba` with magenta diagonal stripes (two pixels of every four), so a partial model set never
/// shows those objects as plain black or as if predicted; the other pixels keep the image. `ids`
/// is the object-id buffer (width `width`); sizes must agree (else nothing changes).
void hatchWithoutNetwork(const std::vector<int>& ids, const std::vector<int>& without, int width, std::vector<uint8_t>& rgba);

/// The objects seen in `objectIds` (the view's id buffer) that `models` cannot predict with
/// `prediction`: without an indirect (or global / joint) network, and with learned direct light also
/// without a direct one. Sorted ids; what ImageSet::withoutNetwork holds for a prediction.
std::vector<int> objectsWithoutNetwork(const std::vector<int>& objectIds, const ModelSet& models,
                                       const PredictionSettings& prediction);

/// Where the Views panel puts its three views: in a row with the figures below, or two over two
/// with the figures in the fourth cell, whichever shows the image larger in the space there is; or,
/// when both would show it under kMinViewSide (thumbnails nobody can read, in a split pane), one
/// view at a time as large as the pane allows, chosen with a selector line above it.
struct ViewsLayout {
    static constexpr float kMinViewSide = 120.f;  ///< pixels: the smaller side of a readable view
    bool grid = false;
    bool single = false;
    ImVec2 view;  ///< the size of each view (the image is fitted inside, keeping its aspect)
};
/// The layout for `avail` (the panel's free content region), ImGui's item spacing, one text line's
/// height with spacing, and the image shown (its aspect; empty: square). Single view: a line for the
/// selector, the view's title and the view, at least kMinViewSide where the width allows (the pane
/// then scrolls to the figures below).
ViewsLayout viewsLayout(ImVec2 avail, ImVec2 spacing, float line, const Image& image);

/// Whether the compared view shows the spread map: it is on, the compared image is the live
/// prediction, and the map was made for exactly that prediction.
bool spreadShown(const ViewState& view, const ImageSet& prediction);
/// spreadShown for the state's view settings and prediction.
bool spreadShown(const WorkbenchState& state);

/// One displayable image.
struct DisplayImage {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;  ///< 4 bytes per pixel, top row first, sRGB-encoded
    uint64_t revision = 0;      ///< changes whenever the pixels change
    bool empty() const { return width == 0 || height == 0; }
};

/// Colour of a pixel the statistics leave out in the error map: hatched grey (diagonal stripes two
/// pixels wide) for an object pixel the footprint mask leaves out, dark for background and emitter.
void leftOutColour(Footprint reason, int x, int y, uint8_t rgba[4]);

/// Tone-maps linear radiance to sRGB RGBA8 (value · 2^exposure, clamped). When `ids` is given and
/// `selected` ≥ 0, pixels of other objects are dimmed so the selected object stands out.
void toneMapRgba(const Image& image, float exposure, const std::vector<int>* ids, int selected,
                 std::vector<uint8_t>& rgba);

class ViewModel {
public:
    static constexpr int kReference = 0, kCompared = 1, kError = 2;

    /// Recomputes whatever the state's inputs invalidated, and publishes the figures under the error
    /// map to state.view.errorStats (the Views panel shows them without per-pixel work).
    void update(WorkbenchState& state);
    const DisplayImage& image(int view) const { return views_[view]; }
    /// The error image of the last update (empty without a compared image of the same size).
    const Image& error() const { return error_; }
    /// The figures under the error map for the last update's term and sources.
    const ViewErrorStats& stats() const { return stats_; }

private:
    struct Key {
        uint64_t gt = ~0ull, cmp = ~0ull;
        Term term = Term::Global;
        CompareSource source = CompareSource::Prediction;
        ErrorMapKind metric = ErrorMapKind::Absolute;
        float exposure = 0.f, errorMax = 0.f;
        int selected = -2;
        size_t ids = 0;            ///< the id map's size
        uint64_t idsRevision = 0;  ///< and its revision: a new map of the same size counts too
        uint64_t leaves = 0;  ///< LeavesInfo::revision when the leaf overlay is on, else 0
        bool flip = false;
        uint64_t flipRevision = 0;  ///< FlipViewMap::revision while the FLIP map is shown, else 0
        uint64_t spreadRevision = 0;  ///< SpreadViewMap::revision while the spread is shown, else 0
        ViewRegion region;
        bool operator==(const Key& o) const {
            return gt == o.gt && cmp == o.cmp && source == o.source && term == o.term && metric == o.metric && exposure == o.exposure &&
                   errorMax == o.errorMax && selected == o.selected && ids == o.ids && idsRevision == o.idsRevision && leaves == o.leaves && flip == o.flip &&
                   flipRevision == o.flipRevision && spreadRevision == o.spreadRevision && region == o.region;
        }
    };
    Key key_;
    DisplayImage views_[3];
    Image error_;
    ViewErrorStats stats_;
    ViewErrorStats regionStats_;
    ErrorHistogram histogram_;
    FlipStats regionFlip_;
    uint64_t counter_ = 0;
};

}  // namespace rrf::panels
