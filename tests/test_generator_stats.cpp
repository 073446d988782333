// Typed generator statistics: what DataGenerator::run counts is what the dataset header stores, and
// a written file reads back into the same numbers (the CLI prints them, the workbench shows them).
#include <gtest/gtest.h>

#include <filesystem>
#include <numeric>

#include <unistd.h>

#include "core/data/data_generator.h"
#include "core/data/dataset_file.h"
#include "core/data/dataset_header_json.h"
#include "core/data/generator_stats.h"
#include "core/data/generator_stats_json.h"
#include "core/project/project.h"
#include "core/project/project_file.h"
#include "core/util/error.h"

namespace test_generator_stats {

using namespace rrf;
namespace fs = std::filesystem;

namespace {
SamplingSettings tinySettings() {
    SamplingSettings s;
    s.nx = s.ny = s.nz = 3;
    s.directions = 12;
    s.spp = 2;
    s.maxSpp = 2;  // fixed paths per record: paths = records · spp below
    s.seed = 7;
    return s;
}
}  // namespace

TEST(GeneratorStats, RunCountsAreTheHeaderStats) {
    const Project project = loadProjectOrScene(std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/project.json");
    const SamplingSettings s = tinySettings();
    const GeneratedData d = DataGenerator(project.scene, s).run();
    const GeneratorStats& st = d.stats;
    EXPECT_EQ(toJson(st), datasetHeader(d).at("stats")) << "the header stores exactly the typed counters";
    EXPECT_EQ(st.cells(), uint64_t(s.nx * s.ny * s.nz));
    ASSERT_EQ(st.recordsPerObject.size(), project.scene.objects.size());
    EXPECT_EQ(std::accumulate(st.recordsPerObject.begin(), st.recordsPerObject.end(), uint64_t(0)), st.records);
    EXPECT_EQ(std::accumulate(st.recordsPerCell.begin(), st.recordsPerCell.end(), uint64_t(0)), st.records);
    EXPECT_EQ(st.records + st.raysEscaped + st.raysHitEmitter + st.recordsWithoutFiniteSample,
              st.keptCells() * uint64_t(s.directions));
    EXPECT_EQ(st.paths, st.records * uint64_t(s.spp));
    EXPECT_GT(st.rays, 0u);
}

TEST(GeneratorStats, WrittenDatasetReadsBackTheSameStats) {
    const Project project = loadProjectOrScene(std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/project.json");
    const GeneratedData d = DataGenerator(project.scene, tinySettings()).run();
    const fs::path path = fs::temp_directory_path() / ("rrf_generator_stats_" + std::to_string(::getpid()) + ".rrfd");
    writeDataset(path.string(), datasetHeader(d), d.sceneHash, d.perObject);
    const Dataset file(path.string());
    const GeneratorStats read = generatorStatsFromHeader(file.header(), file.path());
    EXPECT_EQ(toJson(read), toJson(d.stats));
    EXPECT_EQ(read.recordsPerObject, d.stats.recordsPerObject);
    EXPECT_EQ(read.paths, 0u) << "work counters are not stored";
    fs::remove(path);
}

TEST(GeneratorStats, MistypedCounterNamesItsPointer) {
    nlohmann::json header = {{"stats", {{"records", "many"}}}};
    try {
        generatorStatsFromHeader(header, "data.rrfd");
        FAIL() << "a string counter must be rejected";
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), "data.rrfd");
        EXPECT_EQ(e.where(), "/stats/records");
    }
    header["stats"] = {{"records", 3}};
    EXPECT_EQ(generatorStatsFromHeader(header, "data.rrfd").records, 3u) << "older files: finer counters read as 0";
}

TEST(GeneratorStats, AddingTheNextShardSumsCountersAndAppendsCells) {
    GeneratorStats a;
    a.records = 5;
    a.cellsDroppedInsideObject = 1;
    a.raysEscaped = 2;
    a.recordsPerCell = {3, 2};
    a.recordsPerObject = {4, 1};
    a.paths = 10;
    GeneratorStats b;
    b.records = 4;
    b.cellsDroppedOutsideScene = 2;
    b.raysHitEmitter = 3;
    b.nonFiniteSamplesDropped = 1;
    b.recordsPerCell = {0, 4};
    b.recordsPerObject = {1, 2, 1};
    b.paths = 8;
    a += b;
    EXPECT_EQ(a.records, 9u);
    EXPECT_EQ(a.cellsDroppedInsideObject, 1u);
    EXPECT_EQ(a.cellsDroppedOutsideScene, 2u);
    EXPECT_EQ(a.raysEscaped, 2u);
    EXPECT_EQ(a.raysHitEmitter, 3u);
    EXPECT_EQ(a.nonFiniteSamplesDropped, 1u);
    EXPECT_EQ(a.recordsPerCell, (std::vector<uint64_t>{3, 2, 0, 4})) << "cells stay in cell order";
    EXPECT_EQ(a.recordsPerObject, (std::vector<uint64_t>{5, 3, 1}));
    EXPECT_EQ(a.paths, 18u);
}

}  // namespace test_generator_stats
