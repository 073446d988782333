// The bytes of a dataset part sent between processes (core/data/dataset_part.h): its header as
// JSON text (core/data/dataset_header_json.h), then the counters and records.
#include "core/data/dataset_part.h"

#include <stdexcept>

#include "core/data/dataset_header_json.h"
#include "core/util/byte_stream.h"
#include "core/util/json_reader.h"

namespace rrf {

namespace {
[[noreturn]] void failTransfer(const std::string& part, const std::string& what) { throw std::runtime_error(part + ": " + what); }
}  // namespace

std::string encodeGeneratedPart(const GeneratedData& part) {
    ByteWriter w;
    w.string(datasetHeader(part).dump());
    w.u64(part.sceneHash);
    w.u64(part.stats.paths);
    w.u64(part.stats.rays);
    w.u64(part.stats.shadowRays);
    w.f64(part.seconds);
    w.u64(part.perObject.size());
    for (const std::vector<float>& records : part.perObject) w.floats(records);
    return w.take();
}

GeneratedData decodeGeneratedPart(const std::string& bytes, const std::string& source) {
    ByteReader r(bytes, source);
    GeneratedData d;
    const nlohmann::json header = parseJsonText(r.string(), source);
    d.sceneHash = r.u64();
    const uint64_t paths = r.u64(), rays = r.u64(), shadowRays = r.u64();
    d.seconds = r.f64();
    const uint64_t objects = r.u64();
    const size_t listed = readDatasetHeader(header, source, d);
    if (objects != listed)
        failTransfer(source, "the transfer holds " + std::to_string(objects) + " objects, its header " + std::to_string(listed));
    for (uint64_t i = 0; i < objects; ++i) d.perObject.push_back(r.floats());
    if (!r.atEnd()) failTransfer(source, "trailing bytes after the transfer");
    const size_t fpr = size_t(d.layout.floatsPerRecord());
    d.stats.recordsPerObject.clear();
    for (const std::vector<float>& records : d.perObject) d.stats.recordsPerObject.push_back(records.size() / fpr);
    d.stats.paths = paths;
    d.stats.rays = rays;
    d.stats.shadowRays = shadowRays;
    return d;
}

}  // namespace rrf
