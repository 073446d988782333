// Dataset file (.rrfd) tests on small hand-made datasets: a round trip, every corruption case
// (truncation at many cut points, wrong magic or version, checksum mismatches, a dataset for another
// scene, empty and missing files) yields an error naming the file and never crashes, atomic writes
// leave no temporary file and never clobber the previous file, and the per-object summary computes
// min/mean/max exactly.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include "core/data/dataset_file.h"
#include "core/data/dataset_summary.h"
#include "core/nn/training_samples.h"
#include "tests/file_size_limit.h"

namespace test_dataset_file {

using namespace rrf;
namespace fs = std::filesystem;

namespace {

constexpr uint64_t kSceneHash = 0x1234ABCD5678EF01ULL;

/// A fresh empty directory per test, so parallel ctest runs never share files.
fs::path testDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const fs::path dir = fs::temp_directory_path() / ("rrf_dataset_file_" + std::string(info->test_suite_name()) + "_" +
                                                      info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

/// Header of a two-input, two-target layout (4 floats per record) with objects "A" and "B".
nlohmann::json smallHeader() {
    return {{"format", "rrf-dataset"},
            {"settings", {{"spp", 4}}},
            {"shard", {{"index", 0}, {"count", 1}, {"cell_begin", 0}, {"cell_end", 1}, {"cells_total", 1}}},
            {"stats", {{"records", 5}}},
            {"input_layout", {"in0", "in1"}},
            {"target_layout", {"t0", "t1"}},
            {"floats_per_record", 4},
            {"objects", {{{"id", 0}, {"name", "A"}}, {{"id", 1}, {"name", "B"}}}}};
}

/// Object A: 3 records, object B: 2 records, with values chosen so that min/mean/max are exact.
std::vector<std::vector<float>> smallPayload() {
    return {{1.f, -2.f, 0.5f, 10.f,  //
             3.f, 4.f, 0.25f, 20.f,  //
             5.f, 1.f, 0.75f, 30.f},
            {-1.f, 0.f, 2.f, 7.f,  //
             -3.f, 8.f, 4.f, 9.f}};
}

std::string writeSmall(const fs::path& dir, const std::string& name = "data.rrfd") {
    const std::string path = (dir / name).string();
    writeDataset(path, smallHeader(), kSceneHash, smallPayload());
    return path;
}

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

uint64_t u64At(const std::string& bytes, size_t offset) {
    uint64_t v;
    std::memcpy(&v, bytes.data() + offset, 8);
    return v;
}

void setU64(std::string& bytes, size_t offset, uint64_t v) { std::memcpy(&bytes[offset], &v, 8); }

// Offsets of the fixed header fields (dataset_file.h).
constexpr size_t kVersionAt = 8, kJsonBytesAt = 16, kPayloadOffsetAt = 24, kPayloadChecksumAt = 40,
                 kJsonChecksumAt = 56;

/// Opens `path` and returns the error message; fails the test if opening succeeds or throws anything
/// other than std::runtime_error. The message must name the file so a user knows which one is bad.
std::string openError(const std::string& path, bool verifyPayload = true, uint64_t expectedHash = 0) {
    try {
        const Dataset d(path, verifyPayload, expectedHash);
        ADD_FAILURE() << path << " opened without error";
    } catch (const std::runtime_error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find(path), std::string::npos) << "message does not name the file: " << msg;
        return msg;
    } catch (...) {
        ADD_FAILURE() << path << ": unexpected exception type";
    }
    return "";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

/// Files in `dir` whose name ends in ".tmp" (AtomicFile's temporary files).
int tempFiles(const fs::path& dir) {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir)) n += e.path().extension() == ".tmp";
    return n;
}

}  // namespace

TEST(DatasetFile, RoundTripKeepsHeaderCountsAndRecords) {
    const fs::path dir = testDir();
    const std::string path = writeSmall(dir);
    const Dataset d(path, true, kSceneHash);
    EXPECT_EQ(d.sceneHash(), kSceneHash);
    EXPECT_EQ(d.floatsPerRecord(), 4);
    EXPECT_EQ(d.inputCount(), 2);
    ASSERT_EQ(d.objects().size(), 2u);
    EXPECT_EQ(d.objects()[0].name, "A");
    EXPECT_EQ(d.objects()[0].count, 3u);
    EXPECT_EQ(d.objects()[1].count, 2u);
    EXPECT_EQ(d.objects()[1].offset, 3u * 4u * sizeof(float));
    EXPECT_EQ(d.totalRecords(), 5u);
    const auto payload = smallPayload();
    for (size_t i = 0; i < 2; ++i)
        EXPECT_EQ(std::memcmp(d.records(i), payload[i].data(), payload[i].size() * sizeof(float)), 0) << "object " << i;
    // The payload starts on a 64-byte boundary (aligned loads straight from the mapping).
    const std::string bytes = readBytes(path);
    EXPECT_EQ(u64At(bytes, kPayloadOffsetAt) % 64, 0u);
    EXPECT_EQ(d.header().at("objects")[1].at("count").get<uint64_t>(), 2u);
    EXPECT_EQ(tempFiles(dir), 0);
    fs::remove_all(dir);
}

