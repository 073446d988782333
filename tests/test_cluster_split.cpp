// How the ranks of an MPI job share the work (docs/cluster.md), tested without MPI: the cost-balanced
// contiguous cell ranges and the longest-first object assignment against closed forms, and the
// ranks' parts — generated or trained separately, sent as bytes and joined as rank 0 joins them —
// against the single-process run: the dataset's bytes, the networks' weights bit for bit.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>

#include "core/data/cell_split.h"
#include "core/data/data_generator.h"
#include "core/data/dataset_file.h"
#include "core/data/dataset_header_json.h"
#include "core/data/dataset_part.h"
#include "core/nn/trainer_config_json.h"
#include "core/nn/training_part.h"
#include "core/nn/training_split.h"
#include "core/project/project.h"
#include "core/project/project_file.h"
#include "synthetic_samples.h"
#include "tests/training_builders.h"

namespace test_cluster_split {

using namespace rrf;
namespace fs = std::filesystem;

std::vector<std::pair<int, int>> pairs(const std::vector<CellRange>& ranges) {
    std::vector<std::pair<int, int>> out;
    for (const CellRange& r : ranges) out.emplace_back(r.begin, r.end);
    return out;
}

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Bit equality of doubles (NaN equals NaN of the same bits).
bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }


TEST(CellSplit, RangesHoldNearEqualCostAndTileTheCells) {
    // Ten cells of cost 1 in three parts: range r starts at the first c with 3c >= 10r (c = 4, 7).
    EXPECT_EQ(pairs(splitCellsByCost(std::vector<uint64_t>(10, 1), 3)),
              (std::vector<std::pair<int, int>>{{0, 4}, {4, 7}, {7, 10}}));
    // Four dropped cells (cost 0) then four kept ones: each half of the work is two kept cells, and
    // the dropped cells go with the first.
    EXPECT_EQ(pairs(splitCellsByCost({0, 0, 0, 0, 5, 5, 5, 5}, 2)), (std::vector<std::pair<int, int>>{{0, 6}, {6, 8}}));
}

TEST(CellSplit, WithoutCostTheRangesAreTheShards) {
    // --shard k/3 of ten cells: [k·10/3, (k+1)·10/3).
    EXPECT_EQ(pairs(splitCellsByCost(std::vector<uint64_t>(10, 0), 3)),
              (std::vector<std::pair<int, int>>{{0, 3}, {3, 6}, {6, 10}}));
    EXPECT_THROW(splitCellsByCost({1, 2}, 0), std::invalid_argument);
}

TEST(CellSplit, MorePartsThanCellsLeaveEmptyRanges) {
    EXPECT_EQ(pairs(splitCellsByCost({1, 1}, 3)), (std::vector<std::pair<int, int>>{{0, 1}, {1, 2}, {2, 2}}));
}

TEST(LongestFirst, AssignsInDecreasingCostToTheLeastLoadedRank) {
    // 5 → rank 0; 4 → rank 1; 3 → rank 1 (4 < 5); 3 → rank 0 (5 < 7); 3 → rank 1 (7 < 8).
    EXPECT_EQ(assignLongestFirst({5, 4, 3, 3, 3}, 2), (std::vector<int>{0, 1, 1, 0, 1}));
    // LPT is a heuristic: {3,3,2,2,2} on two ranks gives loads 7 and 5, where 6 and 6 exist.
    const std::vector<uint64_t> costs = {3, 3, 2, 2, 2};
    const std::vector<int> rank = assignLongestFirst(costs, 2);
    uint64_t load[2] = {0, 0};
    for (size_t i = 0; i < costs.size(); ++i) load[rank[i]] += costs[i];
    EXPECT_EQ(load[0], 7u);
    EXPECT_EQ(load[1], 5u);
    // More ranks than items: one item each, the rest idle.
    EXPECT_EQ(assignLongestFirst({1, 9}, 4), (std::vector<int>{1, 0}));
    EXPECT_THROW(assignLongestFirst({1}, 0), std::invalid_argument);
}

