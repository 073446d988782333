// Typed run records (core/project/run_fields.h): a known key of the wrong type in a run's settings,
// metrics or timings is refused with the file, the JSON pointer and what was expected (the damaged
// run is skipped, the others kept); keys this build does not know come back verbatim; and a figure
// recorded as null (a non-finite estimate) stays null.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/nn/trainer_config_json.h"
#include "core/project/runs.h"
#include "core/project/runs_json.h"
#include "core/util/error.h"
#include "core/util/json_reader.h"

namespace rrf::test::test_run_records {
namespace {

using nlohmann::json;

const char* const kFile = "/p/project.json";

/// A train run as the workbench writes one, with a figure of every type.
json trainRun() {
    json run = json::parse(R"({
        "id": "train-1", "name": "train-1", "kind": "train", "created": "2026-12-05T02:40:00",
        "settings": {"dataset": "data/dataset.rrfd", "scene_hash": "00ff", "kernel": "avx2"},
        "loss": [],
        "metrics": {"networks": 7, "skipped": 0, "epochs": 12, "stopped": true, "records": 4096,
                    "relative_rmse": 0.05, "evaluated_light": [0.5, 1.0, 0.25], "glsl_frame_seconds": 0.004},
        "timings": {"train": 12.5, "generate": 3.0},
        "artifacts": ["runs/train-1/models/models.json"]
    })");
    // The workbench writes every key of the trainer (TrainerConfig::toJson).
    run["settings"]["trainer"] = toJson(TrainerConfig().withType(TrainerType::Adam));
    return run;
}

/// readRuns of [good, `damaged`]: the warning it gives about the damaged run (the good run must
/// still be read).
std::string warningFor(const json& damaged) {
    const json runs = json::array({trainRun(), damaged});
    std::vector<std::string> warnings;
    const std::vector<rrf::Run> read = readRuns(JsonReader(runs, kFile, "/runs"), warnings);
    EXPECT_EQ(read.size(), 1u) << "the damaged run is skipped, the good one kept";
    EXPECT_EQ(warnings.size(), 1u);
    return warnings.empty() ? std::string() : warnings.front();
}

void expectMentions(const std::string& text, const std::vector<std::string>& parts) {
    for (const std::string& p : parts) EXPECT_NE(text.find(p), std::string::npos) << "'" << p << "' in: " << text;
}

}  // namespace

TEST(RunRecords, AMistypedMetricIsRefusedWithFilePointerAndExpectation) {
    json run = trainRun();
    run["id"] = "train-2";
    run["metrics"]["networks"] = "seven";
    expectMentions(warningFor(run), {kFile, "/runs/1/metrics/networks", "integer", "string", "run skipped"});
}

TEST(RunRecords, AMistypedTimingIsRefused) {
    json run = trainRun();
    run["timings"]["train"] = json::array({1, 2});
    expectMentions(warningFor(run), {kFile, "/runs/1/timings/train", "number", "array"});
}

TEST(RunRecords, AMistypedSettingIsRefused) {
    json run = trainRun();
    run["settings"]["dataset"] = 3;
    expectMentions(warningFor(run), {kFile, "/runs/1/settings/dataset", "string", "number"});
    json vector = trainRun();
    vector["metrics"]["evaluated_light"] = json::array({1, 2});
    expectMentions(warningFor(vector), {kFile, "/runs/1/metrics/evaluated_light", "3 numbers"});
    json flag = trainRun();
    flag["metrics"]["stopped"] = 1;
    expectMentions(warningFor(flag), {kFile, "/runs/1/metrics/stopped", "true or false"});
}

TEST(RunRecords, KnownFiguresReadIntoFields) {
    std::vector<std::string> warnings;
    const json doc = trainRun();
    const rrf::Run r = rrf::runFromJson(JsonReader(doc, kFile, "/runs/0"), warnings);
    EXPECT_TRUE(warnings.empty());
    EXPECT_EQ(r.metrics.networks, 7);
    EXPECT_EQ(r.metrics.records, 4096);
    EXPECT_EQ(r.metrics.stopped, true);
    ASSERT_TRUE(r.metrics.evaluatedLight.has_value());
    EXPECT_EQ(r.metrics.evaluatedLight->z, 0.25f);
    EXPECT_EQ(r.metrics.glslFrameSeconds, 0.004);
    EXPECT_FALSE(r.metrics.frameSeconds.has_value());
    EXPECT_EQ(r.timings.generate, 3.0);
    EXPECT_EQ(r.settings.dataset, "data/dataset.rrfd");
    ASSERT_TRUE(r.settings.trainer.has_value());
    EXPECT_EQ(r.settings.trainer->type, TrainerType::Adam);
    EXPECT_TRUE(r.metrics.other.empty());
    EXPECT_TRUE(r.settings.other.empty());
}

TEST(RunRecords, ASettingsSectionThisBuildCannotReadKeepsTheRun) {
    // A newer build's trainer type: the run stays (its figures with it), the section is written back
    // as it was, and the warning names the file, the pointer and what was expected.
    json doc = trainRun();
    doc["settings"]["trainer"] = {{"type", "future_optimizer"}};
    const json runs = json::array({doc});
    std::vector<std::string> warnings;
    const std::vector<rrf::Run> read = readRuns(JsonReader(runs, kFile, "/runs"), warnings);
    ASSERT_EQ(read.size(), 1u) << "the run is kept";
    EXPECT_FALSE(read[0].settings.trainer.has_value());
    EXPECT_EQ(read[0].metrics.networks, 7);
    ASSERT_EQ(warnings.size(), 1u);
    expectMentions(warnings[0], {kFile, "/runs/0/settings/trainer", "kept as written"});
    EXPECT_EQ(toJson(read[0]), doc) << "saving writes the section back unchanged";
}

TEST(RunRecords, UnknownKeysAndNullFiguresComeBackVerbatim) {
    json doc = trainRun();
    doc["settings"]["future_setting"] = {{"a", json::array({1, "b"})}};
    doc["metrics"]["future_metric"] = "text";
    doc["metrics"]["relative_rmse"] = nullptr;  // a non-finite estimate, as nlohmann writes NaN
    doc["timings"]["future_stage"] = 1.5;
    doc["future_section"] = true;
    std::vector<std::string> warnings;
    const rrf::Run r = rrf::runFromJson(JsonReader(doc, kFile, "/runs/0"), warnings);
    ASSERT_TRUE(r.metrics.relativeRmse.has_value());
    EXPECT_TRUE(std::isnan(*r.metrics.relativeRmse));
    EXPECT_EQ(finiteOrNone(r.metrics.relativeRmse), std::nullopt) << "a null figure is unknown in tables";
    EXPECT_EQ(parseJsonText(r.metrics.other).at("future_metric"), "text");
    EXPECT_EQ(toJson(r), doc);
    EXPECT_EQ(toJson(r).dump(), doc.dump());
}

}  // namespace rrf::test::test_run_records
