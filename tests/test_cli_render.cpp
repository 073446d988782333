// End-to-end tests of `rrf render` through the real executable: outputs land where promised, and
// every kind of bad input exits non-zero with one clear message naming what is wrong. Also the
// spelling of settings on every command (--grid 15,15,15, --hidden 20,10, sweep --values): bad values
// name their flag, even when core reports them by setting name.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include "core/util/image_io.h"

#include "tests/cli_runner.h"

namespace test_cli_render {

namespace fs = std::filesystem;

namespace {

using Result = rrf::test::CliResult;
using rrf::test::runCli;

fs::path tempDir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("rrf_cli_render_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

const std::string kCornell = std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/project.json";

}  // namespace

TEST(CliRender, WritesThreeImagesAndMetadata) {
    const fs::path out = tempDir("ok");
    const Result r = runCli("render " + kCornell + " --spp 2 --width 32 --height 24 --format pfm --out " + out.string());
    ASSERT_EQ(r.code, 0) << r.output;
    for (const char* name : {"global.pfm", "direct.pfm", "indirect.pfm", "render.json"})
        EXPECT_TRUE(fs::exists(out / name)) << name << "\n" << r.output;
    const rrf::Image g = rrf::readImage((out / "global.pfm").string());
    EXPECT_EQ(g.width, 32);
    EXPECT_EQ(g.height, 24);
    EXPECT_EQ(g.nonFiniteCount(), 0u);
    std::ifstream meta(out / "render.json");
    const nlohmann::json j = nlohmann::json::parse(meta);
    EXPECT_EQ(j.at("spp_completed"), 2);
    EXPECT_EQ(j.at("non_finite_samples_dropped"), 0);
    EXPECT_TRUE(j.at("effects").at("indirect").get<bool>());
    // The report names the rates the issue asks for.
    EXPECT_NE(r.output.find("samples/s"), std::string::npos);
    EXPECT_NE(r.output.find("rays/s"), std::string::npos);
    fs::remove_all(out);
}

TEST(CliRender, LightPositionMovesTheLight) {
    const fs::path out = tempDir("light");
    const Result a = runCli("render " + kCornell + " --spp 4 --width 16 --height 16 --format pfm --out " + (out / "a").string());
    const Result b = runCli("render " + kCornell + " --spp 4 --width 16 --height 16 --format pfm --light-pos -0.4,0.7,0.3 --out " +
                            (out / "b").string());
    ASSERT_EQ(a.code, 0) << a.output;
    ASSERT_EQ(b.code, 0) << b.output;
    const rrf::Image ia = rrf::readImage((out / "a" / "direct.pfm").string());
    const rrf::Image ib = rrf::readImage((out / "b" / "direct.pfm").string());
    EXPECT_NE(ia.data, ib.data);
    std::ifstream meta(out / "b" / "render.json");
    const nlohmann::json j = nlohmann::json::parse(meta);
    EXPECT_NEAR(j.at("light_position")[0].get<double>(), -0.4, 1e-6);
    fs::remove_all(out);
}

TEST(CliRender, BadInputsExitNonZeroWithAClearMessage) {
    const fs::path dir = tempDir("bad");
    const std::string out = " --out " + (dir / "out").string();
    struct Case {
        std::string args, expect;
    };
    {
        std::ofstream(dir / "broken.json") << "{ \"shapes\": [ }";
    }
    const Case cases[] = {
        {"render " + (dir / "missing.json").string() + out, "missing.json"},
        {"render " + (dir / "broken.json").string() + out, "broken.json"},
        {"render " + kCornell + " --light-pos 1,2" + out, "--light-pos"},
        {"render " + kCornell + " --light-pos a,b,c" + out, "--light-pos"},
        {"render " + kCornell + " --format tiff" + out, "--format"},
        {"render " + kCornell + " --spp -3" + out, "--spp"},
        {"render " + kCornell + " --estimator fast" + out, "--estimator"},
        {"render " + kCornell, "--out"},
        {"frobnicate", "frobnicate"},
    };
    for (const Case& c : cases) {
        const Result r = runCli(c.args);
        EXPECT_NE(r.code, 0) << c.args;
        EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << "\n" << r.output;
        EXPECT_EQ(r.output.find("terminate called"), std::string::npos) << r.output;
    }
    EXPECT_FALSE(fs::exists(dir / "out" / "global.exr"));
    fs::remove_all(dir);
}

TEST(CliFlags, BadSettingValuesNameTheirFlag) {
    const fs::path dir = tempDir("flags");
    const std::string out = " --out " + (dir / "out").string();
    struct Case {
        std::string args, expect;
    };
    const Case cases[] = {
        // Typed flags, checked by CLI11 while parsing.
        {"render " + kCornell + " --light-pos nan,1,1" + out, "--light-pos"},
        {"render " + kCornell + " --light-pos 1,2,3,4" + out, "--light-pos"},
        {"generate " + kCornell + " --grid 4,4" + out, "--grid"},
        {"generate " + kCornell + " --grid 4x100" + out, "--grid"},
        {"generate " + kCornell + " --grid 4.5,4,4" + out, "--grid"},
        {"generate " + kCornell + " --shard 1" + out, "--shard"},
        {"train " + kCornell + " --data x.rrfd --hidden 20,x" + out, "--hidden"},
        {"train " + kCornell + " --data x.rrfd --hidden 20-10" + out, "--hidden"},
        {"train " + kCornell + " --data x.rrfd --hidden 0" + out, "--hidden"},
        {"pipeline " + kCornell + " --grid 5" + out, "--grid"},
        {"sweep " + kCornell + " --what depth" + out, "--what"},
        // Checked by core, which names the setting ("shard", "sweep values"); the CLI names the flag.
        {"generate " + kCornell + " --shard 3/3" + out, "--shard"},
        {"sweep " + kCornell + " --what grid --values 4x100" + out, "--values"},
        {"sweep " + kCornell + " --what grid --values 4,4" + out, "--values"},
        {"sweep " + kCornell + " --what hidden --values 10-5" + out, "--values"},
        {"sweep " + kCornell + " --what spp --values 1,4,16" + out, "--values"},
        {"sweep " + kCornell + " --what trainer --values lm sgd" + out, "--values"},
    };
    for (const Case& c : cases) {
        const Result r = runCli(c.args);
        EXPECT_NE(r.code, 0) << c.args << "\n" << r.output;
        EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << "\n" << r.output;
        EXPECT_EQ(r.output.find("terminate called"), std::string::npos) << r.output;
        // Core's names for settings stay inside: the user reads the flag.
        EXPECT_EQ(r.output.find("sweep values"), std::string::npos) << r.output;
    }
    // Every value is read before anything runs: no reference was rendered, nothing was written.
    EXPECT_FALSE(fs::exists(dir / "out"));
    fs::remove_all(dir);
}

TEST(CliFlags, BadShardIsRefusedBeforeGenerating) {
    const fs::path dir = tempDir("shard");
    const Result r = runCli("generate " + kCornell + " --shard 3/2 --out " + (dir / "d.rrfd").string());
    EXPECT_NE(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("--shard"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("100%"), std::string::npos) << "no generation ran before the refusal:\n" << r.output;
    EXPECT_EQ(r.output.find(" records"), std::string::npos) << r.output;
    fs::remove_all(dir);
}

TEST(CliFlags, HelpStatesOneSpellingPerSetting) {
    const Result generate = runCli("generate --help");
    EXPECT_NE(generate.output.find("NX,NY,NZ"), std::string::npos) << generate.output;
    const Result train = runCli("train --help");
    EXPECT_NE(train.output.find("20,10"), std::string::npos) << train.output;
    const Result sweep = runCli("sweep --help");
    EXPECT_NE(sweep.output.find("5 10,5 20,10"), std::string::npos) << sweep.output;
    EXPECT_NE(sweep.output.find("2,2,2 4,4,4"), std::string::npos) << sweep.output;
}

}  // namespace test_cli_render
