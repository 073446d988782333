#include "core/data/dataset_part.h"

#include <algorithm>
#include <stdexcept>

namespace rrf {

namespace {
[[noreturn]] void failPart(const std::string& part, const std::string& what) { throw std::runtime_error(part + ": " + what); }

int partCellBegin(const NamedPart& p) { return p.data.shard.cellBegin; }

/// The parts of one run share every header field but the shard, the statistics and the objects'
/// counts (which the description leaves out).
bool sameRun(const GeneratedData& a, const GeneratedData& b) {
    return a.description == b.description && a.layout.inputs == b.layout.inputs && a.layout.targets == b.layout.targets &&
           a.layout.noise == b.layout.noise && a.noiseLayoutWritten == b.noiseLayoutWritten;
}
}  // namespace

GeneratedData joinGeneratedParts(std::vector<NamedPart> parts) {
    if (parts.empty()) throw std::runtime_error("merge: no parts to join");
    std::stable_sort(parts.begin(), parts.end(), [](const NamedPart& a, const NamedPart& b) { return partCellBegin(a) < partCellBegin(b); });
    const NamedPart& first = parts.front();
    const int cells = first.data.shard.cellsTotal;
    GeneratedData out;
    out.description = first.data.description;
    out.layout = first.data.layout;
    out.noiseLayoutWritten = first.data.noiseLayoutWritten;
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
        if (p.data.sceneHash != first.data.sceneHash || !sameRun(p.data, first.data))
            failPart(p.name, "was generated with a different scene or different settings than " + first.name);
        if (p.data.shard.cellBegin != expectedBegin)
            failPart(p.name, "shards do not tile the grid: expected a shard starting at cell " + std::to_string(expectedBegin));
        expectedBegin = p.data.shard.cellEnd;
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
    out.shard = {0, 1, 0, cells, cells};
    // Noise summaries are quantiles, which do not add: recomputed from the joined records (files
    // without noise columns have none to summarise).
    out.stats.noisePerObject.clear();
    if (out.noiseLayoutWritten && !out.layout.noise.empty()) {
        const int fpr = out.layout.floatsPerRecord();
        const int inputs = out.layout.inputCount();
        const int targets = out.layout.targetCount();
        for (const std::vector<float>& records : out.perObject)
            out.stats.noisePerObject.push_back(
                summarizeNoise(records.data(), records.size() / size_t(fpr), fpr, inputs, inputs + targets));
    }
    return out;
}

}  // namespace rrf
