// The memory budget's sources (core/util/memory_budget.h, issue 31): MemAvailable, the memory limit
// of the process's cgroup and of the cgroups above it (v2 memory.max, "max" = none; v1
// memory.limit_in_bytes), less what the cgroup has charged but could reclaim, and rlimits. Each
// case is a directory tree standing in for /proc and /sys/fs/cgroup (the budget's injectable root).

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <sys/resource.h>
#include <unistd.h>

#include "core/util/memory_budget.h"

namespace test_memory_budget {

using namespace rrf;
namespace fs = std::filesystem;

namespace {

constexpr uint64_t kMiB = 1024 * 1024;
constexpr uint64_t kNone = std::numeric_limits<uint64_t>::max();

/// A fake root with /proc/meminfo (MemAvailable `availableKiB`) and /proc/self/cgroup `cgroupLines`.
struct FakeRoot {
    fs::path dir;
    FakeRoot(uint64_t availableKiB, const std::string& cgroupLines) {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = fs::temp_directory_path() / ("rrf_memory_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir / "proc/self");
        std::ofstream(dir / "proc/meminfo") << "MemTotal:       67108864 kB\nMemFree:         1000 kB\nMemAvailable:   "
                                            << availableKiB << " kB\n";
        std::ofstream(dir / "proc/self/cgroup") << cgroupLines;
    }
    ~FakeRoot() { fs::remove_all(dir); }
    /// Writes `text` to <root>/sys/fs/cgroup/<relative>, creating its directories.
    void put(const std::string& relative, const std::string& text) const {
        const fs::path p = dir / "sys/fs/cgroup" / relative;
        fs::create_directories(p.parent_path());
        std::ofstream(p) << text;
    }
    std::string root() const { return dir.string(); }
};

/// What the process's own rlimits allow (they take part in every budget).
uint64_t rlimits() {
    uint64_t m = kNone;
    for (int r : {RLIMIT_AS, RLIMIT_DATA}) {
        rlimit l{};
        if (::getrlimit(r, &l) == 0 && l.rlim_cur != RLIM_INFINITY) m = std::min<uint64_t>(m, l.rlim_cur);
    }
    return m;
}

}  // namespace

TEST(MemoryBudget, CgroupV2LimitLessReclaimableUsageBoundsTheBudget) {
    // A Slurm-like job: the step's own cgroup is unlimited, the job's above it allows 1 GiB, of
    // which 300 MiB are charged, 100 MiB of them inactive page cache the kernel would reclaim.
    const FakeRoot f(8 * 1024 * 1024, "0::/job/step\n");
    f.put("cgroup.controllers", "cpu memory\n");
    f.put("job/memory.max", "1073741824\n");
    f.put("job/memory.current", std::to_string(300 * kMiB) + "\n");
    f.put("job/memory.stat", "anon 209715200\nfile 104857600\ninactive_file " + std::to_string(100 * kMiB) + "\n");
    f.put("job/step/memory.max", "max\n");
    f.put("job/step/memory.current", std::to_string(300 * kMiB) + "\n");
    EXPECT_EQ(cgroupMemoryRoomBytes(f.root()), 1024 * kMiB - 200 * kMiB);
    EXPECT_EQ(availableMemoryBytes(f.root()), std::min(824 * kMiB, rlimits()));

    // A tighter limit further down wins; a cgroup already over its limit has no room.
    f.put("job/step/memory.max", std::to_string(256 * kMiB) + "\n");
    EXPECT_EQ(cgroupMemoryRoomBytes(f.root()), 0u) << "the step has 300 MiB charged (no reclaimable cache) under 256 MiB";
    f.put("job/step/memory.max", std::to_string(512 * kMiB) + "\n");
    EXPECT_EQ(cgroupMemoryRoomBytes(f.root()), 212 * kMiB);
}

TEST(MemoryBudget, WithoutCgroupLimitsMemAvailableDecides) {
    const FakeRoot f(512 * 1024, "0::/user.slice/session-1.scope\n");
    f.put("cgroup.controllers", "memory\n");
    f.put("user.slice/memory.max", "max\n");
    f.put("user.slice/session-1.scope/memory.max", "max\n");
    EXPECT_EQ(cgroupMemoryRoomBytes(f.root()), kNone);
    EXPECT_EQ(availableMemoryBytes(f.root()), std::min(512 * kMiB, rlimits()));
    // No cgroup file at all (not Linux, or no access): the same.
    const FakeRoot bare(512 * 1024, "");
    EXPECT_EQ(cgroupMemoryRoomBytes(bare.root()), kNone);
}

TEST(MemoryBudget, ContainerSeeingItsCgroupAsTheMountRootIsLimitedByIt) {
    // Docker without a cgroup namespace: /proc/self/cgroup names /docker/<id>, but the container's
    // /sys/fs/cgroup is that cgroup itself, so only the mount's root holds the limit.
    const FakeRoot f(64 * 1024 * 1024, "0::/docker/4f1c\n");
    f.put("cgroup.controllers", "memory\n");
    f.put("memory.max", std::to_string(2048 * kMiB) + "\n");
    f.put("memory.current", std::to_string(48 * kMiB) + "\n");
    EXPECT_EQ(cgroupMemoryRoomBytes(f.root()), 2000 * kMiB);
}

TEST(MemoryBudget, CgroupV1AndHybridHierarchiesAreReadToo) {
    // v1 memory controller (this development machine's layout) with the v2 hierarchy beside it
    // under /sys/fs/cgroup/unified, which sets no memory limit.
    const FakeRoot f(64 * 1024 * 1024,
                     "9:name=systemd:/\n4:memory:/process_api/abc\n1:cpu,cpuacct:/\n0::/\n");
    f.put("unified/cgroup.procs", "1\n");
    f.put("memory/memory.limit_in_bytes", "9223372036854771712\n");  // v1's "no limit"
    f.put("memory/process_api/abc/memory.limit_in_bytes", std::to_string(512 * kMiB) + "\n");
    f.put("memory/process_api/abc/memory.usage_in_bytes", std::to_string(112 * kMiB) + "\n");
    f.put("memory/process_api/abc/memory.stat", "cache 0\ntotal_inactive_file " + std::to_string(12 * kMiB) + "\n");
    EXPECT_EQ(cgroupMemoryRoomBytes(f.root()), 412 * kMiB);
    // Unlimited at every level: no limit.
    f.put("memory/process_api/abc/memory.limit_in_bytes", "9223372036854771712\n");
    EXPECT_EQ(cgroupMemoryRoomBytes(f.root()), kNone);
}

TEST(MemoryBudget, RequireMemoryUsesTheRootItIsGiven) {
    const FakeRoot f(64 * 1024 * 1024, "0::/small\n");
    f.put("cgroup.controllers", "memory\n");
    f.put("small/memory.max", std::to_string(64 * kMiB) + "\n");
    // Back to the real files however the test ends (the root is process-wide).
    struct Restore {
        ~Restore() { setMemoryInfoRoot(""); }
    } restore;
    setMemoryInfoRoot(f.root());
    EXPECT_EQ(availableMemoryBytes(), std::min(64 * kMiB, rlimits()));
    try {
        requireMemory(100 * kMiB, "a test estimate", "input.json", "/where");
        ADD_FAILURE() << "100 MiB accepted under a 64 MiB cgroup";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("input.json: /where: needs about 100 MiB of memory (a test estimate), but only 64 MiB"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace test_memory_budget
