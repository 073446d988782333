// Sweeps over the networks' input encoding (core/pipeline/sweep.h kind "encoding"): names are checked,
// and a trainable encoding under Levenberg–Marquardt refused, before anything renders; each row
// reports its parameters (encoding tables included) and model bytes.
#include <gtest/gtest.h>

#include <string>

#include "core/pipeline/sweep.h"
#include "core/nn/encoding_presets.h"
#include "core/util/error.h"
#include "scene_builders.h"
#include "sweep_refusal.h"
#include "tests/training_builders.h"

namespace test_encoding_sweeps {

using namespace rrf;

namespace {

using rrf::test::settingNamedBy;

}  // namespace

TEST(EncodingSweeps, BadNamesAndAHashGridUnderLmAreRefusedBeforeRendering) {
    EXPECT_EQ(defaultSweepValues("encoding"), (std::vector<std::string>{"raw", "frequency", "hash_grid"}));
    const Scene scene = test::cornellLike();
    SweepOptions o;
    o.training = test::plainTraining();
    o.what = "encoding";
    o.width = o.height = 4096;  // a reference that would take long: the refusal must come first
    o.referenceSpp = 1 << 20;
    o.training.trainer = TrainerConfig().withType(TrainerType::LevenbergMarquardt);
    o.values = {"raw", "nerf"};
    EXPECT_EQ(settingNamedBy(scene, o), "sweep values");
    o.values = {"raw", "hash_grid"};
    EXPECT_EQ(settingNamedBy(scene, o), "sweep values");
}

TEST(EncodingSweeps, RowsCountEncodingParametersAndModelBytes) {
    const Scene scene = test::cornellLike(1.f, 16);
    SweepOptions o;
    o.training = test::plainTraining();
    o.what = "encoding";
    o.values = {"raw", "hash_grid"};
    o.width = o.height = 16;
    o.referenceSpp = 16;
    o.pathTracerSpp = {1, 2};
    o.sampling.nx = o.sampling.ny = o.sampling.nz = 2;
    o.sampling.directions = 40;
    o.sampling.spp = o.sampling.maxSpp = 2;
    o.training.hidden = {3};
    o.training.targets = TargetMode::Global;
    o.training.trainer = TrainerConfig().withType(TrainerType::Adam);
    o.training.trainer.adam.maxEpochs = 2;
    const SweepResult r = runSweep(scene, o);
    ASSERT_EQ(r.rows.size(), 2u);
    const int64_t rawParams = r.rows[0].extra.parameters.value();
    const int64_t gridParams = r.rows[1].extra.parameters.value();
    const int64_t rawBytes = r.rows[0].extra.modelBytes.value();
    // One 3-output network per object: 15 raw inputs → 3 → 3, or 16 grid features + 12 raw → 3 → 3
    // behind 8 levels × 4096 entries × 2 features (the "hash_grid" preset).
    const int64_t perRaw = (15 + 1) * 3 + (3 + 1) * 3, perGrid = (16 + 12 + 1) * 3 + (3 + 1) * 3 + 8 * 4096 * 2;
    ASSERT_GT(rawParams, 0);
    ASSERT_EQ(rawParams % perRaw, 0);
    const int64_t networks = rawParams / perRaw;
    EXPECT_EQ(gridParams, networks * perGrid);
    // float64 payload: parameters, then offset and scale of 15 inputs and of 3 outputs per network.
    EXPECT_EQ(rawBytes, 8 * (rawParams + networks * (2 * 15 + 2 * 3)));
    const std::string csv = sweepCsv(scene, r);
    EXPECT_NE(csv.find(",parameters,model_bytes\n"), std::string::npos);
    EXPECT_NE(csv.find("," + std::to_string(gridParams) + ","), std::string::npos);
}

}  // namespace test_encoding_sweeps
