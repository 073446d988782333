#pragma once
/// How the ranks of an MPI job share the jitter cells of one `rrf generate` (docs/cluster.md): each
/// rank generates one contiguous range of cells, so the ranges join into the bytes of the unsharded
/// run exactly as `--shard k/n` parts do (core/data/dataset_part.h).
///
/// Load balance by a cost model, not by cell count: a viewpoint dropped inside an object, outside
/// the scene or behind a surface costs only its 14 classification probes, while a kept one traces
/// directions × spp paths — in the Cornell box a quarter of the grid lies inside the two blocks or
/// under the floor, so equal cell counts leave some ranks with a third less work than others. Every
/// rank classifies every cell (a pure function of the seed and the scene, 14 rays a cell: a few
/// milliseconds against the minutes of the paths) and derives the same ranges, so no message is
/// needed to agree on them. Adaptive sampling's extra paths are not known in advance and are not
/// modelled: the ranges balance the fixed part, spp paths per direction.

#include <cstdint>
#include <vector>

namespace rrf {

class DataGenerator;
struct Scene;

/// Cells [begin, end) of the grid.
struct CellRange {
    int begin = 0, end = 0;
    int size() const { return end - begin; }
};

/// Splits the cells 0 … costs.size() − 1 into `parts` contiguous ranges with near-equal cost: range
/// r starts at the first cell c whose preceding cells cost at least r/parts of the total
/// (Σ_{i<c} costs[i] · parts ≥ r · total, in exact integers), so each range's cost is within one
/// cell's cost of total/parts. When every cost is 0, the cells are split into equal counts as
/// `--shard r/parts` does. Throws std::invalid_argument unless parts ≥ 1.
std::vector<CellRange> splitCellsByCost(const std::vector<uint64_t>& costs, int parts);

/// Cost of each cell of `gen`'s grid over `scene` in paths: directions × spp for a kept viewpoint,
/// 0 for a dropped one (classified as the generator does, core/data/jitter_grid.h).
std::vector<uint64_t> cellCosts(const Scene& scene, const DataGenerator& gen);

}  // namespace rrf
