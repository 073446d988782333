// PredictionController: the Views' FLIP map. HDR-FLIP filters the whole image at several exposures, far more
// work than a per-pixel metric, so it runs on a worker: one job at a time, started for the images on
// screen (ground truth and compared revisions, term) whenever they differ from the map on hand, its
// result shown only while those images are still the ones on screen (FlipViewMap::matches).
#include <memory>

#include "app/gui/prediction_controller.h"
#include "core/eval/flip.h"
#include "panels/view_model.h"

namespace rrf {

void PredictionController::updateFlipMap() {
    panels::FlipViewMap& shown = state_.view.flipMap;
    flipJob_.poll([&](panels::FlipViewMap& m) {
        m.revision = ++flipMaps_;
        shown = std::move(m);
    });
    if (!state_.view.flip || flipJob_.running()) return;
    const panels::ImageSet& gt = state_.reference();
    const panels::ImageSet& cmp = state_.compared();
    const Term term = state_.view.term;
    if (shown.matches(gt.revision, cmp.revision, term)) return;
    const std::tuple<uint64_t, uint64_t, Term> want{gt.revision, cmp.revision, term};
    if (flipFor_ == want) return;  // started for these images already (a job that failed is not retried)
    const Image& ref = gt.term(term);
    const Image& test = cmp.term(term);
    // Never a map against the ground truth of another light, scene or size (the view says why).
    if (ref.empty() || test.width != ref.width || test.height != ref.height || !panels::comparisonBlocked(gt, cmp).empty()) return;
    // Copies of the two images (a memcpy each, on image changes only) and the shared mask.
    auto images = std::make_shared<const std::pair<Image, Image>>(ref, test);
    std::shared_ptr<const FootprintMask> mask = gt.footprint;
    const bool started = flipJob_.start("FLIP map", [images, mask, want](JobContext&) -> std::optional<panels::FlipViewMap> {
        panels::FlipViewMap m;
        std::tie(m.groundTruth, m.compared, m.term) = want;
        m.range = flipExposureRange(images->first);
        m.map = hdrFlip(images->first, images->second, m.range);
        const bool masked = mask && mask->width == m.map.width && mask->height == m.map.height;
        m.stats = masked ? flipStats(m.map, mask->kept) : flipStats(m.map);
        return m;
    });
    if (started) flipFor_ = want;
}

}  // namespace rrf
