#pragma once
/// What one data-generator run did, typed: the counters stored in the dataset header's "stats"
/// section (records, dropped viewpoints, rays that made no record, records per cell), the records
/// per object, and the work that is reported but never stored (paths and rays traced).
/// `rrf generate` prints it, the workbench shows it, `rrf inspect` reads it back from a file.

#include <cstdint>
#include <string>
#include <vector>

#include "core/data/record_noise.h"

namespace rrf {

struct GeneratorStats {
    // ---- stored in the header's "stats" section (data/generator_stats_json.h) ---------------------
    uint64_t records = 0;
    uint64_t cellsDroppedInsideObject = 0;   ///< viewpoints inside a closed object
    uint64_t cellsDroppedOutsideScene = 0;   ///< viewpoints outside the scene's walls
    /// Viewpoints behind open surfaces (under the floor, behind a wall): their records would lie on
    /// faces no camera inside the scene sees (core/data/jitter_grid.h).
    uint64_t cellsDroppedBehindSurface = 0;
    /// Records whose relative noise was still above noise_target when max_spp paths were traced.
    uint64_t recordsAtSppCap = 0;
    uint64_t raysEscaped = 0;                ///< directions that left the scene
    uint64_t raysHitEmitter = 0;             ///< directions whose first hit is a light
    uint64_t recordsWithoutFiniteSample = 0; ///< hits where every path sample was NaN/Inf
    uint64_t nonFiniteSamplesDropped = 0;    ///< NaN/Inf path samples left out of a record's mean
    std::vector<uint64_t> recordsPerCell;    ///< in cell order over the shard's cells

    // ---- stored elsewhere in the header ("objects"/"count"), or not at all -------------------------
    std::vector<uint64_t> recordsPerObject;  ///< index = scene object id
    uint64_t paths = 0, rays = 0, shadowRays = 0;  ///< work done, for records/s and samples/s (not stored)
    /// Relative noise of the records' targets per object (median, 90th percentile; index = object
    /// id), computed from the run's records; not stored (`rrf inspect` recomputes it from the
    /// file's records) and not summed by += (quantiles do not add).
    std::vector<NoiseSummary> noisePerObject;

    /// Viewpoint cells of the run (the length of recordsPerCell).
    uint64_t cells() const { return recordsPerCell.size(); }
    /// Cells that were traced (not dropped inside an object, outside the scene or behind a surface).
    uint64_t keptCells() const {
        const uint64_t dropped = cellsDroppedInsideObject + cellsDroppedOutsideScene + cellsDroppedBehindSurface;
        return cells() > dropped ? cells() - dropped : 0;
    }

    /// Adds the run `other` that covers the cells after this one's (the next shard, the next worker's
    /// cells): sums the counters and the per-object records, appends `other`'s per-cell counts.
    GeneratorStats& operator+=(const GeneratorStats& other);
};

}  // namespace rrf