TEST(ClusterParts, RankPartsOfTheCornellBoxJoinIntoTheSingleProcessBytes) {
    const Project project = loadProjectOrScene(std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/project.json");
    SamplingSettings s;
    s.nx = s.ny = s.nz = 4;
    s.directions = 20;
    s.spp = 4;
    s.seed = 5;
    const DataGenerator gen(project.scene, s);
    const std::vector<uint64_t> costs = cellCosts(gen);
    int dropped = 0;
    uint64_t predicted = 0;
    for (uint64_t c : costs) {
        EXPECT_EQ(c % 4, 0u) << "a cell costs its records x 4 spp";
        predicted += c / 4;
        dropped += c == 0;
    }
    ASSERT_GT(dropped, 0) << "the box has viewpoints inside the blocks and under the floor";
    const std::vector<CellRange> ranges = splitCellsByCost(costs, 3);
    std::vector<NamedPart> parts;
    for (int r = 0; r < 3; ++r) {
        // Each part crosses a process boundary as bytes, as a rank's does.
        const std::string bytes = encodeGeneratedPart(gen.runCells(ranges[size_t(r)].begin, ranges[size_t(r)].end, r, 3));
        parts.push_back({"rank " + std::to_string(r), decodeGeneratedPart(bytes, "rank " + std::to_string(r))});
    }
    std::swap(parts[0], parts[2]);  // any order
    const GeneratedData joined = joinGeneratedParts(parts);
    const GeneratedData whole = gen.run();
    EXPECT_EQ(joined.stats.records, whole.stats.records);
    // The first-hit prediction is the records the generator stores (no sample here is NaN).
    EXPECT_EQ(predicted, whole.stats.records);
    for (size_t c = 0; c < costs.size(); ++c) EXPECT_EQ(costs[c] / 4, whole.stats.recordsPerCell[c]) << "cell " << c;
    const fs::path dir = fs::temp_directory_path() / ("rrf_cluster_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    writeDataset((dir / "joined.rrfd").string(), datasetHeader(joined), joined.sceneHash, joined.perObject);
    writeDataset((dir / "whole.rrfd").string(), datasetHeader(whole), whole.sceneHash, whole.perObject);
    const std::string a = readBytes((dir / "joined.rrfd").string()), b = readBytes((dir / "whole.rrfd").string());
    ASSERT_FALSE(a.empty());
    EXPECT_TRUE(a == b) << "the joined ranks' parts differ from the single-process dataset";
    // A missing part is refused with the cells it leaves out.
    parts.pop_back();
    try {
        joinGeneratedParts(parts);
        ADD_FAILURE() << "a gap was accepted";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("do not"), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}

TEST(ClusterParts, TrainingSharesJoinIntoTheSingleProcessRunBitForBit) {
    const std::vector<ObjectSamples> objs = {syntheticObject(0, 400), syntheticObject(1, 250), syntheticObject(2, 300)};
    ObjectTrainingOptions o = test::plainTraining();
    o.hidden = {6};
    o.targets = TargetMode::Separate;
    o.trainer = trainerConfigFromJson({{"type", "adam"}, {"max_epochs", 4}});
    // A kd-tree that splits once, so trees with two leaves cross too.
    o.partition.maxDepth = 1;
    o.partition.maxLeaves = 2;
    o.partition.goal = 1e-6;
    o.partition.minRecordsPerWeight = 1;
    const TrainingRun whole = trainNetworks(objs, o);

    const std::vector<int> order = trainingObjectOrder(objs, o);
    const std::vector<int> rankOf = assignLongestFirst(trainingCosts(objs, order), 2);
    ASSERT_EQ(rankOf, (std::vector<int>{0, 1, 1})) << "400 records alone, 300 + 250 together";
    std::vector<TrainingRun> parts;
    for (int r = 0; r < 2; ++r) {
        ObjectTrainingOptions mine = o;
        mine.objects.clear();
        for (size_t p = 0; p < order.size(); ++p)
            if (rankOf[p] == r) mine.objects.push_back(order[p]);
        parts.push_back(decodeTrainingPart(encodeTrainingPart(trainNetworks(objs, mine)), "rank " + std::to_string(r)));
    }
    const TrainingRun joined = joinTrainingParts(parts, rankOf, networksPerObject(o));

    ASSERT_EQ(joined.models.size(), whole.models.size());
    EXPECT_EQ(joined.networks, 6);
    bool split = false;
    for (size_t i = 0; i < whole.models.size(); ++i) {
        const ObjectModel &j = joined.models[i], &w = whole.models[i];
        EXPECT_EQ(j.objectId, w.objectId);
        EXPECT_EQ(j.target, w.target);
        ASSERT_EQ(j.model.tree.nodes.size(), w.model.tree.nodes.size());
        split = split || w.model.leafCount() > 1;
        for (size_t n = 0; n < w.model.tree.nodes.size(); ++n) {
            EXPECT_EQ(j.model.tree.nodes[n].split, w.model.tree.nodes[n].split);
            EXPECT_TRUE(sameBits(j.model.tree.nodes[n].error, w.model.tree.nodes[n].error));
        }
        ASSERT_EQ(j.model.leafCount(), w.model.leafCount());
        for (int l = 0; l < w.model.leafCount(); ++l) {
            const NetworkModel &a = j.model.leaves[size_t(l)], &b = w.model.leaves[size_t(l)];
            ASSERT_EQ(a.params.size(), b.params.size());
            EXPECT_EQ(std::memcmp(a.params.data(), b.params.data(), size_t(a.params.size()) * sizeof(double)), 0)
                << "object " << w.objectId << " " << w.target << " leaf " << l;
            EXPECT_EQ(a.outputScaler.scale, b.outputScaler.scale);
            EXPECT_EQ(a.training.epochs, b.training.epochs);
            EXPECT_EQ(a.training.stopReason, b.training.stopReason);
            EXPECT_TRUE(sameBits(a.training.validationRelativeRmseCorrected, b.training.validationRelativeRmseCorrected));
            ASSERT_EQ(a.training.history.size(), b.training.history.size());
            for (size_t e = 0; e < a.training.history.size(); ++e)
                EXPECT_TRUE(sameBits(a.training.history[e].trainLoss, b.training.history[e].trainLoss));
        }
    }
    EXPECT_TRUE(split) << "the test should cover a tree of more than one leaf";
    ASSERT_EQ(joined.curves.size(), whole.curves.size());
    for (size_t c = 0; c < whole.curves.size(); ++c) {
        EXPECT_EQ(joined.curves[c].objectId, whole.curves[c].objectId);
        EXPECT_EQ(joined.curves[c].target, whole.curves[c].target);
        EXPECT_EQ(joined.curves[c].epochs.size(), whole.curves[c].epochs.size());
    }
    // A rank that returns fewer models than its objects need is refused.
    parts[1].models.pop_back();
    EXPECT_THROW(joinTrainingParts(parts, rankOf, networksPerObject(o)), std::runtime_error);
}

}  // namespace test_cluster_split
