#pragma once
/// Binary training-data file (.rrfd).
///
///   bytes 0–63   fixed header: magic "RRFD\r\n\x1a\n", u32 version, u32 0, u64 JSON header size,
///                u64 payload offset, u64 payload size, u64 payload checksum, u64 scene hash,
///                u64 JSON header checksum (all little-endian)
///   then         the JSON header (generator settings, record layout, shard, per-object counts and
///                byte offsets into the payload, generation statistics)
///   then         zero padding to a 64-byte boundary, then the payload: per object, its records
///                back to back, each `floats_per_record` little-endian float32 (inputs, then targets,
///                then — version 2 — the targets' noise: the "noise_layout" columns).
///
/// Version 2 added the per-record noise columns (the variance of each target's Monte Carlo mean)
/// and the stats counters for viewpoints behind surfaces and records at the spp cap. Version 1
/// files still load: they have no "noise_layout", so their targets' noise is unknown.
///
/// The magic's CR-LF and ^Z bytes catch text-mode transfers (as PNG's do). The file contains no
/// timestamps, host names or thread counts, so the same settings give the same bytes, and merging
/// shards gives the bytes of the unsharded run. Files are written to a temporary name and renamed:
/// an interrupted run leaves no file that looks complete. Reading maps the file into memory.

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/data/generator_stats.h"

namespace rrf {

/// Version written by this build.
constexpr uint32_t kDatasetVersion = 2;
/// Oldest version this build reads.
constexpr uint32_t kOldestDatasetVersion = 1;

/// 64-bit checksum of a byte range (word-wise SplitMix-style mixing; detects corruption, not attacks).
uint64_t checksum64(const void* data, size_t bytes);

/// The same checksum computed over a byte stream fed in pieces of any size:
/// Checksum64 c; c.update(a, n); c.update(b, m); c.finish() == checksum64(a ‖ b, n + m).
class Checksum64 {
public:
    void update(const void* data, size_t bytes);
    uint64_t finish() const;

private:
    uint64_t h_ = 0x243F6A8885A308D3ULL;
    uint64_t total_ = 0;
    unsigned char pending_[8] = {};
    size_t pendingBytes_ = 0;
};

/// One object's records inside a dataset.
struct DatasetObject {
    int id = 0;
    std::string name;
    uint64_t count = 0;   ///< records
    uint64_t offset = 0;  ///< byte offset in the payload
};

/// Writes a dataset atomically. `perObject[i]` holds the records of header "objects"[i] (floats,
/// floats_per_record each); the writer fills in counts and offsets.
void writeDataset(const std::string& path, nlohmann::json header, uint64_t sceneHash,
                  const std::vector<std::vector<float>>& perObject);

/// A dataset file mapped read-only into memory. Every structural problem (short file, wrong magic or
/// version, checksum mismatch, inconsistent counts) throws std::runtime_error naming the file.
class Dataset {
public:
    /// Opens and validates `path`. `verifyPayload` recomputes the payload checksum (reads the whole
    /// file). `expectedSceneHash` ≠ 0 rejects a dataset made for a different scene.
    explicit Dataset(const std::string& path, bool verifyPayload = true, uint64_t expectedSceneHash = 0);
    ~Dataset();
    Dataset(const Dataset&) = delete;
    Dataset& operator=(const Dataset&) = delete;

    const std::string& path() const { return path_; }
    const nlohmann::json& header() const { return header_; }
    uint64_t sceneHash() const { return sceneHash_; }
    int floatsPerRecord() const { return floatsPerRecord_; }
    int inputCount() const { return inputCount_; }
    /// Names of the input columns of every record ("input_layout"), in column order; a model set
    /// trained on this dataset stores them so prediction builds its inputs the same way.
    const std::vector<std::string>& inputLayout() const { return inputLayout_; }
    /// Names of the noise columns after the targets ("noise_layout"); empty when the file stores no
    /// noise (version 1, or a file written by another tool): its targets' noise is unknown.
    const std::vector<std::string>& noiseLayout() const { return noiseLayout_; }
    /// Columns of the targets (floats per record − inputs − noise columns).
    int targetCount() const { return floatsPerRecord_ - inputCount_ - int(noiseLayout_.size()); }
    /// Format version of the file (kOldestDatasetVersion … kDatasetVersion).
    uint32_t version() const { return version_; }
    const std::vector<DatasetObject>& objects() const { return objects_; }
    uint64_t totalRecords() const;
    /// Records of objects()[i]: count × floatsPerRecord floats.
    const float* records(size_t i) const;

private:
    /// Parses the JSON header `text` and checks every field readers use (types, integer ranges, the
    /// record layout against floats_per_record, the scene hash against the fixed header's); a bad
    /// field throws InputError naming the file and its JSON pointer ("malformed dataset header: ...").
    void readHeader(const std::string& text);

    std::string path_;
    nlohmann::json header_;
    uint64_t sceneHash_ = 0;
    int floatsPerRecord_ = 0, inputCount_ = 0;
    std::vector<std::string> inputLayout_, noiseLayout_;
    std::vector<DatasetObject> objects_;
    uint32_t version_ = 0;
    void* map_ = nullptr;
    size_t mapSize_ = 0;
    const unsigned char* payload_ = nullptr;
};

/// Merges shards produced with the same scene and settings into one file identical to the unsharded
/// run. Shards may be given in any order; they must cover the grid exactly once. Throws
/// std::runtime_error naming the offending file.
void mergeDatasets(const std::vector<std::string>& inputs, const std::string& output);

/// The header fields a dataset report prints (formatDatasetReport, core/data/dataset_summary.h).
struct DatasetReportFields {
    std::string sceneHash;  ///< "scene_hash" as written, "?" when absent
    std::string settings;   ///< the "settings" object as compact JSON text
    /// The header has an "estimator" object (its "used" and "reason"): datasets before the
    /// bidirectional tracer name only the setting, which is what ran.
    bool estimator = false;
    std::string estimatorUsed, estimatorReason;
    std::string shard;                      ///< the "shard" object as compact JSON text
    std::vector<std::string> targetLayout;  ///< "target_layout"
    GeneratorStats stats;                   ///< "stats" and the objects' counts (generatorStatsFromHeader)
};

/// Reads the report's fields of `data`'s header; a malformed "stats" is an InputError naming the file.
DatasetReportFields datasetReportFields(const Dataset& data);

}  // namespace rrf
