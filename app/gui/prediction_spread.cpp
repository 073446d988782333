// PredictionController: the Views' spread map (uncertainty without a reference, core/eval/uncertainty.h). The
// members' spread needs the CPU predictor (the GLSL path evaluates the merged network only), so it
// runs on a worker: from the last CPU frame when that frame is the prediction on screen, else by
// predicting the frame again on the CPU; one job at a time, shown only for the prediction it was
// made for (SpreadViewMap::matches).
#include <algorithm>
#include <memory>

#include "app/gui/cpu_frame.h"
#include "app/gui/prediction_controller.h"
#include "core/eval/error_metrics.h"
#include "core/eval/uncertainty.h"
#include "panels/view_model.h"

namespace rrf {

namespace {
/// The spread map of `p` (its relative spread, scale at the 99th percentile of the known pixels;
/// the global term's, whichever term the views show).
panels::SpreadViewMap spreadMapOf(const Prediction& p, uint64_t forPrediction) {
    panels::SpreadViewMap m;
    m.prediction = forPrediction;
    if (p.spread.empty()) {
        m.why = "these models have no ensemble members' spread (train with network.ensemble of 2 or more)";
        return m;
    }
    m.map = relativeSpreadMap(p.spread, p.image(Term::Global), p.spreadKnown);
    m.pixels = p.spreadPixels;
    m.scale = relativeSpreadScale(m.map, p.spreadKnown);
    if (!m.pixels) m.why = "no pixel of this view has a spread (gathered or single networks only)";
    return m;
}
}  // namespace

void PredictionController::updateSpreadMap() {
    panels::SpreadViewMap& shown = state_.view.spreadMap;
    spreadJob_.poll([&](panels::SpreadViewMap& m) {
        m.revision = ++spreadMaps_;
        shown = std::move(m);
    });
    if (!state_.view.spread || spreadJob_.running() || !live_.loaded()) return;
    const panels::ImageSet& pred = state_.prediction;
    if (pred.empty() || shown.matches(pred.revision) || spreadFor_ == pred.revision) return;
    const std::shared_ptr<const ModelSet> models = live_.models();
    const PredictionSettings settings = state_.project.prediction;
    const uint64_t revision = pred.revision;
    std::shared_ptr<const CpuFrame> frame = lastCpuFrame_;
    if (!(pred.stamp && frame && frame->matches(models, settings, *pred.stamp))) frame.reset();
    auto scene = std::make_shared<const Scene>(state_.project.scene);
    const Vec3 light = pred.stamp ? pred.stamp->light : state_.project.scene.lightPosition();
    const int width = pred.stamp ? pred.stamp->width : pred.term(Term::Global).width;
    const int height = pred.stamp ? pred.stamp->height : pred.term(Term::Global).height;
    const bool started = spreadJob_.start("spread map", [=](JobContext& ctx) -> std::optional<panels::SpreadViewMap> {
        if (frame) return spreadMapOf(frame->prediction, revision);
        const Predictor predictor(*scene, *models, settings);
        const Prediction p = predictor.predict(predictor.gbuffer(light, width, height));
        if (ctx.cancelled()) return std::nullopt;
        return spreadMapOf(p, revision);
    });
    if (started) spreadFor_ = revision;
}

}  // namespace rrf
