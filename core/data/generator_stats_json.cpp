#include "core/data/generator_stats_json.h"

namespace rrf {

nlohmann::json toJson(const GeneratorStats& s) {
    return {{"records", s.records},
            {"cells_dropped_inside_object", s.cellsDroppedInsideObject},
            {"cells_dropped_outside_scene", s.cellsDroppedOutsideScene},
            {"cells_dropped_behind_surface", s.cellsDroppedBehindSurface},
            {"records_at_spp_cap", s.recordsAtSppCap},
            {"rays_escaped", s.raysEscaped},
            {"rays_hit_emitter", s.raysHitEmitter},
            {"records_without_finite_sample", s.recordsWithoutFiniteSample},
            {"non_finite_samples_dropped", s.nonFiniteSamplesDropped},
            {"records_per_cell", s.recordsPerCell}};
}

GeneratorStats generatorStatsFromHeader(const nlohmann::json& header, const std::string& file) {
    const JsonReader h(header, file);
    const JsonReader st = h.at("stats");
    st.requireObject();
    GeneratorStats s;
    s.records = st.at("records").unsignedInteger();
    // Older files may lack the finer counters; they then read as 0, as the generator would report.
    auto counter = [&](const char* key) { return st.has(key) ? st.at(key).unsignedInteger() : uint64_t(0); };
    s.cellsDroppedInsideObject = counter("cells_dropped_inside_object");
    s.cellsDroppedOutsideScene = counter("cells_dropped_outside_scene");
    s.cellsDroppedBehindSurface = counter("cells_dropped_behind_surface");
    s.recordsAtSppCap = counter("records_at_spp_cap");
    s.raysEscaped = counter("rays_escaped");
    s.raysHitEmitter = counter("rays_hit_emitter");
    s.recordsWithoutFiniteSample = counter("records_without_finite_sample");
    s.nonFiniteSamplesDropped = counter("non_finite_samples_dropped");
    if (const auto perCell = st.find("records_per_cell")) {
        const size_t n = perCell->requireArray();
        for (size_t i = 0; i < n; ++i) s.recordsPerCell.push_back(perCell->at(i).unsignedInteger());
    }
    if (const auto objects = h.find("objects")) {
        const size_t n = objects->requireArray();
        for (size_t i = 0; i < n; ++i) {
            const JsonReader o = objects->at(i);
            s.recordsPerObject.push_back(o.has("count") ? o.at("count").unsignedInteger() : uint64_t(0));
        }
    }
    return s;
}

}  // namespace rrf
