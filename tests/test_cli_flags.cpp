#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "app/cli/cli_flags.h"
#include "core/project/project.h"
#include "project_builders.h"

namespace test_cli_flags {

using namespace rrf;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

/// The Cornell box project with `sections` added (tests/project_builders.h), in this file's directory.
Project cornellWith(const std::string& name, const json& sections) {
    return rrf::test::cornellProjectWith("rrf_cli_flags_tests", name, sections);
}

struct Experiment {
    SamplingSettings sampling;
    ObjectTrainingOptions training;
};

/// experimentSettings with no flags given.
Experiment settingsOf(const Project& p, bool quick) {
    const cli::ExperimentFlags flags;
    Experiment e;
    cli::experimentSettings(p, flags, quick ? &cli::quickPreset() : nullptr, e.sampling, e.training);
    return e;
}

}  // namespace

TEST(CliFlags, NetworkWithoutTrainerGetsTheDefaultTrainer) {
    const Project p = cornellWith("network_only.json", {{"network", {{"hidden", {8, 4}}}}});
    const Experiment e = settingsOf(p, false);
    EXPECT_EQ(e.training.hidden, (std::vector<int>{8, 4})) << "the project's network section is used";
    // No trainer section: the project default (Adam, relative L2, error goal 0.02, 600 epochs).
    EXPECT_EQ(e.training.trainer.type, TrainerType::Adam);
    EXPECT_EQ(e.training.trainer.adam.loss, AdamLoss::RelativeL2);
    EXPECT_EQ(e.training.trainer.maxEpochs(), 600);
    EXPECT_DOUBLE_EQ(e.training.trainer.errorGoal(), 0.02);
    EXPECT_EQ(settingsOf(p, true).training.trainer.maxEpochs(), 50) << "--quick's epoch limit";
}

TEST(CliFlags, TrainerSectionKeepsItsEpochLimit) {
    const Project p = cornellWith("trainer.json", {{"trainer", {{"type", "lm"}, {"max_epochs", 7}}}});
    EXPECT_EQ(settingsOf(p, false).training.trainer.maxEpochs(), 7);
    EXPECT_EQ(settingsOf(p, true).training.trainer.maxEpochs(), 50) << "--quick overrides the project";
}

TEST(CliFlags, NeitherSectionGetsTheProjectDefaults) {
    const Project p = cornellWith("bare.json", json::object());
    const Experiment e = settingsOf(p, false);
    EXPECT_EQ(e.training.trainer.maxEpochs(), 600);
    EXPECT_EQ(e.sampling.nx, 8);
    EXPECT_EQ(e.sampling.directions, 300);
    const Experiment q = settingsOf(p, true);
    EXPECT_EQ(q.sampling.nx, 5) << "--quick's sizes";
    EXPECT_EQ(q.sampling.directions, 150);
    // A partial section keeps the project defaults for what it does not say.
    const Project partial = cornellWith("partial.json", {{"sampling", {{"grid", {4, 4, 4}}}}});
    EXPECT_EQ(settingsOf(partial, false).sampling.nx, 4);
    EXPECT_EQ(settingsOf(partial, false).sampling.directions, 300);
}

}  // namespace test_cli_flags