TEST(DatasetFile, SameInputsGiveTheSameBytes) {
    // No timestamps or host data in the file: two writes of the same data are byte-identical
    // (the basis of the generator's determinism and shard-merge identity).
    const fs::path dir = testDir();
    EXPECT_EQ(readBytes(writeSmall(dir, "a.rrfd")), readBytes(writeSmall(dir, "b.rrfd")));
    fs::remove_all(dir);
}

TEST(DatasetFile, TruncatedFilesAreRejectedAtEveryCutPoint) {
    const fs::path dir = testDir();
    const std::string good = readBytes(writeSmall(dir));
    const size_t jsonBytes = size_t(u64At(good, kJsonBytesAt));
    const size_t payloadAt = size_t(u64At(good, kPayloadOffsetAt));
    ASSERT_GT(good.size(), payloadAt);
    // Inside the fixed header, at its end, inside the JSON, inside the padding, at the payload start,
    // inside the payload and one byte short of the end.
    const std::vector<size_t> cuts = {1, 8, 12, 63, 64, 65, 64 + jsonBytes / 2, 64 + jsonBytes - 1, 64 + jsonBytes,
                                      payloadAt - 1, payloadAt, payloadAt + 5, good.size() - 1};
    const std::string path = (dir / "cut.rrfd").string();
    for (size_t cut : cuts) {
        SCOPED_TRACE("cut at " + std::to_string(cut) + " of " + std::to_string(good.size()));
        writeBytes(path, good.substr(0, cut));
        const std::string msg = openError(path);
        EXPECT_TRUE(contains(msg, "truncated") || contains(msg, "shorter than") || contains(msg, "corrupt")) << msg;
    }
    // A file with extra bytes appended is not the file that was written either.
    writeBytes(path, good + std::string(16, '\0'));
    EXPECT_TRUE(contains(openError(path), "payload")) << "appended bytes";
    fs::remove_all(dir);
}

TEST(DatasetFile, EmptyAndMissingFilesAreRejected) {
    const fs::path dir = testDir();
    const std::string empty = (dir / "empty.rrfd").string();
    writeBytes(empty, "");
    EXPECT_TRUE(contains(openError(empty), "0 bytes"));
    const std::string missing = (dir / "missing.rrfd").string();
    EXPECT_TRUE(contains(openError(missing), "cannot open"));
    // A directory is not a dataset either.
    EXPECT_FALSE(openError(dir.string()).empty());
    fs::remove_all(dir);
}

TEST(DatasetFile, WrongMagicIsRejected) {
    const fs::path dir = testDir();
    const std::string path = writeSmall(dir);
    std::string bytes = readBytes(path);
    std::string wrong = bytes;
    wrong[0] = 'X';
    writeBytes(path, wrong);
    EXPECT_TRUE(contains(openError(path), "magic"));
    // A text-mode transfer turns the magic's CR-LF into LF: caught by the magic, not by a checksum.
    std::string text = bytes;
    text.erase(4, 1);
    writeBytes(path, text);
    EXPECT_TRUE(contains(openError(path), "magic"));
    // Some other binary file of plausible size.
    writeBytes(path, std::string(bytes.size(), '\x7f'));
    EXPECT_TRUE(contains(openError(path), "magic"));
    fs::remove_all(dir);
}

TEST(DatasetFile, WrongVersionIsRejected) {
    const fs::path dir = testDir();
    const std::string path = writeSmall(dir);
    std::string bytes = readBytes(path);
    const uint32_t future = kDatasetVersion + 1;
    std::memcpy(&bytes[kVersionAt], &future, 4);
    writeBytes(path, bytes);
    const std::string msg = openError(path);
    EXPECT_TRUE(contains(msg, "version " + std::to_string(future))) << msg;
    fs::remove_all(dir);
}

