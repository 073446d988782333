// Clean targets and only visible records: the per-record variance of the mean against the spread of
// independent seeds, adaptive sampling, no record on faces no camera inside the Cornell box sees,
// and the dataset's version 2 (noise columns) beside version 1 files (noise unknown).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <unistd.h>

#include "core/data/data_generator.h"
#include "core/data/dataset_file.h"
#include "core/data/dataset_header_json.h"
#include "core/data/dataset_summary.h"
#include "core/data/jitter_grid.h"
#include "core/data/record_noise.h"
#include "core/nn/training_samples.h"
#include "core/project/project.h"
#include "core/project/project_file.h"

namespace test_record_noise {

using namespace rrf;
namespace fs = std::filesystem;

namespace {

Project cornellBox() { return loadProjectOrScene(std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/project.json"); }

fs::path tempFile(const std::string& name) {
    return fs::temp_directory_path() / ("rrf_record_noise_" + name + "_" + std::to_string(::getpid()) + ".rrfd");
}

int objectId(const Scene& s, const std::string& name) {
    for (const Object& o : s.objects)
        if (o.name == name) return o.id;
    return -1;
}

}  // namespace

TEST(RecordNoise, VarianceOfTheMeanMatchesTheSpreadOverSeeds) {
    // A few fixed rays; each seed gives an independent 32-path mean. The stored variance of the mean
    // (averaged over seeds) must match the empirical variance of the means across K = 60 seeds:
    // their ratio has a standard deviation of about sqrt(2/59) ≈ 0.18 for Gaussian means (more for
    // path-traced heavy tails), so [0.5, 2] is a bound of about 3σ.
    const Project p = cornellBox();
    const Vec3 viewpoint(0.1f, 0.2f, 0.5f);
    const Vec3 dirs[3] = {normalize(Vec3(0.f, -1.f, -0.2f)), normalize(Vec3(-1.f, -0.1f, 0.f)),
                          normalize(Vec3(0.2f, 1.f, -0.3f))};
    const Vec3 light = p.scene.lightPosition();
    constexpr int kSeeds = 60;
    for (int d = 0; d < 3; ++d) {
        std::vector<std::array<double, 6>> means;
        double meanVar[6] = {};
        for (int seed = 0; seed < kSeeds; ++seed) {
            SamplingSettings s;
            s.spp = s.maxSpp = 32;
            s.seed = uint64_t(1000 + seed);
            const DataGenerator gen(p.scene, s);
            std::vector<float> rec(size_t(gen.layout().floatsPerRecord()));
            int object = -1;
            TraceCounters counters;
            uint64_t nonFinite = 0;
            ASSERT_TRUE(gen.estimateRecord(viewpoint, dirs[d], light, 7, rec.data(), object, counters, nonFinite));
            const float* t = rec.data() + gen.layout().inputCount();
            std::array<double, 6> m{};
            for (int c = 0; c < 6; ++c) {
                m[size_t(c)] = t[c];
                meanVar[c] += t[6 + c] / kSeeds;
            }
            means.push_back(m);
        }
        for (int c = 0; c < 6; ++c) {
            double mu = 0, var = 0;
            for (const auto& m : means) mu += m[size_t(c)] / kSeeds;
            for (const auto& m : means) var += std::pow(m[size_t(c)] - mu, 2) / (kSeeds - 1);
            if (meanVar[c] < 1e-12 && var < 1e-12) continue;  // a channel without noise (e.g. fully shadowed)
            const double ratio = var / meanVar[c];
            EXPECT_GT(ratio, 0.5) << "ray " << d << " channel " << c;
            EXPECT_LT(ratio, 2.0) << "ray " << d << " channel " << c;
        }
    }
}

TEST(RecordNoise, AdaptiveSamplingReachesTheTargetOrTheCap) {
    const Project p = cornellBox();
    SamplingSettings s;
    s.nx = s.ny = s.nz = 2;
    s.directions = 10;
    s.spp = 16;
    s.maxSpp = 256;
    s.noiseTarget = 0.05;
    s.seed = 3;
    const DataGenerator gen(p.scene, s);
    const GeneratedData d = gen.run();
    const RecordLayout& l = gen.layout();
    const int fpr = l.floatsPerRecord(), in = l.inputCount();
    uint64_t above = 0, records = 0;
    for (const auto& recs : d.perObject)
        for (size_t k = 0; k + size_t(fpr) <= recs.size(); k += size_t(fpr)) {
            const double r = relativeNoise(&recs[k + size_t(in)], &recs[k + size_t(in) + 6]);
            ASSERT_TRUE(std::isfinite(r));
            above += r > s.noiseTarget;
            ++records;
        }
    ASSERT_GT(records, 0u);
    EXPECT_EQ(above, d.stats.recordsAtSppCap) << "a record above the target stopped only at the cap";
    EXPECT_GE(d.stats.paths, records * uint64_t(s.spp));
    EXPECT_LE(d.stats.paths, records * uint64_t(s.maxSpp) + d.stats.recordsWithoutFiniteSample * uint64_t(s.maxSpp));
    EXPECT_GT(d.stats.paths, records * uint64_t(s.spp)) << "some record needed more than the first round";
}

TEST(VisibleRecords, NoRecordOnTheFloorUndersideOrTheBlocksBottoms) {
    const Project p = cornellBox();
    // Under the floor (the tall block reaches 1 cm below it, so the grid does too): behind a surface.
    const DataGenerator probe(p.scene, SamplingSettings());
    const ViewpointClassifier classify(probe.tracer());
    EXPECT_EQ(classify.classify(Vec3(0.f, -1.005f, 0.f)), ViewpointStatus::BehindSurface);
    EXPECT_EQ(classify.classify(Vec3(0.f, -0.99f, 0.f)), ViewpointStatus::Kept) << "just above the floor";

    SamplingSettings s;
    s.nx = s.nz = 5;
    s.ny = 15;  // bottom cells 0.135 high: about 7 % of their viewpoints fall into the 1 cm slab
    s.directions = 30;
    s.spp = s.maxSpp = 1;
    s.seed = 2;
    const DataGenerator gen(p.scene, s);
    const GeneratedData d = gen.run();
    EXPECT_GT(d.stats.cellsDroppedBehindSurface, 0u) << "the test needs viewpoints under the floor";
    const int fpr = gen.layout().floatsPerRecord();
    const int floor = objectId(p.scene, "floor"), shortBox = objectId(p.scene, "short-box"),
              tallBox = objectId(p.scene, "tall-box");
    ASSERT_GE(floor, 0);
    uint64_t checked = 0;
    for (int id : {floor, shortBox, tallBox}) {
        const std::vector<float>& recs = d.perObject[size_t(id)];
        for (size_t k = 0; k + size_t(fpr) <= recs.size(); k += size_t(fpr)) {
            const float ny = recs[k + 10];  // normal_y, flipped to the viewer's side
            if (id == floor) EXPECT_GT(ny, 0.f) << "floor record seen from below";
            else EXPECT_GT(ny, -0.5f) << "block record on its bottom face";
            ++checked;
        }
    }
    EXPECT_GT(checked, 100u);
}

TEST(DatasetVersion, VersionTwoRoundTripsTheNoiseAndVersionOneLoadsWithNoiseUnknown) {
    const Project p = cornellBox();
    SamplingSettings s;
    s.nx = s.ny = s.nz = 2;
    s.directions = 8;
    s.spp = s.maxSpp = 4;
    const DataGenerator gen(p.scene, s);
    const GeneratedData d = gen.run();
    const fs::path v2 = tempFile("v2");
    writeDataset(v2.string(), datasetHeader(d), d.sceneHash, d.perObject);
    {
        const Dataset file(v2.string());
        EXPECT_EQ(file.version(), 2u);
        EXPECT_EQ(file.noiseLayout(), RecordLayout::noiseNames());
        EXPECT_EQ(file.targetCount(), 6);
        const std::vector<ObjectSamples> samples = samplesFromDataset(file);
        const int fpr = file.floatsPerRecord(), in = file.inputCount();
        for (size_t i = 0; i < samples.size(); ++i) {
            ASSERT_EQ(samples[i].directVariance.size(), samples[i].direct.size());
            for (size_t k = 0; k < samples[i].size(); ++k)
                for (int c = 0; c < 3; ++c) {
                    EXPECT_EQ(samples[i].directVariance[3 * k + size_t(c)], d.perObject[i][k * size_t(fpr) + size_t(in + 6 + c)]);
                    EXPECT_EQ(samples[i].indirectVariance[3 * k + size_t(c)], d.perObject[i][k * size_t(fpr) + size_t(in + 9 + c)]);
                }
        }
        const std::string report = formatDatasetReport(file, summarizeDataset(file));
        EXPECT_NE(report.find("target noise: relative standard error"), std::string::npos);
    }
    // A version-1 file: the same records without their noise columns, the header without "noise_layout",
    // and version 1 in the fixed header (bytes 8–11; the fixed header is not under a checksum).
    nlohmann::json h1 = datasetHeader(d);
    h1.erase("noise_layout");
    const int in = gen.layout().inputCount(), fpr = gen.layout().floatsPerRecord();
    h1["floats_per_record"] = in + 6;
    std::vector<std::vector<float>> old(d.perObject.size());
    for (size_t i = 0; i < d.perObject.size(); ++i)
        for (size_t k = 0; k + size_t(fpr) <= d.perObject[i].size(); k += size_t(fpr))
            old[i].insert(old[i].end(), d.perObject[i].begin() + long(k), d.perObject[i].begin() + long(k) + in + 6);
    const fs::path v1 = tempFile("v1");
    writeDataset(v1.string(), h1, d.sceneHash, old);
    {
        std::fstream f(v1, std::ios::in | std::ios::out | std::ios::binary);
        const uint32_t one = 1;
        f.seekp(8);
        f.write(reinterpret_cast<const char*>(&one), 4);
    }
    {
        const Dataset file(v1.string());
        EXPECT_EQ(file.version(), 1u);
        EXPECT_TRUE(file.noiseLayout().empty());
        const std::vector<ObjectSamples> samples = samplesFromDataset(file);
        for (const ObjectSamples& o : samples) {
            EXPECT_TRUE(o.directVariance.empty() && o.indirectVariance.empty()) << "noise unknown";
            EXPECT_EQ(o.size(), size_t(d.stats.recordsPerObject[size_t(o.objectId)]));
        }
        const std::string report = formatDatasetReport(file, summarizeDataset(file));
        EXPECT_NE(report.find("target noise: unknown"), std::string::npos) << report;
    }
    fs::remove(v1);
    fs::remove(v2);
}

}  // namespace test_record_noise
