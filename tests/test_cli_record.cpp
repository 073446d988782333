// `rrf render|train|evaluate --record` through the real executable: the run lands in the project's
// "runs" section with the fields the workbench records (core/pipeline/run_recording.h), its files
// under <project dir>/runs/<id>/, and the project loads back with every artifact the run names
// present — what the workbench needs to list, re-open and compare it.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

#include "core/project/project.h"
#include "core/pipeline/run_recording.h"

#include "core/project/project_file.h"
#include "core/project/runs_json.h"
#include "tests/cli_runner.h"

namespace fs = std::filesystem;

namespace rrf::test::test_cli_record {
namespace {

using Result = rrf::test::CliResult;
using rrf::test::runCli;

const fs::path kCornellDir = fs::path(RRF_SOURCE_DIR) / "projects" / "cornell-box";

/// A private copy of the Cornell box project (project.json + scene.json).
fs::path copyOfCornell(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("rrf_cli_record_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    for (const char* f : {"project.json", "scene.json"}) fs::copy_file(kCornellDir / f, d / f);
    return d;
}

/// Every artifact a run names exists under the project directory (what the workbench opens).
void expectArtifactsPresent(const Project& p, const rrf::Run& run) {
    ASSERT_FALSE(run.artifacts.empty()) << run.id;
    for (const std::string& a : run.artifacts)
        EXPECT_TRUE(fs::exists(fs::path(projectDirectory(p)) / a)) << run.id << ": " << a;
}

/// The runs the CLI wrote read into the typed records and write back as the very same text: the
/// format is unchanged by reading it.
void expectRunsRoundTrip(const std::string& projectFile) {
    const nlohmann::json doc = readJsonFile(projectFile);
    ASSERT_TRUE(doc.contains("runs"));
    std::vector<std::string> warnings;
    const std::vector<rrf::Run> runs = readRuns(JsonReader(doc.at("runs"), projectFile, "/runs"), warnings);
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    ASSERT_EQ(runs.size(), doc.at("runs").size());
    EXPECT_EQ(runsToJson(runs).dump(2), doc.at("runs").dump(2));
}

}  // namespace

TEST(CliRecord, RenderRecordsARunWithItsImagesAndSettings) {
    const fs::path dir = copyOfCornell("render");
    const std::string project = (dir / "project.json").string();
    const Result r = runCli("render " + project + " --spp 1 --width 16 --height 16 --record");
    ASSERT_EQ(r.code, 0) << r.output;

    const Project p = loadProjectOrScene(project);
    ASSERT_EQ(p.runs.size(), 1u) << r.output;
    const rrf::Run& run = p.runs[0];
    EXPECT_EQ(run.kind, "render");
    EXPECT_EQ(run.name, run.id);
    EXPECT_FALSE(run.created.empty());
    expectArtifactsPresent(p, run);
    for (const char* f : {"global.exr", "direct.exr", "indirect.exr", "render.json"})
        EXPECT_TRUE(fs::exists(dir / "runs" / run.id / f)) << f;
    // The settings snapshot the workbench re-opens: render settings, light and scene.
    ASSERT_TRUE(run.settings.render.has_value());
    EXPECT_EQ(run.settings.render->width, 16);
    EXPECT_EQ(run.settings.render->height, 16);
    EXPECT_EQ(run.settings.render->spp, 1);
    EXPECT_TRUE(run.settings.lightPosition.has_value());
    EXPECT_TRUE(run.settings.sceneHash.has_value());
    EXPECT_EQ(run.metrics.spp.value_or(0), 1);
    EXPECT_TRUE(run.metrics.relativeError.has_value());
    EXPECT_TRUE(run.timings.render.has_value());
    expectRunsRoundTrip(project);
    // The user's own settings are not touched by recording.
    EXPECT_EQ(p.render.spp, 64);
    EXPECT_EQ(p.render.width, 0);

    // A second run gets its own id and directory.
    ASSERT_EQ(runCli("render " + project + " --spp 1 --width 8 --height 8 --record").code, 0);
    const Project again = loadProjectOrScene(project);
    ASSERT_EQ(again.runs.size(), 2u);
    EXPECT_NE(again.runs[0].id, again.runs[1].id);
    expectArtifactsPresent(again, again.runs[1]);
    fs::remove_all(dir);
}

TEST(CliRecord, WithoutRecordTheProjectIsNotChanged) {
    const fs::path dir = copyOfCornell("plain");
    const std::string project = (dir / "project.json").string();
    std::ifstream before(project);
    const std::string text((std::istreambuf_iterator<char>(before)), {});
    const Result r = runCli("render " + project + " --spp 1 --width 8 --height 8 --out " + (dir / "out").string());
    ASSERT_EQ(r.code, 0) << r.output;
    std::ifstream after(project);
    EXPECT_EQ(std::string((std::istreambuf_iterator<char>(after)), {}), text);
    EXPECT_FALSE(fs::exists(dir / "runs"));
    fs::remove_all(dir);
}

TEST(CliRecord, RefusesABareSceneFile) {
    const fs::path dir = copyOfCornell("bare");
    const std::string scene = (dir / "scene.json").string();
    std::ifstream before(scene);
    const std::string text((std::istreambuf_iterator<char>(before)), {});
    for (const std::string& cmd : {"render " + scene + " --spp 1 --width 8 --height 8 --record",
                                   "train " + scene + " --data " + (dir / "none.rrfd").string() + " --record"}) {
        const Result r = runCli(cmd);
        EXPECT_NE(r.code, 0) << cmd;
        EXPECT_NE(r.output.find("--record"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("scene file"), std::string::npos) << r.output;
    }
    std::ifstream after(scene);
    EXPECT_EQ(std::string((std::istreambuf_iterator<char>(after)), {}), text);
    EXPECT_FALSE(fs::exists(dir / "runs"));
    // Without --record an output directory is still required.
    const Result noOut = runCli("render " + (dir / "project.json").string() + " --spp 1");
    EXPECT_NE(noOut.code, 0);
    EXPECT_NE(noOut.output.find("--out"), std::string::npos) << noOut.output;
    fs::remove_all(dir);
}

TEST(CliRecord, TrainAndEvaluateRecordLikeTheWorkbench) {
    const fs::path dir = copyOfCornell("train");
    const std::string project = (dir / "project.json").string();
    const std::string data = (dir / "data.rrfd").string();
    const Result g = runCli("generate " + project + " --grid 2,2,2 --dirs 4 --spp 2 --threads 2 --out " + data);
    ASSERT_EQ(g.code, 0) << g.output;
    const Result t = runCli("train " + project + " --data " + data + " --hidden 4 --epochs 3 --threads 2 --log-every 0 --record");
    ASSERT_EQ(t.code, 0) << t.output;

    const Project p = loadProjectOrScene(project);
    ASSERT_EQ(p.runs.size(), 1u) << t.output;
    const rrf::Run& run = p.runs[0];
    EXPECT_EQ(run.kind, "train");
    expectArtifactsPresent(p, run);
    // The workbench loads the models from the first artifact's directory.
    const std::string models = trainRunModelsDir(run, projectDirectory(p));
    EXPECT_TRUE(fs::exists(fs::path(models) / "models.json"));
    EXPECT_EQ(fs::path(models), dir / "runs" / run.id / "models");
    ASSERT_TRUE(run.settings.network.has_value());
    EXPECT_EQ(run.settings.network->options.hidden, std::vector<int>({4}));
    EXPECT_TRUE(run.settings.trainer.has_value());
    EXPECT_EQ(run.settings.dataset.value_or(""), "data.rrfd");
    EXPECT_FALSE(run.curves.empty());
    EXPECT_FALSE(run.loss.empty());
    EXPECT_GT(run.metrics.networks.value_or(0), 0);
    EXPECT_EQ(run.metrics.epochs.value_or(-1), 3);
    EXPECT_TRUE(run.timings.train.has_value());
    EXPECT_EQ(findTrainRun(p.runs, projectDirectory(p), models), &run);

    // Evaluating those models adds the metrics to the train run, as the workbench's Evaluate does.
    const Result e = runCli("evaluate " + project + " --models " + models + " --spp 1 --width 16 --height 16 --threads 2 --record");
    ASSERT_EQ(e.code, 0) << e.output;
    const Project q = loadProjectOrScene(project);
    ASSERT_EQ(q.runs.size(), 1u);
    const rrf::Run& judged = q.runs[0];
    EXPECT_TRUE(judged.metrics.relativeRmse.has_value());
    EXPECT_TRUE(judged.metrics.rmse.has_value());
    EXPECT_EQ(judged.metrics.evaluatedSpp.value_or(0), 1);
    EXPECT_TRUE(judged.metrics.evaluatedLight.has_value());
    EXPECT_TRUE(judged.timings.evaluate.has_value());
    expectRunsRoundTrip(project);
    EXPECT_EQ(judged.artifacts.front(), run.artifacts.front());
    expectArtifactsPresent(q, judged);
    EXPECT_TRUE(fs::exists(dir / "runs" / run.id / "evaluation" / "evaluation.json"));

    // Models that no recorded run made cannot take an evaluation's metrics.
    const Result stray = runCli("train " + project + " --data " + data + " --hidden 4 --epochs 1 --threads 2 --log-every 0 --out " +
                                (dir / "stray").string());
    ASSERT_EQ(stray.code, 0) << stray.output;
    const Result refused = runCli("evaluate " + project + " --models " + (dir / "stray").string() +
                                  " --spp 1 --width 8 --height 8 --record");
    EXPECT_NE(refused.code, 0);
    EXPECT_NE(refused.output.find("--record"), std::string::npos) << refused.output;
    fs::remove_all(dir);
}

}  // namespace rrf::test::test_cli_record
