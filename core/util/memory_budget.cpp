#include "core/util/memory_budget.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <optional>
#include <sstream>

#include <sys/resource.h>

#include "core/util/error.h"

namespace rrf {

namespace {
constexpr uint64_t kUnknown = std::numeric_limits<uint64_t>::max();
/// cgroup v1 writes "no limit" as the largest page-aligned int64 (9223372036854771712); any limit
/// from 2^62 bytes up is taken for none.
constexpr uint64_t kNoLimitFrom = uint64_t(1) << 62;

uint64_t memAvailable(const std::string& root) {
    std::ifstream in(root + "/proc/meminfo");
    std::string key;
    uint64_t kib = 0;
    std::string unit;
    while (in >> key >> kib) {
        std::getline(in, unit);
        if (key == "MemAvailable:") return kib * 1024;
    }
    return kUnknown;
}

uint64_t limitOf(int resource) {
    struct rlimit r {};
    if (::getrlimit(resource, &r) != 0 || r.rlim_cur == RLIM_INFINITY) return kUnknown;
    return uint64_t(r.rlim_cur);
}

/// The first word of a one-value file (memory.max, memory.current, ...), if it can be read.
std::optional<std::string> firstWordOf(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::string word;
    if (!(in >> word)) return std::nullopt;
    return word;
}

std::optional<uint64_t> parseCount(const std::optional<std::string>& word) {
    if (!word || word->empty() || word->find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
    errno = 0;
    const unsigned long long v = std::strtoull(word->c_str(), nullptr, 10);
    if (errno == ERANGE) return kUnknown;
    return uint64_t(v);
}

/// The value of `key` in a "key value" per line file (memory.stat), 0 when absent.
uint64_t memoryStatValue(const std::filesystem::path& file, const std::string& key) {
    std::ifstream in(file);
    std::string k;
    uint64_t v = 0;
    while (in >> k >> v)
        if (k == key) return v;
    return 0;
}

/// Room under the limits of cgroup `path` (as /proc/self/cgroup names it) and its ancestors, in
/// the hierarchy mounted at `mount`. `limitFile`, `usageFile`, `inactiveKey`: v2's or v1's names.
/// A directory of the path that does not exist under the mount (a container that sees its own
/// cgroup as the mount's root without a cgroup namespace) is skipped, so the walk still reaches it.
uint64_t roomUnderCgroup(const std::filesystem::path& mount, const std::string& path, const char* limitFile, const char* usageFile,
                   const char* inactiveKey) {
    uint64_t room = kUnknown;
    std::filesystem::path rel = std::filesystem::path(path).relative_path();
    for (;;) {
        const std::filesystem::path dir = mount / rel;
        const std::optional<uint64_t> limit = parseCount(firstWordOf(dir / limitFile));  // "max" reads as none
        if (limit && *limit < kNoLimitFrom) {
            const uint64_t usage = parseCount(firstWordOf(dir / usageFile)).value_or(0);
            const uint64_t inactive = memoryStatValue(dir / "memory.stat", inactiveKey);
            const uint64_t charged = usage > inactive ? usage - inactive : 0;
            room = std::min(room, *limit > charged ? *limit - charged : 0);
        }
        if (rel.empty()) break;
        rel = rel.parent_path();
    }
    return room;
}

std::mutex g_memoryRootMutex;
std::optional<std::string> g_memoryRoot;  ///< set by setMemoryInfoRoot, or from the environment at first use

std::string currentRoot() {
    const std::lock_guard<std::mutex> lock(g_memoryRootMutex);
    if (!g_memoryRoot) {
        const char* env = std::getenv("RRF_MEMORY_INFO_ROOT");
        g_memoryRoot = env ? env : "";
    }
    return *g_memoryRoot;
}
}  // namespace

uint64_t cgroupMemoryRoomBytes(const std::string& root) {
    std::ifstream in(root + "/proc/self/cgroup");
    uint64_t room = kUnknown;
    const std::filesystem::path fsRoot = root + "/sys/fs/cgroup";
    for (std::string line; std::getline(in, line);) {
        // "<hierarchy id>:<controllers>:<path>"; v2 is "0::<path>", v1's memory controller "<n>:memory:<path>".
        const size_t a = line.find(':'), b = a == std::string::npos ? a : line.find(':', a + 1);
        if (b == std::string::npos) continue;
        const std::string id = line.substr(0, a), controllers = line.substr(a + 1, b - a - 1), path = line.substr(b + 1);
        if (id == "0" && controllers.empty()) {
            // The unified hierarchy is /sys/fs/cgroup itself, or /sys/fs/cgroup/unified on hybrid systems.
            std::error_code ec;
            const std::filesystem::path mount =
                std::filesystem::exists(fsRoot / "cgroup.controllers", ec) ? fsRoot : fsRoot / "unified";
            room = std::min(room, roomUnderCgroup(mount, path, "memory.max", "memory.current", "inactive_file"));
        } else if (("," + controllers + ",").find(",memory,") != std::string::npos) {
            room = std::min(room, roomUnderCgroup(fsRoot / "memory", path, "memory.limit_in_bytes", "memory.usage_in_bytes",
                                            "total_inactive_file"));
        }
    }
    return room;
}

uint64_t availableMemoryBytes(const std::string& root) {
    return std::min({memAvailable(root), cgroupMemoryRoomBytes(root), limitOf(RLIMIT_AS), limitOf(RLIMIT_DATA)});
}

uint64_t availableMemoryBytes() { return availableMemoryBytes(currentRoot()); }

void setMemoryInfoRoot(const std::string& root) {
    const std::lock_guard<std::mutex> lock(g_memoryRootMutex);
    g_memoryRoot = root;
}

std::string formatBytes(uint64_t bytes) {
    static const char* const kUnits[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    if (bytes < 1024) return std::to_string(bytes) + " bytes";
    double v = double(bytes);
    int unit = -1;
    while (v >= 1024 && unit < 5) {
        v /= 1024;
        ++unit;
    }
    char buf[32];
    std::snprintf(buf, sizeof buf, v < 10 ? "%.1f %s" : "%.0f %s", v, kUnits[unit]);
    return buf;
}

std::string memoryShortfall(uint64_t estimate, uint64_t available, const std::string& what) {
    if (estimate <= available) return "";
    return "needs about " + formatBytes(estimate) + " of memory (" + what + "), but only " + formatBytes(available) +
           " is available";
}

void requireMemory(uint64_t estimate, const std::string& what, const std::string& file, const std::string& where) {
    const std::string why = memoryShortfall(estimate, availableMemoryBytes(), what);
    if (!why.empty()) throw InputError(file, where, why);
}

void requireDecodeMemory(int64_t width, int64_t height, int64_t decoderBytesPerPixel, const std::string& file) {
    const uint64_t perPixel = uint64_t(std::max<int64_t>(decoderBytesPerPixel, 0) + 12);
    const uint64_t pixels = saturatingProduct(uint64_t(std::max<int64_t>(width, 0)), uint64_t(std::max<int64_t>(height, 0)));
    requireMemory(saturatingProduct(pixels, perPixel),
                  "decoding " + std::to_string(width) + " x " + std::to_string(height) + " pixels x " + std::to_string(perPixel) +
                      " bytes",
                  file, "");
}

uint64_t saturatingProduct(uint64_t a, uint64_t b, uint64_t c) {
    uint64_t ab = 0, abc = 0;
    if (__builtin_mul_overflow(a, b, &ab) || __builtin_mul_overflow(ab, c, &abc)) return kUnknown;
    return abc;
}

}  // namespace rrf