TEST(DatasetFile, PayloadChecksumMismatchIsRejected) {
    const fs::path dir = testDir();
    const std::string path = writeSmall(dir);
    const std::string good = readBytes(path);
    const size_t payloadAt = size_t(u64At(good, kPayloadOffsetAt));
    // One flipped bit at the start, middle and end of the payload.
    for (size_t at : {payloadAt, payloadAt + (good.size() - payloadAt) / 2, good.size() - 1}) {
        SCOPED_TRACE("flipped byte " + std::to_string(at));
        std::string bad = good;
        bad[at] = char(bad[at] ^ 0x01);
        writeBytes(path, bad);
        EXPECT_TRUE(contains(openError(path), "payload checksum mismatch"));
        // verifyPayload = false skips the full read by design (documented): the header still opens.
        EXPECT_NO_THROW(Dataset(path, false));
    }
    // A corrupted stored checksum is a mismatch too.
    std::string bad = good;
    setU64(bad, kPayloadChecksumAt, u64At(good, kPayloadChecksumAt) ^ 1);
    writeBytes(path, bad);
    EXPECT_TRUE(contains(openError(path), "payload checksum mismatch"));
    fs::remove_all(dir);
}

TEST(DatasetFile, HeaderChecksumMismatchIsRejected) {
    const fs::path dir = testDir();
    const std::string path = writeSmall(dir);
    const std::string good = readBytes(path);
    const size_t jsonBytes = size_t(u64At(good, kJsonBytesAt));
    // A flipped byte inside the JSON (still valid JSON or not, the checksum must catch it first).
    for (size_t at : {size_t(64), size_t(64 + jsonBytes / 2), size_t(64 + jsonBytes - 1)}) {
        SCOPED_TRACE("flipped byte " + std::to_string(at));
        std::string bad = good;
        bad[at] = char(bad[at] ^ 0x04);
        writeBytes(path, bad);
        EXPECT_TRUE(contains(openError(path), "header checksum mismatch"));
    }
    std::string bad = good;
    setU64(bad, kJsonChecksumAt, u64At(good, kJsonChecksumAt) + 1);
    writeBytes(path, bad);
    EXPECT_TRUE(contains(openError(path), "header checksum mismatch"));
    fs::remove_all(dir);
}

TEST(DatasetFile, DatasetForAnotherSceneIsRejected) {
    const fs::path dir = testDir();
    const std::string path = writeSmall(dir);
    const std::string msg = openError(path, true, kSceneHash ^ 0x10);
    EXPECT_TRUE(contains(msg, "different scene")) << msg;
    EXPECT_NO_THROW(Dataset(path, true, kSceneHash));
    EXPECT_NO_THROW(Dataset(path, true, 0));  // 0 = do not check
    fs::remove_all(dir);
}

namespace {

/// Writes `path` by hand with a valid fixed header and valid checksums around `header` and a zero
/// payload of `payloadBytes`: simulates a writer bug (not random corruption, which the checksums
/// catch) so that the reader's own count/offset checks are exercised.
void writeHandBuilt(const std::string& path, const nlohmann::json& header, size_t payloadBytes) {
    const std::string json = header.dump(1);
    std::string bytes(64, '\0');
    const unsigned char magic[8] = {'R', 'R', 'F', 'D', '\r', '\n', 0x1a, '\n'};
    std::memcpy(&bytes[0], magic, 8);
    std::memcpy(&bytes[kVersionAt], &kDatasetVersion, 4);
    const size_t payloadAt = (64 + json.size() + 63) & ~size_t(63);
    const std::string payload(payloadBytes, '\0');
    setU64(bytes, kJsonBytesAt, json.size());
    setU64(bytes, kPayloadOffsetAt, payloadAt);
    setU64(bytes, 32, payloadBytes);
    setU64(bytes, kPayloadChecksumAt, checksum64(payload.data(), payload.size()));
    setU64(bytes, 48, kSceneHash);
    setU64(bytes, kJsonChecksumAt, checksum64(json.data(), json.size()));
    writeBytes(path, bytes + json + std::string(payloadAt - 64 - json.size(), '\0') + payload);
}

/// smallHeader() with explicit counts and offsets (object A 3 records at 0, B 2 records at 48).
nlohmann::json countedHeader() {
    nlohmann::json h = smallHeader();
    h["objects"][0]["count"] = 3;
    h["objects"][0]["offset"] = 0;
    h["objects"][1]["count"] = 2;
    h["objects"][1]["offset"] = 48;
    return h;
}

}  // namespace

