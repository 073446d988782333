#pragma once
/// How the ranks of an MPI job share the jitter cells of one `rrf generate` (docs/cluster.md): each
/// rank generates one contiguous range of cells, so the ranges join into the bytes of the unsharded
/// run exactly as `--shard k/n` parts do (core/data/dataset_part.h).
///
/// Load balance by a cost model, not by cell count: a cell costs its records × spp paths. A viewpoint
/// dropped inside an object, outside the scene or behind a surface makes no record, and of a kept
/// one's directions only those that hit an object do (rays that escape or hit the light cost one ray);
/// both vary across the grid — in the Cornell box, cells next to the open front see half their
/// directions escape. The records of every cell are predicted by tracing each direction's first hit
/// (DataGenerator::cellRecordCounts: one ray a direction against spp paths of several bounces each)
/// on rank 0, which sends the costs to the others (app/cli/cli_generate.cpp), so every rank derives
/// the same ranges even where nodes' Embree results differ at edges. Not modelled: paths differ
/// in length (Russian roulette, dark and bright regions), and adaptive sampling's extra paths are not
/// known in advance: the ranges balance the fixed spp paths per record.

#include <cstdint>
#include <vector>

namespace rrf {

class DataGenerator;

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

/// Cost of each cell of `gen`'s grid in paths: its predicted records × spp
/// (DataGenerator::cellRecordCounts).
std::vector<uint64_t> cellCosts(const DataGenerator& gen);

}  // namespace rrf
