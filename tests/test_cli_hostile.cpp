// Hostile input through the real `rrf` executable (issue 12): each case exits with status 1 and one
// message naming the file or option, the field and the accepted range — never a signal (Embree's
// ray assertion, std::bad_alloc), raw library text, an overwritten input or a run that keeps going
// after Ctrl-C.

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <fcntl.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include "tests/cli_runner.h"

namespace test_cli_hostile {

namespace fs = std::filesystem;
using nlohmann::json;
using rrf::test::runCli;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

fs::path testDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const fs::path dir = fs::temp_directory_path() / ("rrf_cli_hostile_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// A small open room with a point light and the camera at `eye`, written to `dir`/`name`.
std::string writeScene(const fs::path& dir, const std::string& name, const std::string& eye = "[0, 0, 3]") {
    const std::string text = R"({
  "camera": { "eye": )" + eye + R"(, "target": [0, 0, 0], "fov_y": 60, "width": 8, "height": 8 },
  "materials": { "white": { "type": "lambert", "albedo": [0.8, 0.8, 0.8] } },
  "shapes": [
    { "type": "quad", "name": "floor", "material": "white", "corner": [-1, -1, -1], "edge1": [0, 0, 2], "edge2": [2, 0, 0] },
    { "type": "quad", "name": "back", "material": "white", "corner": [-1, -1, -1], "edge1": [2, 0, 0], "edge2": [0, 2, 0] },
    { "type": "quad", "name": "left", "material": "white", "corner": [-1, -1, -1], "edge1": [0, 2, 0], "edge2": [0, 0, 2] }
  ],
  "lights": [ { "type": "point", "name": "bulb", "position": [0, 0.5, 0], "intensity": [2, 2, 2] } ]
})";
    const fs::path p = dir / name;
    std::ofstream(p) << text;
    return p.string();
}

/// `rrf args` with the address space limited to 4 GiB (`ulimit -v`): the memory the process may
/// use is then known whatever machine runs the test.
rrf::test::CliResult runCliWithin4GiB(const std::string& args) {
    const std::string cmd = "ulimit -v 4194304; exec " + std::string(RRF_CLI_PATH) + " " + args + " 2>&1";
    return rrf::test::runShell(cmd);
}

/// `rrf args` on a "disk" of `kib` KiB per file (`ulimit -f`; SIGXFSZ ignored, as a full disk
/// raises none): writes beyond it fail with EFBIG where ENOSPC would.
rrf::test::CliResult runCliOnFullDisk(int kib, const std::string& args) {
    const std::string cmd = "trap '' XFSZ; ulimit -f " + std::to_string(kib) + "; exec " + std::string(RRF_CLI_PATH) + " " + args + " 2>&1";
    return rrf::test::runShell(cmd);
}

}  // namespace

TEST(CliHostile, CoordinatesBeyondTheRayRangeExitWithTheFieldAndRange) {
    const fs::path dir = testDir();
    const std::string far = writeScene(dir, "far.json", "[0, 1, 1e19]");
    const auto eye = runCli("render " + far + " --spp 1 --out " + (dir / "o1").string());
    EXPECT_EQ(eye.code, 1) << eye.output;
    EXPECT_TRUE(contains(eye.output, far + ": /camera/eye: camera eye: z = 1e+19 is outside [-1e+09, 1e+09]")) << eye.output;

    const std::string ok = writeScene(dir, "ok.json");
    const auto light = runCli("render " + ok + " --spp 1 --light-pos 1e30,0,0 --out " + (dir / "o2").string());
    EXPECT_EQ(light.code, 1) << light.output;
    EXPECT_TRUE(contains(light.output, "command line: --light-pos: x = 1e+30 is outside [-1e+09, 1e+09]")) << light.output;
    EXPECT_FALSE(fs::exists(dir / "o2"));
    fs::remove_all(dir);
}

