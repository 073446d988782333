#pragma once
/// Per-object statistics of a dataset (min / mean / max of every input and target column), so a user
/// sees coverage at a glance: which objects got few records, whether light positions span the
/// region, whether targets are in a sane range.

#include <string>
#include <vector>

#include "core/data/dataset_file.h"
#include "core/data/record_noise.h"

namespace rrf {

struct ColumnStats {
    float min = 0.f, max = 0.f;
    double mean = 0.0;
};

struct ObjectSummary {
    int id = 0;
    std::string name;
    uint64_t count = 0;
    std::vector<ColumnStats> columns;  ///< one per input, then per target (then per noise column)
    NoiseSummary noise;                ///< relative noise of the targets; known = 0 when not stored
};

std::vector<ObjectSummary> summarizeDataset(const Dataset& data);

/// Multi-line human-readable report: header fields, counts, the generator's drops, the targets'
/// relative noise per object (median, 90th percentile, or "unknown" for files without noise), then a
/// min/mean/max table per object.
std::string formatDatasetReport(const Dataset& data, const std::vector<ObjectSummary>& summary);

}  // namespace rrf
