#include "core/data/cell_split.h"

#include <stdexcept>
#include <string>

#include "core/data/data_generator.h"

namespace rrf {

std::vector<CellRange> splitCellsByCost(const std::vector<uint64_t>& costs, int parts) {
    if (parts < 1) throw std::invalid_argument("splitCellsByCost: parts must be >= 1, got " + std::to_string(parts));
    const int cells = int(costs.size());
    unsigned __int128 total = 0;
    for (uint64_t c : costs) total += c;
    std::vector<CellRange> ranges(static_cast<size_t>(parts), CellRange{});
    if (total == 0) {
        for (int r = 0; r < parts; ++r)
            ranges[size_t(r)] = {int(int64_t(cells) * r / parts), int(int64_t(cells) * (r + 1) / parts)};
        return ranges;
    }
    // 128-bit sums: a prefix times `parts` cannot overflow (costs are paths, up to ~2^40 a cell).
    std::vector<int> starts(size_t(parts) + 1, cells);
    starts[0] = 0;
    unsigned __int128 prefix = 0;
    int r = 1;
    for (int c = 0; c <= cells && r < parts; ++c) {
        while (r < parts && prefix * unsigned(parts) >= total * unsigned(r)) starts[size_t(r++)] = c;
        if (c < cells) prefix += costs[size_t(c)];
    }
    for (int i = 0; i < parts; ++i) ranges[size_t(i)] = {starts[size_t(i)], starts[size_t(i) + 1]};
    return ranges;
}

std::vector<uint64_t> cellCosts(const DataGenerator& gen) {
    std::vector<uint64_t> costs = gen.cellRecordCounts();
    for (uint64_t& c : costs) c *= uint64_t(gen.settings().spp);
    return costs;
}

}  // namespace rrf