TEST(CliHostile, NumberBeyondDoubleNamesFileAndLine) {
    const fs::path dir = testDir();
    const std::string huge = writeScene(dir, "huge.json", "[0, 1, 1e400]");
    const auto r = runCli("generate " + huge + " --out " + (dir / "d.rrfd").string());
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_TRUE(contains(r.output, huge + ": number 1e400 at line 2, column 29")) << r.output;
    EXPECT_FALSE(contains(r.output, "json.exception")) << r.output;
    fs::remove_all(dir);
}

TEST(CliHostile, OutputThatIsAnInputIsRefusedForEveryCommand) {
    const fs::path dir = testDir();
    const std::string scene = writeScene(dir, "scene.json");
    const std::string before = readText(scene);
    const fs::path data = dir / "data.rrfd";
    std::ofstream(data) << "not read: the output check comes first";
    // The same file under another spelling counts too.
    const std::string sameScene = (dir / "." / "scene.json").string();
    const struct {
        std::string args, out;
    } cases[] = {
        {"generate " + scene + " --grid 1,1,1 --dirs 1 --out " + sameScene, sameScene},
        {"render " + scene + " --spp 1 --out " + scene, scene},
        {"train " + scene + " --data " + data.string() + " --out " + data.string(), data.string()},
        {"merge " + data.string() + " --out " + data.string(), data.string()},
        {"predict " + scene + " --models " + (dir).string() + " --out " + dir.string(), dir.string()},
    };
    for (const auto& c : cases) {
        const auto r = runCli(c.args);
        EXPECT_EQ(r.code, 1) << c.args << "\n" << r.output;
        EXPECT_TRUE(contains(r.output, "command line: --out: '" + c.out + "' is the input")) << c.args << "\n" << r.output;
    }
    EXPECT_EQ(readText(scene), before);
    fs::remove_all(dir);
}

TEST(CliHostile, RequestsBeyondMemoryAreRefusedWithTheEstimate) {
    const fs::path dir = testDir();
    const std::string scene = writeScene(dir, "scene.json");
    const auto image = runCliWithin4GiB("render " + scene + " --spp 1 --width 16384 --height 16384 --out " + (dir / "o").string());
    EXPECT_EQ(image.code, 1) << image.output;
    EXPECT_TRUE(contains(image.output, "command line: --width/--height: a 16384 x 16384 render needs about 100 GiB of memory"))
        << image.output;
    EXPECT_TRUE(contains(image.output, "each 1 ... 16384")) << image.output;
    const auto grid = runCliWithin4GiB("generate " + scene + " --grid 1000,1000,1000 --dirs 1 --out " + (dir / "d.rrfd").string());
    EXPECT_EQ(grid.code, 1) << grid.output;
    EXPECT_TRUE(contains(grid.output, "command line: --grid/--dirs: the run needs about")) << grid.output;
    EXPECT_TRUE(contains(grid.output, "1000000000 cells x 1 directions")) << grid.output;
    EXPECT_FALSE(fs::exists(dir / "d.rrfd"));
    fs::remove_all(dir);
}

TEST(CliHostile, CtrlCStopsOneHugeCellWithinASecond) {
    // One viewpoint with ten million directions: Ctrl-C must not wait for the cell to finish.
    const fs::path dir = testDir();
    const std::string scene = writeScene(dir, "scene.json");
    const std::string out = (dir / "d.rrfd").string();
    const rrf::test::InterruptedRun run =
        rrf::test::interruptCli({"generate", scene, "--grid", "1,1,1", "--dirs", "10000000", "--spp", "1", "--max-spp", "1",
                                 "--out", out},
                                "generate:");
    ASSERT_TRUE(run.started);
    ASSERT_TRUE(run.exited) << "still running a minute after SIGINT: " << run.err;
    const int status = run.status;
    const std::string& err = run.err;
    const double seconds = run.seconds;
    ASSERT_TRUE(WIFEXITED(status)) << err;
    EXPECT_EQ(WEXITSTATUS(status), 130) << err;
    EXPECT_LT(seconds, 1.0) << err;
    EXPECT_FALSE(fs::exists(out));
    fs::remove_all(dir);
}

