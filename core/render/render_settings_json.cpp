#include "core/render/render_settings_json.h"

namespace rrf {

RenderSettings parseRenderSettings(const JsonReader& r) {
    r.checkKeys({"spp", "width", "height", "mode", "seed", "max_depth", "exposure"});
    RenderSettings s;
    s.spp = int(r.integerOr("spp", s.spp, 1, 1 << 30));
    s.width = int(r.integerOr("width", s.width, 0, kMaxImageSide));
    s.height = int(r.integerOr("height", s.height, 0, kMaxImageSide));
    if (auto mode = r.find("mode")) {
        const std::string m = mode->string();
        const std::optional<Estimator> e = parseEstimator(m);
        if (!e) mode->fail("unknown render mode '" + m + "' (known: " + estimatorNames() + ")");
        s.estimator = *e;
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
            {"mode", estimatorName(s.estimator)},
            {"seed", s.seed},
            {"max_depth", s.maxDepth},
            {"exposure", s.exposure}};
}

}  // namespace rrf
