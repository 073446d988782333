#pragma once
/// Parts of one dataset made by different processes, joined into the dataset of the unsharded run:
/// the shards of `rrf generate --shard k/n` read back from their files (`rrf merge`,
/// mergeDatasets in core/data/dataset_file.h) and the ranks' shares of an MPI job
/// (`mpirun -n N rrf generate`, sent to rank 0 as bytes). One join for both, so both give the bytes
/// of the single-process run.

#include <string>
#include <vector>

#include "core/data/data_generator.h"

namespace rrf {

/// The bytes of `part` (header, scene hash, records per object, the counters that are reported but
/// not stored in a dataset: paths, rays, seconds) for sending to another process of the same build
/// (core/util/byte_stream.h).
std::string encodeGeneratedPart(const GeneratedData& part);

/// Reads what encodeGeneratedPart wrote; `source` (e.g. "rank 2") names the part in errors.
/// stats.noisePerObject is left empty (joinGeneratedParts recomputes it). Throws std::runtime_error
/// on a truncated transfer and InputError on a malformed header.
GeneratedData decodeGeneratedPart(const std::string& bytes, const std::string& source);

/// A part and the name errors give it (a file path, "rank 2").
struct NamedPart {
    std::string name;
    GeneratedData data;
};

/// Joins parts generated with the same scene and settings whose cell ranges ("shard" cell_begin …
/// cell_end) tile the grid, given in any order, into the data of the unsharded run: records per
/// object in cell order, statistics summed with per-cell counts in cell order, the header's "shard"
/// the whole grid, the noise summaries recomputed, `seconds` the longest part's. Writing the result
/// with writeDataset gives the bytes of the single-process run. Each part's records are freed as they
/// are copied. Throws std::runtime_error naming the offending part when the parts differ in scene or
/// settings, overlap, leave a gap or do not cover the grid.
GeneratedData joinGeneratedParts(std::vector<NamedPart> parts);

}  // namespace rrf