TEST(CliHostile, FullDiskNamesTheOutputAndWhatWasKeptNeverATemporary) {
    // Issue 31: `rrf render` on a full disk named `/…/.render.32701.0.tmp/global.exr`.
    const fs::path dir = testDir();
    const std::string scene = writeScene(dir, "scene.json");
    const std::string out = (dir / "o").string();
    ASSERT_EQ(runCli("render " + scene + " --spp 2 --out " + out).code, 0);
    const std::string before = readText(dir / "o" / "global.exr");
    const auto render = runCliOnFullDisk(8, "render " + scene + " --spp 2 --width 128 --height 128 --out " + out);
    EXPECT_EQ(render.code, 1) << render.output;
    EXPECT_TRUE(contains(render.output, out + "/global.exr: write failed: File too large; the previous contents of '" + out +
                                            "' are kept"))
        << render.output;
    EXPECT_EQ(readText(dir / "o" / "global.exr"), before);

    const std::string data = (dir / "d.rrfd").string();
    const auto generate = runCliOnFullDisk(4, "generate " + scene + " --grid 2,2,2 --dirs 50 --spp 2 --out " + data);
    EXPECT_EQ(generate.code, 1) << generate.output;
    EXPECT_TRUE(contains(generate.output, data + ": write failed: File too large; no file was created")) << generate.output;
    for (const auto* r : {&render, &generate}) EXPECT_FALSE(contains(r->output, ".tmp")) << r->output;
    for (const auto& e : fs::directory_iterator(dir)) EXPECT_NE(e.path().filename().string()[0], '.') << e.path();
    fs::remove_all(dir);
}

TEST(CliHostile, UnknownKernelIsRefusedBeforeAnyWork) {
    const fs::path dir = testDir();
    const std::string scene = writeScene(dir, "room.json");
    const fs::path out = dir / "out";
    const auto r = rrf::test::runShell("RRF_MLP_KERNEL=sse9 " + std::string(RRF_CLI_PATH) + " pipeline " + scene +
                                       " --preset quick --out " + out.string() + " 2>&1");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_TRUE(contains(r.output, "RRF_MLP_KERNEL=sse9: expected portable, avx2 or avx512")) << r.output;
    EXPECT_FALSE(fs::exists(out)) << "nothing was started";
    // The portable kernel runs everywhere: naming it is accepted.
    const auto ok = rrf::test::runShell("RRF_MLP_KERNEL=portable " + std::string(RRF_CLI_PATH) + " inspect " + scene + " 2>&1");
    EXPECT_EQ(ok.code, 0) << ok.output;
    fs::remove_all(dir);
}

TEST(CliHostile, ObjAndMtlNumbersOutOfRangeExitBeforeAnyWork) {
    const fs::path dir = testDir();
    std::ofstream(dir / "room.mtl") << "newmtl white\nKd 0.8 0.8 0.8\nnewmtl lamp\nKd 0 0 0\nKe 1e30 1e30 1e30\n";
    const std::string obj = "mtllib room.mtl\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv -0.2 1 -0.2\nv 0.2 1 -0.2\n"
                            "v 0.2 1 0.2\nv -0.2 1 0.2\nusemtl white\nf 1 4 3 2\nusemtl lamp\nf 5 6 7 8\n";
    std::ofstream(dir / "room.obj") << obj;
    const fs::path scene = dir / "scene.json";
    std::ofstream(scene) << R"({"camera": {"eye": [0, 0.5, 3], "target": [0, 0.5, 0], "fov_y": 40, "width": 8, "height": 8},
                                "shapes": [{"type": "obj", "file": "room.obj"}]})";
    const auto ke = runCli("render " + scene.string() + " --spp 1 --out " + (dir / "o").string());
    EXPECT_EQ(ke.code, 1) << ke.output;
    EXPECT_TRUE(contains(ke.output, "room.mtl' line 5: material 'lamp': Ke must lie in [0, 1e+10]")) << ke.output;
    EXPECT_FALSE(contains(ke.output, "rendered")) << "refused before the render: " << ke.output;

    std::ofstream(dir / "room.mtl") << "newmtl white\nKd 0.8 0.8 0.8\nnewmtl lamp\nKd 0 0 0\nKe 10 10 10\n";
    std::ofstream(dir / "room.obj") << std::string(obj).replace(obj.find("v 1 0 -1"), 8, "v nan 0 -1");
    const auto nan = runCli("generate " + scene.string() + " --grid 1,1,1 --dirs 4 --out " + (dir / "d.rrfd").string());
    EXPECT_EQ(nan.code, 1) << nan.output;
    EXPECT_TRUE(contains(nan.output, "room.obj' line 3: v x coordinate 'nan' is not a finite number")) << nan.output;
    EXPECT_FALSE(fs::exists(dir / "o"));
    EXPECT_FALSE(fs::exists(dir / "d.rrfd"));
    fs::remove_all(dir);
}

