#include "core/render/render_settings.h"

#include "core/util/json_reader.h"

namespace rrf {

RenderSettings parseRenderSettings(const JsonReader& r) {
    r.checkKeys({"spp", "width", "height", "mode", "seed", "max_depth", "exposure"});
    RenderSettings s;
    s.spp = int(r.integerOr("spp", s.spp, 1, 1 << 30));
    s.width = int(r.integerOr("width", s.width, 0, 16384));
    s.height = int(r.integerOr("height", s.height, 0, 16384));
    if (auto mode = r.find("mode")) {
        const std::string m = mode->string();
        if (m == "nee") s.estimator = Estimator::NEE;
        else if (m == "naive") s.estimator = Estimator::Naive;
        else mode->fail("unknown render mode '" + m + "' (known: nee, naive)");
    }
    if (auto seed = r.find("seed")) s.seed = seed->unsignedInteger();
    s.maxDepth = int(r.integerOr("max_depth", s.maxDepth, 1, 1 << 16));
    s.exposure = r.floatOr("exposure", s.exposure);
    return s;
}

nlohmann::json renderSettingsToJson(const RenderSettings& s) {
    return {{"spp", s.spp},
            {"width", s.width},
            {"height", s.height},
            {"mode", s.estimator == Estimator::NEE ? "nee" : "naive"},
            {"seed", s.seed},
            {"max_depth", s.maxDepth},
            {"exposure", s.exposure}};
}

}  // namespace rrf
