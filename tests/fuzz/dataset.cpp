// libFuzzer target: the dataset reader (rrf::Dataset, a ".rrfd" file: 64-byte fixed header, JSON
// header, payload of float32 records), fed through a file as the programs read it (mapped).
//
// The first input byte chooses how the rest is written. Odd: as is. Even: with the fixed header's
// two checksums recomputed over the mutated JSON header and payload, as a tool that writes a wrong
// but well-formed file would; without this almost every mutation would stop at "header checksum
// mismatch" and the JSON header's fields would never be reached.
//
// The reader documents std::runtime_error naming the file as its error (core/data/dataset_file.h),
// so that is accepted beside InputError; anything else (std::out_of_range from a number parser,
// nlohmann's own exceptions, bad_alloc, ...) is a finding, and so is a record range that lies
// outside the file (every object's records are read).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <typeinfo>
#include <vector>

#include "core/data/dataset_file.h"
#include "tests/fuzz/fuzz_input.h"

namespace {

// Fixed-header layout (core/data/dataset_file.h): u64 fields at these byte offsets.
constexpr size_t kFixedHeader = 64, kJsonBytes = 16, kPayloadOffset = 24, kPayloadBytes = 32, kPayloadChecksum = 40,
                 kJsonChecksum = 56;

uint64_t u64At(const std::vector<uint8_t>& b, size_t at) {
    uint64_t v;
    std::memcpy(&v, b.data() + at, 8);
    return v;
}

void setU64(std::vector<uint8_t>& b, size_t at, uint64_t v) { std::memcpy(b.data() + at, &v, 8); }

/// Recomputes both checksums where the header's sizes leave a range to compute them over.
void fixChecksums(std::vector<uint8_t>& b) {
    if (b.size() < kFixedHeader) return;
    const uint64_t jsonBytes = u64At(b, kJsonBytes), payloadOffset = u64At(b, kPayloadOffset);
    if (jsonBytes <= b.size() - kFixedHeader) setU64(b, kJsonChecksum, rrf::checksum64(b.data() + kFixedHeader, jsonBytes));
    if (payloadOffset <= b.size())
        setU64(b, kPayloadChecksum, rrf::checksum64(b.data() + payloadOffset, b.size() - payloadOffset));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    std::vector<uint8_t> bytes(data + 1, data + size);
    if ((data[0] & 1) == 0) fixChecksums(bytes);
    const std::string path = rrf::fuzz::writeInput("data.rrfd", bytes.data(), bytes.size());
    const auto namesTheFile = [&](const std::exception& e) {
        return typeid(e) == typeid(std::runtime_error) && std::string(e.what()).rfind(path + ": ", 0) == 0;
    };
    rrf::fuzz::expectOnlyInputErrors(
        [&] {
            const rrf::Dataset d(path);
            // The mapping is not under ASan, so check each object's byte range against the payload
            // the reader accepted, then read its first and last float.
            const uint64_t payloadBytes = u64At(bytes, kPayloadBytes);
            float sum = 0;
            for (size_t i = 0; i < d.objects().size(); ++i) {
                const rrf::DatasetObject& o = d.objects()[i];
                const uint64_t recordBytes = uint64_t(d.floatsPerRecord()) * 4;
                if (o.offset > payloadBytes || o.count > (payloadBytes - o.offset) / recordBytes)
                    rrf::fuzz::finding("no exception", ("object " + std::to_string(i) + " lies outside the payload").c_str());
                const size_t n = size_t(o.count) * size_t(d.floatsPerRecord());
                const float* r = d.records(i);
                if (n) sum += r[0] + r[n - 1];
            }
            (void)sum;
        },
        namesTheFile);
    return 0;
}
