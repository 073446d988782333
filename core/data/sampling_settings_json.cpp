#include "core/data/sampling_settings_json.h"

namespace rrf {

SamplingSettings samplingSettingsFromJson(const JsonReader& r, const SamplingSettings& base) {
    r.checkKeys(SamplingSettings::keys());
    SamplingSettings s = base;
    if (const auto grid = r.find("grid")) {
        if (!grid->isArray() || grid->value().size() != 3)
            grid->fail("expected an array of 3 integers [nx, ny, nz], got " + JsonReader::describe(grid->value()));
        int* dims[] = {&s.nx, &s.ny, &s.nz};
        for (size_t i = 0; i < 3; ++i) *dims[i] = int(grid->at(i).integer(1, kMaxGridCells));
    }
    s.directions = int(r.integerOr("directions", s.directions, 1, kMaxDirections));
    s.spp = int(r.integerOr("spp", s.spp, 1, kMaxSamplesPerRecord));
    s.maxSpp = int(r.integerOr("max_spp", s.maxSpp, 1, kMaxSamplesPerRecord));
    s.noiseTarget = r.numberOr("noise_target", s.noiseTarget, 0.0, 1e6, true);
    s.maxDepth = int(r.integerOr("max_depth", s.maxDepth, 1, kMaxSamplingDepth));
    s.seed = r.unsignedOr("seed", s.seed);
    s.fixedLight = r.choiceOr("light", s.fixedLight ? "fixed" : "region", {"region", "fixed"}) == "fixed";
    s.estimator = *parseEstimator(r.choiceOr("estimator", estimatorName(s.estimator), {"nee", "naive", "bdpt", "auto"}));
    return s;
}

nlohmann::json toJson(const SamplingSettings& s) {
    return {{"grid", {s.nx, s.ny, s.nz}},
            {"directions", s.directions},
            {"spp", s.spp},
            {"max_spp", s.maxSpp},
            {"noise_target", s.noiseTarget},
            {"seed", s.seed},
            {"light", s.fixedLight ? "fixed" : "region"},
            {"estimator", estimatorName(s.estimator)},
            {"max_depth", s.maxDepth}};
}

}  // namespace rrf
