#pragma once
/// One render split across processes by rows (the ground truth of `mpirun -n N rrf pipeline`,
/// docs/cluster.md): part r of n renders the rows y with y mod n = r (RenderOptions::rowOffset,
/// rowStride), sends them as bytes, and one process joins the parts into the state of the whole
/// render, bit for bit: sample k of pixel i uses Rng(seed, i, k) whatever process traces it
/// (core/render/renderer.h). Interleaved rows balance the parts without a cost model: every part
/// gets rows from the whole height (sky, walls, objects alike), so no part holds only cheap rows.

#include <string>
#include <vector>

#include "core/render/renderer.h"

namespace rrf {

/// The bytes of the rows y ≡ `offset` (mod `stride`) of `state` and its counters, for another process
/// of the same build (core/util/byte_stream.h).
std::string encodeRenderRows(const RenderState& state, int offset, int stride);

/// Joins the parts of one render, part r encoded with offset r and stride parts.size() (`names[r]`
/// names it in errors), into the whole render's state: every row from its part, the sample, ray and
/// NaN counters summed, spp and passes the parts' (equal), seconds the longest part's. Throws
/// std::runtime_error when a part is truncated, has another size, stride, spp or pass count, or the
/// wrong offset.
RenderState joinRenderRows(const std::vector<std::string>& parts, const std::vector<std::string>& names);

}  // namespace rrf
