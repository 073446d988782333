#include "core/pipeline/run_summary.h"

#include "core/nn/network_settings.h"
#include "core/pipeline/run_recording.h"

namespace rrf {

namespace {
/// settings[section][key] when it is a string, else "".
std::string settingText(const Run& run, const char* section, const char* key) {
    const auto s = run.settings.find(section);
    if (s == run.settings.end() || !s->is_object()) return {};
    const auto v = s->find(key);
    return v != s->end() && v->is_string() ? v->get<std::string>() : std::string();
}
}  // namespace

RunSummary summarizeRun(const Run& run) {
    RunSummary r;
    r.kind = run.kind;
    r.status = trainRunStatusText(run);
    r.stopped = isStoppedTrainRun(run);
    if (run.kind == "train") {
        const std::string type = settingText(run, "trainer", "type");
        r.trainer = type == "adam" ? "Adam" : type == "levenberg_marquardt" ? "LM" : type;
        const auto net = run.settings.find("network");
        if (net != run.settings.end() && net->is_object()) {
            const auto h = net->find("hidden");
            if (h != net->end() && h->is_array())
                for (const auto& v : *h)
                    if (v.is_number_integer()) r.hidden.push_back(v.get<int>());
        }
        if (const auto leaves = run.metric("leaves")) r.leaves = int(*leaves);
        r.records = run.metric("records");
        r.seconds = run.timing("train");
        r.error = run.metric("relative_rmse");
        r.noiseFloor = run.metric("relative_rmse_noise_floor");
        if (const auto glsl = run.metric("glsl_frame_seconds")) {
            r.frameSeconds = glsl;
            r.frameGlsl = true;
        } else {
            r.frameSeconds = run.metric("frame_seconds");
        }
        const std::string timed = r.frameGlsl ? "glsl_frame_seconds" : "frame_seconds";
        r.frameWidth = int(run.metric(frameSizeKey(timed, "width")).value_or(0));
        r.frameHeight = int(run.metric(frameSizeKey(timed, "height")).value_or(0));
        r.evaluatedWidth = int(run.metric("evaluated_width").value_or(0));
        r.evaluatedHeight = int(run.metric("evaluated_height").value_or(0));
    } else {
        r.spp = run.metric("spp");
        r.seconds = run.timing("render");
        // A render's own relative error estimate is its noise: the floor any comparison with it has.
        r.noiseFloor = run.metric("relative_error");
    }
    return r;
}

std::string hiddenText(const std::vector<int>& hidden) {
    return hidden.empty() ? "-" : hiddenSizesText(hidden);
}

}  // namespace rrf
