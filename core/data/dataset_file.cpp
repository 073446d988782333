#include "core/data/dataset_file.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/data/dataset_header_json.h"
#include "core/data/dataset_part.h"
#include "core/data/generator_stats.h"
#include "core/data/generator_stats_json.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/util/json_reader.h"
#include "core/util/rng.h"

namespace rrf {

namespace {
const unsigned char kMagic[8] = {'R', 'R', 'F', 'D', '\r', '\n', 0x1a, '\n'};
constexpr size_t kFixedHeader = 64;

struct FixedHeader {
    unsigned char magic[8];
    uint32_t version, reserved;
    uint64_t jsonBytes, payloadOffset, payloadBytes, payloadChecksum, sceneHash, jsonChecksum;
};
static_assert(sizeof(FixedHeader) == kFixedHeader, "fixed header must be 64 bytes");

size_t align64(size_t n) { return (n + 63) & ~size_t(63); }

[[noreturn]] void fail(const std::string& path, const std::string& what) {
    throw std::runtime_error(path + ": " + what);
}
}  // namespace

void Checksum64::update(const void* data, size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    total_ += bytes;
    auto word = [this](const unsigned char* w) {
        uint64_t v;
        std::memcpy(&v, w, 8);
        h_ = mix64(h_ ^ v) + 0x9E3779B97F4A7C15ULL;
    };
    while (pendingBytes_ > 0 && pendingBytes_ < 8 && bytes > 0) {
        pending_[pendingBytes_++] = *p++;
        --bytes;
        if (pendingBytes_ == 8) {
            word(pending_);
            pendingBytes_ = 0;
        }
    }
    for (; bytes >= 8; p += 8, bytes -= 8) word(p);
    // An empty range may come with a null pointer (an object without records): memcpy must not see it.
    if (bytes > 0) std::memcpy(pending_ + pendingBytes_, p, bytes);
    pendingBytes_ += bytes;
}

uint64_t Checksum64::finish() const {
    // The length enters at the start in checksum64(); here it is only known at the end, so both
    // functions fold it in at the end instead.
    uint64_t tail = 0;
    std::memcpy(&tail, pending_, pendingBytes_);
    return mix64(h_ ^ total_ ^ tail ^ (uint64_t(pendingBytes_) << 56));
}

uint64_t checksum64(const void* data, size_t bytes) {
    Checksum64 c;
    c.update(data, bytes);
    return c.finish();
}

void writeDataset(const std::string& path, nlohmann::json header, uint64_t sceneHash,
                  const std::vector<std::vector<float>>& perObject) {
    const int fpr = header.at("floats_per_record").get<int>();
    nlohmann::json& objs = header.at("objects");
    if (objs.size() != perObject.size()) throw std::logic_error("writeDataset: objects and data differ in count");
    // Records are written straight from the callers' vectors (no payload copy: datasets reach
    // hundreds of MiB); a first pass computes the checksum the fixed header needs.
    uint64_t offset = 0;
    Checksum64 sum;
    for (size_t i = 0; i < perObject.size(); ++i) {
        const auto& v = perObject[i];
        if (v.size() % size_t(fpr) != 0) throw std::logic_error("writeDataset: partial record");
        objs[i]["count"] = v.size() / size_t(fpr);
        objs[i]["offset"] = offset;
        if (!v.empty()) sum.update(v.data(), v.size() * sizeof(float));
        offset += v.size() * sizeof(float);
    }
    const std::string json = header.dump(1);
    FixedHeader fh{};
    std::memcpy(fh.magic, kMagic, 8);
    fh.version = kDatasetVersion;
    fh.jsonBytes = json.size();
    fh.payloadOffset = align64(kFixedHeader + json.size());
    fh.payloadBytes = offset;
    fh.payloadChecksum = sum.finish();
    fh.sceneHash = sceneHash;
    fh.jsonChecksum = checksum64(json.data(), json.size());
    AtomicFile f(path);
    f.write(&fh, sizeof fh);
    f.write(json);
    const std::string pad(fh.payloadOffset - kFixedHeader - json.size(), '\0');
    f.write(pad);
    for (const auto& v : perObject)
        if (!v.empty()) f.write(v.data(), v.size() * sizeof(float));
    f.commit();
}

Dataset::Dataset(const std::string& path, bool verifyPayload, uint64_t expectedSceneHash) : path_(path) {
    const int fd = ::open(path.c_str(), O_RDONLY);
    if (fd < 0) fail(path, std::string("cannot open dataset: ") + std::strerror(errno));
    struct stat st {};
    if (::fstat(fd, &st) != 0) {
        ::close(fd);
        fail(path, "cannot stat dataset");
    }
    mapSize_ = size_t(st.st_size);
    if (mapSize_ < kFixedHeader) {
        ::close(fd);
        fail(path, "not a dataset: file is " + std::to_string(mapSize_) + " bytes, shorter than the 64-byte header");
    }
    map_ = ::mmap(nullptr, mapSize_, PROT_READ, MAP_PRIVATE, fd, 0);
    ::close(fd);
    if (map_ == MAP_FAILED) {
        map_ = nullptr;
        fail(path, "cannot map dataset into memory");
    }
    try {
        const auto* base = static_cast<const unsigned char*>(map_);
        FixedHeader fh;
        std::memcpy(&fh, base, sizeof fh);
        if (std::memcmp(fh.magic, kMagic, 8) != 0) fail(path, "not an RRF dataset (wrong magic bytes)");
        if (fh.version < kOldestDatasetVersion || fh.version > kDatasetVersion)
            fail(path, "dataset format version " + std::to_string(fh.version) + " is not supported (this build reads versions " +
                           std::to_string(kOldestDatasetVersion) + " to " + std::to_string(kDatasetVersion) + ")");
        version_ = fh.version;
        if (fh.jsonBytes > mapSize_ - kFixedHeader || fh.payloadOffset < kFixedHeader + fh.jsonBytes ||
            fh.payloadOffset > mapSize_)
            fail(path, "truncated or corrupt header");
        if (fh.payloadBytes != mapSize_ - fh.payloadOffset)
            fail(path, "truncated file: payload should be " + std::to_string(fh.payloadBytes) + " bytes, found " +
                           std::to_string(mapSize_ - fh.payloadOffset));
        const char* json = reinterpret_cast<const char*>(base + kFixedHeader);
        if (checksum64(json, fh.jsonBytes) != fh.jsonChecksum) fail(path, "header checksum mismatch (file corrupted)");
        sceneHash_ = fh.sceneHash;
        payload_ = base + fh.payloadOffset;
        readHeader(std::string(json, fh.jsonBytes));
        if (expectedSceneHash != 0 && expectedSceneHash != sceneHash_)
            fail(path, "dataset was generated for a different scene (scene hash mismatch): regenerate it for this project");
        uint64_t expected = 0;
        for (DatasetObject d : objects_) {
            // Compare counts before multiplying: a crafted count must not wrap the byte size around.
            const uint64_t recordBytes = uint64_t(floatsPerRecord_) * 4;
            if (d.offset != expected || d.offset > fh.payloadBytes || d.count > (fh.payloadBytes - d.offset) / recordBytes)
                fail(path, "object '" + d.name + "' lies outside the payload (corrupt header)");
            const uint64_t bytes = d.count * recordBytes;
            if (bytes > fh.payloadBytes - d.offset)
                fail(path, "object '" + d.name + "' lies outside the payload (corrupt header)");
            expected += bytes;
        }
        if (expected != fh.payloadBytes) fail(path, "payload size does not match the per-object counts");
        if (verifyPayload && checksum64(payload_, fh.payloadBytes) != fh.payloadChecksum)
            fail(path, "payload checksum mismatch (file corrupted)");
    } catch (...) {
        ::munmap(map_, mapSize_);
        map_ = nullptr;
        throw;
    }
}

namespace {
/// The value of a hexadecimal string of 1 to 16 digits (a scene hash); false for anything else.
bool parseHex64(const std::string& text, uint64_t& value) {
    if (text.empty() || text.size() > 16) return false;
    value = 0;
    for (char c : text) {
        const int digit = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
        if (digit < 0) return false;
        value = value << 4 | uint64_t(digit);
    }
    return true;
}

std::vector<std::string> stringList(const JsonReader& r) {
    std::vector<std::string> out(r.requireArray());
    for (size_t i = 0; i < out.size(); ++i) out[i] = r.at(i).string();
    return out;
}
}  // namespace

void Dataset::readHeader(const std::string& text) {
    try {
        header_ = parseJsonText(text, path_);
        // Every field a reader of the dataset uses is checked here, so that later readers (inspect,
        // merge, training) may access the header directly.
        const JsonReader h(header_, path_);
        h.requireObject();
        if (const auto hash = h.find("scene_hash")) {
            // The fixed header's hash is not under a checksum; the JSON's copy is, so they must agree.
            uint64_t v = 0;
            if (!parseHex64(hash->string(), v))
                hash->fail("expected a hexadecimal number of 1 to 16 digits, got \"" + hash->string() + "\"");
            if (v != sceneHash_) fail(path_, "scene hash in the fixed header disagrees with the JSON header (file corrupted)");
        }
        h.at("settings").requireObject();
        const JsonReader shard = h.at("shard");
        for (const char* key : {"index", "count", "cell_begin", "cell_end", "cells_total"})
            shard.at(key).integer(0, std::numeric_limits<int>::max());
        const std::vector<std::string> targets = stringList(h.at("target_layout"));
        inputLayout_ = stringList(h.at("input_layout"));
        if (version_ >= 2 && h.has("noise_layout")) noiseLayout_ = stringList(h.at("noise_layout"));
        const JsonReader fpr = h.at("floats_per_record");
        floatsPerRecord_ = int(fpr.integer(1, std::numeric_limits<int>::max()));
        inputCount_ = int(inputLayout_.size());
        // Every column is named, so the record size is bounded by the header's own size.
        const size_t named = inputLayout_.size() + targets.size() + noiseLayout_.size();
        if (targets.empty() || size_t(floatsPerRecord_) != named)
            fpr.fail("inconsistent record layout in header: floats_per_record is " + std::to_string(floatsPerRecord_) +
                     ", but the layouts name " + std::to_string(inputLayout_.size()) + " inputs, " +
                     std::to_string(targets.size()) + " targets and " + std::to_string(noiseLayout_.size()) +
                     " noise columns (at least one target)");
        generatorStatsFromHeader(header_, path_);  // checks "stats" (counters, records_per_cell)
        const JsonReader objects = h.at("objects");
        const size_t n = objects.requireArray();
        for (size_t i = 0; i < n; ++i) {
            const JsonReader o = objects.at(i);
            DatasetObject d;
            d.id = int(o.at("id").integer(0, std::numeric_limits<int>::max()));
            d.name = o.at("name").string();
            d.count = o.at("count").unsignedInteger();
            d.offset = o.at("offset").unsignedInteger();
            objects_.push_back(d);
        }
    } catch (const InputError& e) {
        const std::string detail = e.detail();
        throw InputError(path_, e.where(), detail.rfind("inconsistent", 0) == 0 ? detail : "malformed dataset header: " + detail);
    }
}

Dataset::~Dataset() {
    if (map_) ::munmap(map_, mapSize_);
}

uint64_t Dataset::totalRecords() const {
    uint64_t n = 0;
    for (const DatasetObject& o : objects_) n += o.count;
    return n;
}

const float* Dataset::records(size_t i) const {
    return reinterpret_cast<const float*>(payload_ + objects_.at(i).offset);
}

void mergeDatasets(const std::vector<std::string>& inputs, const std::string& output) {
    if (inputs.empty()) throw std::runtime_error("merge: no input files");
    std::vector<NamedPart> parts;
    for (const std::string& path : inputs) {
        const Dataset d(path);
        NamedPart p;
        p.name = path;
        readDatasetHeader(d.header(), path, p.data);
        p.data.sceneHash = d.sceneHash();
        for (size_t i = 0; i < d.objects().size(); ++i) {
            const float* r = d.records(i);
            p.data.perObject.emplace_back(r, r + d.objects()[i].count * size_t(d.floatsPerRecord()));
        }
        parts.push_back(std::move(p));
    }
    const GeneratedData joined = joinGeneratedParts(std::move(parts));
    writeDataset(output, datasetHeader(joined), joined.sceneHash, joined.perObject);
}

DatasetReportFields datasetReportFields(const Dataset& data) {
    const nlohmann::json& h = data.header();
    DatasetReportFields f;
    f.sceneHash = h.value("scene_hash", "?");
    f.settings = h.at("settings").dump();
    // Datasets before the bidirectional tracer name only the setting (nee or naive), which is what ran.
    if (h.contains("estimator") && h["estimator"].is_object()) {
        f.estimator = true;
        f.estimatorUsed = h["estimator"].value("used", "?");
        f.estimatorReason = h["estimator"].value("reason", "");
    }
    f.shard = h.at("shard").dump();
    for (const auto& t : h.at("target_layout")) f.targetLayout.push_back(t.get<std::string>());
    f.stats = generatorStatsFromHeader(h, data.path());
    return f;
}

}  // namespace rrf
