// Sweeps over the settings of partitioned, goal-driven training (core/pipeline/sweep.h kinds "goal",
// "leaves", "record_spp"): bad values name the setting before anything renders, and each kind changes
// what it says — more leaves where the budget allows, earlier stops for a looser goal, more paths per
// record for a larger max_spp.
#include <gtest/gtest.h>

#include <string>

#include "core/pipeline/sweep.h"
#include "core/util/error.h"
#include "scene_builders.h"
#include "sweep_refusal.h"
#include "tests/training_builders.h"

namespace test_partition_sweeps {

using namespace rrf;

namespace {

using rrf::test::settingNamedBy;

/// A sweep small enough for a unit test: 16² images, a 2³ grid, tiny networks.
SweepOptions smallSweep(const std::string& what, std::vector<std::string> values) {
    SweepOptions o;
    o.training = test::plainTraining();
    o.what = what;
    o.values = std::move(values);
    o.width = o.height = 16;
    o.referenceSpp = 16;
    o.pathTracerSpp = {1, 2};
    o.sampling.nx = o.sampling.ny = o.sampling.nz = 2;
    o.sampling.directions = 60;
    o.sampling.spp = 2;
    o.sampling.maxSpp = 2;
    o.training.hidden = {3};
    o.training.targets = TargetMode::Global;
    o.training.trainer.lm.maxEpochs = 30;
    o.training.trainer.lm.errorGoal = 0;
    o.training.partition.goal = 1e-6;  // every node is above it: only the budget stops the trees
    o.training.partition.minRecordsPerWeight = 1;
    return o;
}

}  // namespace

TEST(PartitionSweeps, DefaultsAndBadValues) {
    EXPECT_EQ(defaultSweepValues("goal"), (std::vector<std::string>{"0.1", "0.05", "0.03"}));
    EXPECT_EQ(defaultSweepValues("leaves"), (std::vector<std::string>{"1", "4", "16"}));
    EXPECT_EQ(defaultSweepValues("record_spp"), (std::vector<std::string>{"64", "256", "1024"}));
    // A scene whose reference would take long: a bad value must be reported before it renders.
    const Scene scene = test::cornellLike();
    SweepOptions o;
    o.training = test::plainTraining();
    o.width = o.height = 4096;
    o.referenceSpp = 1 << 20;
    const std::pair<const char*, std::vector<std::string>> bad[] = {
        {"goal", {"0.05", "0"}},   {"goal", {"-0.1"}},      {"goal", {"11"}},      {"goal", {"0.05x"}},
        {"leaves", {"0"}},         {"leaves", {"5000"}},    {"leaves", {"2.5"}},   {"record_spp", {"0"}},
        {"record_spp", {"64,128"}}, {"record_spp", {"2000000"}},
    };
    for (const auto& [what, values] : bad) {
        o.what = what;
        o.values = values;
        EXPECT_EQ(settingNamedBy(scene, o), "sweep values") << what << " " << values.back();
    }
}

TEST(PartitionSweeps, LeavesGrowWithTheBudgetAndALooseGoalStopsEarly) {
    const Scene scene = test::cornellLike(1.f, 16);
    const SweepResult leaves = runSweep(scene, smallSweep("leaves", {"1", "4"}));
    ASSERT_EQ(leaves.rows.size(), 2u);
    const int64_t objects = leaves.rows[0].extra.leaves.value();
    EXPECT_GT(objects, 0);
    // One network per object at "1"; with a goal nothing reaches, "4" lets every tree that has the
    // records grow past its root, and none beyond 4 leaves.
    EXPECT_GT(leaves.rows[1].extra.leaves.value(), objects);
    EXPECT_LE(leaves.rows[1].extra.leaves.value(), 4 * objects);

    SweepOptions g = smallSweep("goal", {"10", "0.000001"});
    g.training.partition.maxLeaves = 1;
    const SweepResult goal = runSweep(scene, g);
    ASSERT_EQ(goal.rows.size(), 2u);
    // A goal of 10 (relative RMSE) is met by the first epoch; 1e-6 by none, so each network runs to
    // max_epochs or another stop rule.
    EXPECT_LT(goal.rows[0].extra.leafEpochs.value(), goal.rows[1].extra.leafEpochs.value());
    EXPECT_LE(goal.rows[0].extra.leafEpochs.value(), objects * 1);
}

TEST(PartitionSweeps, RecordSppSetsThePathsPerRecord) {
    const Scene scene = test::cornellLike(1.f, 16);
    SweepOptions o = smallSweep("record_spp", {"1", "8"});
    o.sampling.spp = 4;  // "1" lowers spp to 1 (fixed), "8" lets the adaptive sampler go up to 8
    o.sampling.maxSpp = 4;
    o.training.trainer.lm.maxEpochs = 2;
    const SweepResult r = runSweep(scene, o);
    ASSERT_EQ(r.rows.size(), 2u);
    EXPECT_EQ(r.rows[0].extra.meanRecordSpp.value(), 1.0);
    EXPECT_GE(r.rows[1].extra.meanRecordSpp.value(), 4.0);
    EXPECT_LE(r.rows[1].extra.meanRecordSpp.value(), 8.0);
}

}  // namespace test_partition_sweeps
