#include <gtest/gtest.h>

#include <algorithm>
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

namespace test_cli_flags {

TEST(CliFlags, NetworkFlagsSetEveryNetworkAndDropThePerObjectEntriesOfTheirSetting) {
    const Project p = cornellWith("per_object.json",
                                  json::parse(R"({"network": {"hidden": [20, 10], "objects": {
                                      "tall-box": {"hidden": [32, 16], "inputs": {"reflected": true}},
                                      "floor": {"hidden": [8]}}}})"));
    const ObjectTrainingOptions base = settingsOf(p, false).training;
    ASSERT_EQ(base.choiceFor("tall-box").hidden, (std::vector<int>{32, 16}));
    ASSERT_TRUE(base.choiceFor("tall-box").inputs.reflected);
    ASSERT_FALSE(base.choiceFor("floor").inputs.reflected);

    auto parsed = [&](std::vector<std::string> args) {
        CLI::App app;
        cli::SettingFlags<ObjectTrainingOptions> flags;
        cli::addNetworkFlags(&app, flags);
        std::reverse(args.begin(), args.end());  // CLI11 parses a vector from its back
        app.parse(args);
        return flags.applied(base);
    };
    // --reflected: every network's, the tall box's entry keeps only its hidden sizes.
    const ObjectTrainingOptions off = parsed({"--reflected", "off"});
    EXPECT_FALSE(off.inputs.reflected);
    EXPECT_FALSE(off.choiceFor("tall-box").inputs.reflected);
    EXPECT_EQ(off.choiceFor("tall-box").hidden, (std::vector<int>{32, 16}));
    const ObjectTrainingOptions on = parsed({"--reflected", "on"});
    EXPECT_TRUE(on.choiceFor("floor").inputs.reflected);
    // --hidden: every network's; the floor's entry had nothing else and is gone.
    const ObjectTrainingOptions hidden = parsed({"--hidden", "12,6"});
    EXPECT_EQ(hidden.choiceFor("tall-box").hidden, (std::vector<int>{12, 6}));
    EXPECT_EQ(hidden.choiceFor("floor").hidden, (std::vector<int>{12, 6}));
    EXPECT_EQ(hidden.perObject.count("floor"), 0u);
    EXPECT_TRUE(hidden.choiceFor("tall-box").inputs.reflected) << "the entry's other settings stay";
    EXPECT_THROW(parsed({"--reflected", "maybe"}), CLI::ValidationError);
}

}  // namespace test_cli_flags