TEST(CliHostile, NonFiniteNumbersOnTheCommandLineAreRefusedBeforeAnyWork) {
    // CLI11 converts "nan" and "inf" to numbers its range checks let through: --exposure nan used to
    // render the whole image before the PNG encoder refused it, naming the temporary directory.
    const fs::path dir = testDir();
    const std::string scene = writeScene(dir, "scene.json");
    const struct {
        std::string args, message;
    } cases[] = {
        {"render " + scene + " --spp 1 --format png --exposure nan --out " + (dir / "o").string(), "--exposure: expected a finite number, got 'nan'"},
        {"reference " + scene + " --noise nan", "--noise: expected a finite number, got 'nan'"},
        {"generate " + scene + " --noise-target inf --out " + (dir / "d.rrfd").string(), "--noise-target: expected a finite number, got 'inf'"},
    };
    for (const auto& c : cases) {
        const auto r = runCli(c.args);
        EXPECT_EQ(r.code, 1) << c.args << "\n" << r.output;
        EXPECT_TRUE(contains(r.output, c.message)) << c.args << "\n" << r.output;
        EXPECT_FALSE(contains(r.output, "rendered")) << r.output;
    }
    EXPECT_FALSE(fs::exists(dir / "o"));
    EXPECT_FALSE(fs::exists(dir / "references"));
    fs::remove_all(dir);
}

TEST(CliHostile, CgroupMemoryLimitBoundsTheRequests) {
    // A container or job limited to 64 MiB by its cgroup (files under RRF_MEMORY_INFO_ROOT, as
    // core/util/memory_budget.h reads them): a render of 2048 x 2048 pixels (1.6 GiB) is refused.
    const fs::path dir = testDir();
    const fs::path root = dir / "root";
    fs::create_directories(root / "proc/self");
    fs::create_directories(root / "sys/fs/cgroup/job");
    std::ofstream(root / "proc/meminfo") << "MemAvailable:   67108864 kB\n";
    std::ofstream(root / "proc/self/cgroup") << "0::/job\n";
    std::ofstream(root / "sys/fs/cgroup/cgroup.controllers") << "memory\n";
    std::ofstream(root / "sys/fs/cgroup/job/memory.max") << 64 * 1024 * 1024 << "\n";
    const std::string scene = writeScene(dir, "scene.json");
    const auto r = rrf::test::runShell("RRF_MEMORY_INFO_ROOT=" + root.string() + " " + RRF_CLI_PATH + " render " + scene +
                                       " --spp 1 --width 2048 --height 2048 --out " + (dir / "o").string() + " 2>&1");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_TRUE(contains(r.output, "a 2048 x 2048 render needs about 1.6 GiB of memory")) << r.output;
    EXPECT_TRUE(contains(r.output, "but only 64 MiB is available")) << r.output;
    fs::remove_all(dir);
}

}  // namespace test_cli_hostile
