#include "core/data/dataset_header_json.h"

#include <limits>

#include "core/data/generator_stats_json.h"
#include "core/data/sampling_settings_json.h"
#include "core/scene/effects_json.h"
#include "core/util/json_reader.h"
#include "core/util/text_format.h"

namespace rrf {

namespace {

/// The header keys GeneratedData holds typed; every other key is part of the description.
constexpr const char* kTypedKeys[] = {"input_layout", "target_layout", "noise_layout", "floats_per_record",
                                      "shard",        "stats"};

std::vector<std::string> layoutNames(const JsonReader& r) {
    std::vector<std::string> out;
    const size_t n = r.requireArray();
    for (size_t i = 0; i < n; ++i) out.push_back(r.at(i).string());
    return out;
}

}  // namespace

JsonText datasetDescription(const Scene& scene, uint64_t sceneHash, const SamplingSettings& settings,
                            const Bounds3& region, const Bounds3& grid, const Effects& effects,
                            const EstimatorChoice& estimator) {
    nlohmann::json objects = nlohmann::json::array();
    for (const Object& o : scene.objects) objects.push_back({{"id", o.id}, {"name", o.name}});
    return jsonText({
        {"format", "rrf-dataset"},
        {"scene_hash", hexString(sceneHash)},
        {"settings", toJson(settings)},
        {"light_region", {{"min", {region.lo.x, region.lo.y, region.lo.z}}, {"max", {region.hi.x, region.hi.y, region.hi.z}}}},
        {"grid_bounds", {{"min", {grid.lo.x, grid.lo.y, grid.lo.z}}, {"max", {grid.hi.x, grid.hi.y, grid.hi.z}}}},
        {"effects", toJson(effects)},
        {"estimator", {{"used", estimatorName(estimator.estimator)}, {"reason", estimator.reason}}},
        {"objects", objects},
    });
}

nlohmann::json datasetHeader(const GeneratedData& data) {
    nlohmann::json h = parseJsonText(data.description);
    h["input_layout"] = data.layout.inputs;
    h["target_layout"] = data.layout.targets;
    if (data.noiseLayoutWritten) h["noise_layout"] = data.layout.noise;
    h["floats_per_record"] = data.layout.floatsPerRecord();
    const DatasetShard& s = data.shard;
    h["shard"] = {{"index", s.index}, {"count", s.count}, {"cell_begin", s.cellBegin}, {"cell_end", s.cellEnd},
                  {"cells_total", s.cellsTotal}};
    h["stats"] = toJson(data.stats);
    return h;
}

size_t readDatasetHeader(const nlohmann::json& header, const std::string& file, GeneratedData& data) {
    const JsonReader h(header, file);
    h.requireObject();
    const JsonReader shard = h.at("shard");
    constexpr int64_t kMaxInt = std::numeric_limits<int>::max();
    data.shard = {int(shard.at("index").integer(0, kMaxInt)), int(shard.at("count").integer(0, kMaxInt)),
                  int(shard.at("cell_begin").integer(0, kMaxInt)), int(shard.at("cell_end").integer(0, kMaxInt)),
                  int(shard.at("cells_total").integer(0, kMaxInt))};
    data.layout = RecordLayout();
    data.layout.inputs = layoutNames(h.at("input_layout"));
    data.layout.targets = layoutNames(h.at("target_layout"));
    data.noiseLayoutWritten = h.has("noise_layout");
    if (data.noiseLayoutWritten) data.layout.noise = layoutNames(h.at("noise_layout"));
    const int64_t fpr = h.at("floats_per_record").integer(1, kMaxInt);
    if (fpr != data.layout.floatsPerRecord())
        h.at("floats_per_record").fail("inconsistent record layout in header: floats_per_record is " + std::to_string(fpr) +
                                       ", but the layouts name " + std::to_string(data.layout.floatsPerRecord()) + " columns");
    data.stats = generatorStatsFromHeader(header, file);
    nlohmann::json description = header;
    for (const char* key : kTypedKeys) description.erase(key);
    const size_t objects = h.at("objects").requireArray();
    for (nlohmann::json& o : description.at("objects")) {
        o.erase("count");
        o.erase("offset");
    }
    data.description = jsonText(description);
    return objects;
}

}  // namespace rrf
