#include "core/data/dataset_summary.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "core/data/generator_stats.h"

namespace rrf {

std::vector<ObjectSummary> summarizeDataset(const Dataset& data) {
    std::vector<ObjectSummary> out;
    const size_t fpr = size_t(data.floatsPerRecord());
    for (size_t i = 0; i < data.objects().size(); ++i) {
        const DatasetObject& o = data.objects()[i];
        ObjectSummary s;
        s.id = o.id;
        s.name = o.name;
        s.count = o.count;
        s.columns.resize(fpr);
        const float* r = data.records(i);
        for (size_t c = 0; c < fpr; ++c) {
            if (o.count == 0) continue;
            float lo = r[c], hi = r[c];
            double sum = 0;
            for (uint64_t k = 0; k < o.count; ++k) {
                const float v = r[k * fpr + c];
                lo = std::min(lo, v);
                hi = std::max(hi, v);
                sum += v;
            }
            s.columns[c] = {lo, hi, sum / double(o.count)};
        }
        if (data.noiseLayout().size() == 6 && data.targetCount() == 6)
            s.noise = summarizeNoise(r, size_t(o.count), int(fpr), data.inputCount(), data.inputCount() + 6);
        out.push_back(std::move(s));
    }
    return out;
}

std::string formatDatasetReport(const Dataset& data, const std::vector<ObjectSummary>& summary) {
    std::ostringstream os;
    const DatasetReportFields h = datasetReportFields(data);
    os << "dataset: " << data.path() << "\n";
    os << "scene hash: " << h.sceneHash << "\n";
    os << "settings: " << h.settings << "\n";
    // Datasets before the bidirectional tracer name only the setting (nee or naive), which is what ran.
    if (h.estimator) os << "estimator: " << h.estimatorUsed << " (" << h.estimatorReason << ")\n";
    os << "shard: " << h.shard << "\n";
    os << "records: " << data.totalRecords() << " (" << data.floatsPerRecord() << " floats each)\n";
    const GeneratorStats& typed = h.stats;
    char line[256];
    os << "format version: " << data.version() << "\n";
    os << "generator: " << typed.records << " records; viewpoint cells dropped: " << typed.cellsDroppedInsideObject
       << " inside an object, " << typed.cellsDroppedOutsideScene << " outside the scene, "
       << typed.cellsDroppedBehindSurface << " behind a surface (under the floor, behind a wall); rays escaped "
       << typed.raysEscaped << ", hit an emitter " << typed.raysHitEmitter << "; records without a finite sample "
       << typed.recordsWithoutFiniteSample << "; non-finite samples dropped " << typed.nonFiniteSamplesDropped << "\n";
    if (!typed.recordsPerCell.empty()) {
        const auto [lo, hi] = std::minmax_element(typed.recordsPerCell.begin(), typed.recordsPerCell.end());
        const auto zero = std::count(typed.recordsPerCell.begin(), typed.recordsPerCell.end(), uint64_t(0));
        os << "records per cell: min " << *lo << ", max " << *hi << ", cells without records " << zero << " of "
           << typed.cells() << "\n";
    }
    if (data.noiseLayout().empty()) {
        os << "target noise: unknown (the file stores no per-record variance; dataset version " << data.version()
           << ")\n";
    } else {
        os << "target noise: relative standard error per record, max over direct and indirect of "
              "sqrt(mean_c var_c / (|target_c| + 0.01)^2); records at the spp cap with noise above the target: "
           << typed.recordsAtSppCap << "\n";
        std::snprintf(line, sizeof line, "  %-24s %10s %10s %10s\n", "object", "median", "p90", "known");
        os << line;
        for (const ObjectSummary& s : summary) {
            std::snprintf(line, sizeof line, "  %-24s %10.4g %10.4g %10llu\n", s.name.c_str(), s.noise.median,
                          s.noise.p90, (unsigned long long)s.noise.known);
            os << line;
        }
    }
    std::vector<std::string> names = data.inputLayout();
    for (const std::string& t : h.targetLayout) names.push_back(t);
    for (const std::string& n : data.noiseLayout()) names.push_back(n);
    for (const ObjectSummary& s : summary) {
        os << "\nobject " << s.id << " '" << s.name << "': " << s.count << " records\n";
        if (s.count == 0) continue;
        std::snprintf(line, sizeof line, "  %-24s %12s %12s %12s\n", "column", "min", "mean", "max");
        os << line;
        for (size_t c = 0; c < s.columns.size() && c < names.size(); ++c) {
            std::snprintf(line, sizeof line, "  %-24s %12.5g %12.5g %12.5g\n", names[c].c_str(), double(s.columns[c].min),
                          s.columns[c].mean, double(s.columns[c].max));
            os << line;
        }
    }
    return os.str();
}

}  // namespace rrf
