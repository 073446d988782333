// A render split by interleaved rows: the rows' bytes and their join (render_rows.h).
#include "core/render/render_rows.h"

#include <algorithm>
#include <stdexcept>
#include <type_traits>

#include "core/util/byte_stream.h"

namespace rrf {

static_assert(std::is_trivially_copyable_v<PixelSums>, "rows travel as the bytes of their PixelSums");

std::string encodeRenderRows(const RenderState& state, int offset, int stride) {
    if (stride < 1 || offset < 0 || offset >= stride) throw std::invalid_argument("encodeRenderRows: offset must be in [0, stride)");
    ByteWriter out;
    for (int64_t v : {int64_t(state.width), int64_t(state.height), int64_t(offset), int64_t(stride), int64_t(state.sppDone),
                      int64_t(state.passes)})
        out.i64(v);
    for (uint64_t v : {state.samples, state.rays, state.shadowRays, state.nonFinite}) out.u64(v);
    out.f64(state.seconds);
    const size_t rowBytes = size_t(state.width) * sizeof(PixelSums);
    for (int y = offset; y < state.height; y += stride)
        out.string(std::string(reinterpret_cast<const char*>(state.pixels.data() + size_t(y) * size_t(state.width)), rowBytes));
    return out.take();
}

RenderState joinRenderRows(const std::vector<std::string>& parts, const std::vector<std::string>& names) {
    RenderState joined;
    const int64_t stride = int64_t(parts.size());
    for (size_t r = 0; r < parts.size(); ++r) {
        const std::string& source = r < names.size() ? names[r] : "part " + std::to_string(r);
        ByteReader in(parts[r], source);
        const int64_t width = in.i64(), height = in.i64(), offset = in.i64(), partStride = in.i64(), spp = in.i64(),
                      passes = in.i64();
        if (offset != int64_t(r) || partStride != stride)
            throw std::runtime_error(source + ": rows " + std::to_string(offset) + " mod " + std::to_string(partStride) +
                                     ", expected " + std::to_string(r) + " mod " + std::to_string(stride));
        if (width <= 0 || height <= 0) throw std::runtime_error(source + ": an empty render");
        if (r == 0) {
            joined.width = int(width);
            joined.height = int(height);
            joined.sppDone = int(spp);
            joined.passes = int(passes);
            joined.pixels.resize(size_t(width) * size_t(height));
        } else if (width != joined.width || height != joined.height || spp != joined.sppDone || passes != joined.passes) {
            throw std::runtime_error(source + ": a render of " + std::to_string(width) + "x" + std::to_string(height) + " at " +
                                     std::to_string(spp) + " spp in " + std::to_string(passes) + " passes, the first part's is " +
                                     std::to_string(joined.width) + "x" + std::to_string(joined.height) + " at " +
                                     std::to_string(joined.sppDone) + " spp in " + std::to_string(joined.passes) + " passes");
        }
        joined.samples += in.u64();
        joined.rays += in.u64();
        joined.shadowRays += in.u64();
        joined.nonFinite += in.u64();
        joined.seconds = std::max(joined.seconds, in.f64());
        const size_t rowBytes = size_t(width) * sizeof(PixelSums);
        for (int64_t y = offset; y < height; y += stride) {
            const std::string row = in.string();
            if (row.size() != rowBytes) throw std::runtime_error(source + ": row " + std::to_string(y) + " has the wrong size");
            std::copy(row.begin(), row.end(), reinterpret_cast<char*>(joined.pixels.data() + size_t(y) * size_t(width)));
        }
        if (!in.atEnd()) throw std::runtime_error(source + ": bytes left over after its rows");
    }
    return joined;
}

}  // namespace rrf
