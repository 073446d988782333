// FLIP figures in JSON (see flip_evaluation_json.h).
#include "core/eval/flip_evaluation_json.h"

#include "core/eval/error_metrics_json.h"

namespace rrf {

nlohmann::json flipStatsJson(const FlipStats& s) {
    return {{"mean", s.mean},
            {"weighted_median", s.weightedMedian},
            {"weighted_first_quartile", s.weightedFirstQuartile},
            {"weighted_third_quartile", s.weightedThirdQuartile},
            {"min", s.min},
            {"max", s.max},
            {"pixels", s.pixels},
            {"non_finite_pixels", s.nonFinite}};
}

nlohmann::json flipJson(const FlipEvaluation& f, const std::vector<std::string>& names) {
    nlohmann::json objects = nlohmann::json::array();
    for (size_t id = 0; id < f.hdrPerObject.size(); ++id)
        objects.push_back({{"id", int(id)}, {"name", id < names.size() ? names[id] : ""}, {"hdr", flipStatsJson(f.hdrPerObject[id])}});
    return {{"method",
             "FLIP (Andersson et al. 2020, 2021) of the global term over the object pixels the footprint mask keeps; hdr: "
             "HDR-FLIP over the reference's exposure range; ldr: LDR-FLIP at exposure 0; hdr_noise_floor: the mean HDR-FLIP "
             "of the reference against itself plus one draw of its own noise (null when its variance is unknown)"},
            {"pixels_per_degree", f.settings.pixelsPerDegree},
            {"exposures", {{"start", f.range.start}, {"stop", f.range.stop}, {"count", f.range.count}}},
            {"hdr", flipStatsJson(f.hdr)},
            {"hdr_noise_floor", noiseFigureJson(f.hdrNoiseFloor)},
            {"ldr", flipStatsJson(f.ldr)},
            {"seconds", f.seconds},
            {"objects", objects}};
}

}  // namespace rrf
