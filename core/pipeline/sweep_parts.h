#pragma once
/// The bytes a sweep's processes exchange when its tasks run apart (`mpirun -n N rrf sweep`,
/// core/pipeline/sweep.h, docs/cluster.md): the reference rank 0 obtains for every rank, and each rank's
/// SweepPart for rank 0 to join (joinSweepParts). Numbers keep their exact bits
/// (core/util/byte_stream.h), so a joined sweep writes the files of one process but for its times.

#include <string>

#include "core/pipeline/sweep.h"

namespace rrf {

/// The bytes of `reference` (images, variances, light, spp, seconds, counters) for another process of
/// the same build.
std::string encodeReference(const Reference& reference);
/// Reads what encodeReference wrote; `source` (e.g. "rank 0") names it in errors. Throws
/// std::runtime_error on a truncated transfer.
Reference decodeReference(const std::string& bytes, const std::string& source);

/// The bytes of `part`: its tasks and their rows (every field but SweepRow::models; doubles keep
/// their bits).
std::string encodeSweepPart(const SweepPart& part);
/// Reads what encodeSweepPart wrote; `source` names the part in errors. Throws std::runtime_error
/// on a truncated or malformed transfer.
SweepPart decodeSweepPart(const std::string& bytes, const std::string& source);

}  // namespace rrf