TEST(DatasetFile, InconsistentCountsBehindAValidChecksumAreRejected) {
    const fs::path dir = testDir();
    const std::string path = (dir / "counts.rrfd").string();
    nlohmann::json h = countedHeader();
    writeHandBuilt(path, h, 80);
    ASSERT_NO_THROW(Dataset(path, true)) << "the hand-built file itself must be valid";

    // Object B claims one record more than the payload holds.
    h["objects"][1]["count"] = 3;
    writeHandBuilt(path, h, 80);
    EXPECT_TRUE(contains(openError(path), "outside the payload"));
    // Objects that overlap.
    h["objects"][1]["count"] = 2;
    h["objects"][1]["offset"] = 32;
    writeHandBuilt(path, h, 80);
    EXPECT_TRUE(contains(openError(path), "outside the payload"));
    // Counts that do not add up to the payload size.
    h["objects"][1]["offset"] = 48;
    h["objects"][1]["count"] = 1;
    writeHandBuilt(path, h, 80);
    EXPECT_TRUE(contains(openError(path), "does not match"));
    // A header that is valid JSON but lacks a required field.
    nlohmann::json noLayout = countedHeader();
    noLayout.erase("input_layout");
    writeHandBuilt(path, noLayout, 80);
    EXPECT_TRUE(contains(openError(path), "malformed dataset header"));
    // floats_per_record not larger than the inputs (no targets).
    nlohmann::json noTargets = countedHeader();
    noTargets["floats_per_record"] = 2;
    writeHandBuilt(path, noTargets, 80);
    EXPECT_TRUE(contains(openError(path), "inconsistent record layout"));
    fs::remove_all(dir);
}

TEST(DatasetFile, RecordCountThatOverflowsTheByteSizeIsRejected) {
    // count × floats_per_record × 4 computed in uint64 wraps around for count = 2^62 (× 16 = 2^66 ≡ 0):
    // object A then seems to occupy 0 bytes, B covers the whole payload, and every check passes —
    // a reader of object A (summarizeDataset) would walk 2^62 records past the end of the mapping.
    const fs::path dir = testDir();
    const std::string path = (dir / "overflow.rrfd").string();
    nlohmann::json h = countedHeader();
    h["objects"][0]["count"] = uint64_t(1) << 62;
    h["objects"][1]["offset"] = 0;
    h["objects"][1]["count"] = 5;
    writeHandBuilt(path, h, 80);
    EXPECT_TRUE(contains(openError(path), "outside the payload"));
    fs::remove_all(dir);
}

TEST(DatasetFile, FailedWriteLeavesNoTemporaryFileAndKeepsThePreviousFile) {
    const fs::path dir = testDir();
    const std::string path = writeSmall(dir);
    const std::string before = readBytes(path);

    // A record that is cut short is refused before anything touches the disk.
    std::vector<std::vector<float>> partial = smallPayload();
    partial[1].pop_back();
    EXPECT_THROW(writeDataset(path, smallHeader(), kSceneHash, partial), std::logic_error);
    EXPECT_EQ(tempFiles(dir), 0);
    EXPECT_EQ(readBytes(path), before);

    // A write that fails midway (file size limit smaller than the dataset: the kernel refuses the
    // write with EFBIG, as a full disk would): the exception propagates, the temporary file is
    // removed and the previous dataset is untouched.
    std::vector<std::vector<float>> big(2);
    big[0].assign(4 * 4096, 1.f);  // 64 KiB of payload
    bool threw = false;
    {
        const rrf::test::FileSizeLimit limit(8192);
        ASSERT_TRUE(limit.active());
        try {
            writeDataset(path, smallHeader(), kSceneHash, big);
        } catch (const std::runtime_error& e) {
            threw = true;
            EXPECT_TRUE(contains(e.what(), path + ": write failed: File too large; the previous file is kept")) << e.what();
            EXPECT_FALSE(contains(e.what(), ".tmp")) << "names the temporary file: " << e.what();
        }
    }
    EXPECT_TRUE(threw);
    EXPECT_EQ(tempFiles(dir), 0);
    EXPECT_EQ(readBytes(path), before);
    EXPECT_NO_THROW(Dataset(path, true, kSceneHash));
    fs::remove_all(dir);
}

TEST(DatasetFile, ChecksumDetectsSingleBitFlipsAndLength) {
    std::vector<unsigned char> bytes(37);
    for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(i * 7 + 3);
    const uint64_t ref = checksum64(bytes.data(), bytes.size());
    EXPECT_EQ(ref, checksum64(bytes.data(), bytes.size()));
    // Every single-bit flip, in the 8-byte words and in the 5-byte tail, changes the checksum.
    for (size_t i = 0; i < bytes.size(); ++i)
        for (int b = 0; b < 8; ++b) {
            bytes[i] = static_cast<unsigned char>(bytes[i] ^ (1u << b));
            EXPECT_NE(checksum64(bytes.data(), bytes.size()), ref) << "byte " << i << " bit " << b;
            bytes[i] = static_cast<unsigned char>(bytes[i] ^ (1u << b));
        }
    // Appending a zero byte changes it too (the length is mixed in).
    std::vector<unsigned char> longer = bytes;
    longer.push_back(0);
    EXPECT_NE(checksum64(longer.data(), longer.size()), ref);
    EXPECT_NE(checksum64(nullptr, 0), checksum64(longer.data(), 1));
}

