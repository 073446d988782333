#include "core/pipeline/run_summary.h"

#include "core/nn/network_settings.h"
#include "core/pipeline/run_recording.h"

namespace rrf {

RunSummary summarizeRun(const Run& run) {
    RunSummary r;
    r.kind = run.kind;
    r.status = trainRunStatusText(run);
    r.stopped = isStoppedTrainRun(run);
    const RunMetrics& m = run.metrics;
    if (run.kind == "train") {
        if (const auto& t = run.settings.trainer) r.trainer = t->type == TrainerType::Adam ? "Adam" : "LM";
        if (const auto& net = run.settings.network) r.hidden = net->options.hidden;
        r.leaves = m.leaves;
        if (m.records) r.records = double(*m.records);
        r.seconds = finiteOrNone(run.timings.train);
        r.error = finiteOrNone(m.relativeRmse);
        r.noiseFloor = finiteOrNone(m.relativeRmseNoiseFloor);
        if (const auto glsl = finiteOrNone(m.glslFrameSeconds)) {
            r.frameSeconds = glsl;
            r.frameGlsl = true;
            r.frameWidth = m.glslFrameWidth.value_or(0);
            r.frameHeight = m.glslFrameHeight.value_or(0);
        } else {
            r.frameSeconds = finiteOrNone(m.frameSeconds);
            r.frameWidth = m.frameWidth.value_or(0);
            r.frameHeight = m.frameHeight.value_or(0);
        }
        r.evaluatedWidth = m.evaluatedWidth.value_or(0);
        r.evaluatedHeight = m.evaluatedHeight.value_or(0);
    } else {
        if (m.spp) r.spp = double(*m.spp);
        r.seconds = finiteOrNone(run.timings.render);
        // A render's own relative error estimate is its noise: the floor any comparison with it has.
        r.noiseFloor = finiteOrNone(m.relativeError);
    }
    return r;
}

std::string hiddenText(const std::vector<int>& hidden) {
    return hidden.empty() ? "-" : hiddenSizesText(hidden);
}

}  // namespace rrf
