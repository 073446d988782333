#include "core/data/dataset_part.h"

#include <algorithm>
#include <stdexcept>

#include "core/util/byte_stream.h"
#include "core/util/json_reader.h"

namespace rrf {

namespace {
[[noreturn]] void failPart(const std::string& part, const std::string& what) { throw std::runtime_error(part + ": " + what); }

int partCellBegin(const NamedPart& p) { return p.data.header.at("shard").at("cell_begin").get<int>(); }

/// The header without what differs between parts of one run.
nlohmann::json comparableHeader(nlohmann::json h) {
    h.erase("shard");
    h.erase("stats");
    for (auto& o : h.at("objects")) {
        o.erase("count");
        o.erase("offset");
    }
    return h;
}
}  // namespace

std::string encodeGeneratedPart(const GeneratedData& part) {
    ByteWriter w;
    w.string(part.header.dump());
    w.u64(part.sceneHash);
    w.u64(part.stats.paths);
    w.u64(part.stats.rays);
    w.u64(part.stats.shadowRays);
    w.f64(part.seconds);
    w.u64(part.perObject.size());
    for (const std::vector<float>& records : part.perObject) w.floats(records);
    return w.take();
}

GeneratedData decodeGeneratedPart(const std::string& bytes, const std::string& source) {
    ByteReader r(bytes, source);
    GeneratedData d;
    d.header = parseJsonText(r.string(), source);
    d.sceneHash = r.u64();
    const uint64_t paths = r.u64(), rays = r.u64(), shadowRays = r.u64();
    d.seconds = r.f64();
    const uint64_t objects = r.u64();
    if (objects != d.header.at("objects").size())
        failPart(source, "the transfer holds " + std::to_string(objects) + " objects, its header " +
                         std::to_string(d.header.at("objects").size()));
    for (uint64_t i = 0; i < objects; ++i) d.perObject.push_back(r.floats());
    if (!r.atEnd()) failPart(source, "trailing bytes after the transfer");
    d.stats = GeneratorStats::fromHeader(d.header, source);
    const size_t fpr = d.header.at("floats_per_record").get<size_t>();
    d.stats.recordsPerObject.clear();
    for (const std::vector<float>& records : d.perObject) d.stats.recordsPerObject.push_back(records.size() / fpr);
    d.stats.paths = paths;
    d.stats.rays = rays;
    d.stats.shadowRays = shadowRays;
    return d;
}

GeneratedData joinGeneratedParts(std::vector<NamedPart> parts) {
    if (parts.empty()) throw std::runtime_error("merge: no parts to join");
    std::stable_sort(parts.begin(), parts.end(), [](const NamedPart& a, const NamedPart& b) { return partCellBegin(a) < partCellBegin(b); });
    const NamedPart& first = parts.front();
    const nlohmann::json reference = comparableHeader(first.data.header);
    const int cells = first.data.header.at("shard").at("cells_total").get<int>();
    GeneratedData out;
    out.header = first.data.header;
    out.sceneHash = first.data.sceneHash;
    out.perObject.resize(first.data.perObject.size());
    // Exact reservations: the joined payload is held once, each part's records freed once copied.
    for (size_t i = 0; i < out.perObject.size(); ++i) {
        size_t floats = 0;
        for (const NamedPart& p : parts) floats += i < p.data.perObject.size() ? p.data.perObject[i].size() : 0;
        out.perObject[i].reserve(floats);
    }
    int expectedBegin = 0;
    for (size_t s = 0; s < parts.size(); ++s) {
        NamedPart& p = parts[s];
        if (p.data.sceneHash != first.data.sceneHash || comparableHeader(p.data.header) != reference)
            failPart(p.name, "was generated with a different scene or different settings than " + first.name);
        const nlohmann::json& sh = p.data.header.at("shard");
        if (sh.at("cell_begin").get<int>() != expectedBegin)
            failPart(p.name, "shards do not tile the grid: expected a shard starting at cell " + std::to_string(expectedBegin));
        expectedBegin = sh.at("cell_end").get<int>();
        for (size_t i = 0; i < out.perObject.size(); ++i) {
            std::vector<float>& src = p.data.perObject[i];
            out.perObject[i].insert(out.perObject[i].end(), src.begin(), src.end());
            std::vector<float>().swap(src);
        }
        // Parts are in cell order, so appending their per-cell counts keeps the cell order.
        if (s == 0) out.stats = p.data.stats;
        else out.stats += p.data.stats;
        out.seconds = std::max(out.seconds, p.data.seconds);
    }
    if (expectedBegin != cells)
        failPart(parts.back().name, "shards do not cover the grid: cells " + std::to_string(expectedBegin) + ".." +
                                    std::to_string(cells) + " are missing");
    out.header["stats"] = out.stats.toJson();
    out.header["shard"] = {{"index", 0}, {"count", 1}, {"cell_begin", 0}, {"cell_end", cells}, {"cells_total", cells}};
    // Noise summaries are quantiles, which do not add: recomputed from the joined records (files
    // without noise columns have none to summarise).
    out.stats.noisePerObject.clear();
    if (out.header.contains("noise_layout") && !out.header.at("noise_layout").empty()) {
        const int fpr = out.header.at("floats_per_record").get<int>();
        const int inputs = int(out.header.at("input_layout").size());
        const int targets = int(out.header.at("target_layout").size());
        for (const std::vector<float>& records : out.perObject)
            out.stats.noisePerObject.push_back(
                summarizeNoise(records.data(), records.size() / size_t(fpr), fpr, inputs, inputs + targets));
    }
    return out;
}

}  // namespace rrf