TEST(DatasetSummary, MinMeanMaxOfAHandMadeDataset) {
    const fs::path dir = testDir();
    const Dataset d(writeSmall(dir));
    const std::vector<ObjectSummary> s = summarizeDataset(d);
    ASSERT_EQ(s.size(), 2u);
    EXPECT_EQ(s[0].name, "A");
    EXPECT_EQ(s[0].count, 3u);
    ASSERT_EQ(s[0].columns.size(), 4u);
    // Object A's columns: {1,3,5}, {-2,4,1}, {0.5,0.25,0.75}, {10,20,30}; every value and every mean
    // is exact in binary floating point except 1/3-type means, compared to 1e-12.
    const float mins[4] = {1.f, -2.f, 0.25f, 10.f}, maxs[4] = {5.f, 4.f, 0.75f, 30.f};
    const double means[4] = {3.0, 1.0, 0.5, 20.0};
    for (int c = 0; c < 4; ++c) {
        EXPECT_EQ(s[0].columns[size_t(c)].min, mins[c]) << "column " << c;
        EXPECT_EQ(s[0].columns[size_t(c)].max, maxs[c]) << "column " << c;
        EXPECT_NEAR(s[0].columns[size_t(c)].mean, means[c], 1e-12) << "column " << c;
    }
    // Object B: {-1,-3}, {0,8}, {2,4}, {7,9}.
    EXPECT_EQ(s[1].count, 2u);
    const float minsB[4] = {-3.f, 0.f, 2.f, 7.f}, maxsB[4] = {-1.f, 8.f, 4.f, 9.f};
    const double meansB[4] = {-2.0, 4.0, 3.0, 8.0};
    for (int c = 0; c < 4; ++c) {
        EXPECT_EQ(s[1].columns[size_t(c)].min, minsB[c]) << "column " << c;
        EXPECT_EQ(s[1].columns[size_t(c)].max, maxsB[c]) << "column " << c;
        EXPECT_NEAR(s[1].columns[size_t(c)].mean, meansB[c], 1e-12) << "column " << c;
    }
    const std::string report = formatDatasetReport(d, s);
    for (const char* part : {"records: 5", "object 0 'A': 3 records", "object 1 'B': 2 records", "in1", "t0"})
        EXPECT_TRUE(contains(report, part)) << "missing '" << part << "' in\n" << report;
    fs::remove_all(dir);
}

TEST(DatasetSummary, ObjectWithoutRecordsHasNoStatistics) {
    const fs::path dir = testDir();
    const std::string path = (dir / "sparse.rrfd").string();
    std::vector<std::vector<float>> payload = smallPayload();
    payload[0].clear();
    writeDataset(path, smallHeader(), kSceneHash, payload);
    const Dataset d(path);
    const std::vector<ObjectSummary> s = summarizeDataset(d);
    ASSERT_EQ(s.size(), 2u);
    EXPECT_EQ(s[0].count, 0u);
    for (const ColumnStats& c : s[0].columns) {
        EXPECT_EQ(c.min, 0.f);
        EXPECT_EQ(c.max, 0.f);
        EXPECT_EQ(c.mean, 0.0);
    }
    EXPECT_EQ(s[1].columns[3].max, 9.f);
    EXPECT_TRUE(contains(formatDatasetReport(d, s), "object 0 'A': 0 records"));
    fs::remove_all(dir);
}

TEST(DatasetFile, TrainingRefusesALayoutWithoutSixTargets) {
    // The reader is generic (any target count); the trainer's bridge needs direct and indirect RGB.
    const fs::path dir = testDir();
    const std::string path = writeSmall(dir);  // 2 inputs, 2 targets
    const Dataset d(path);
    try {
        samplesFromDataset(d);
        ADD_FAILURE() << "a 2-target dataset was accepted for training";
    } catch (const std::runtime_error& e) {
        EXPECT_TRUE(contains(e.what(), path)) << e.what();
        EXPECT_TRUE(contains(e.what(), "6 targets")) << e.what();
    }
    fs::remove_all(dir);
}

}  // namespace test_dataset_file
