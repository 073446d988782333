#include "core/util/temp_files.h"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <signal.h>
#include <unistd.h>

namespace rrf {

namespace fs = std::filesystem;

namespace {

std::atomic<unsigned> g_counter{0};

std::string uniqueTag() { return std::to_string(::getpid()) + "." + std::to_string(g_counter++); }

/// Parses "<pid>.<n>.<suffix>" (the part after the target's name and a dot); -1 if it is not one.
long parseTag(const std::string& s, const std::vector<std::string>& suffixes) {
    const size_t a = s.find('.');
    if (a == 0 || a == std::string::npos) return -1;
    const size_t b = s.find('.', a + 1);
    if (b == a + 1 || b == std::string::npos) return -1;
    for (size_t i = 0; i < b; ++i)
        if (i != a && (s[i] < '0' || s[i] > '9')) return -1;
    bool known = false;
    for (const std::string& x : suffixes) known = known || s.compare(b + 1, std::string::npos, x) == 0;
    // More than 9 digits cannot be a pid (pid_max is at most 2^22) and would not fit a long safely.
    if (!known || a > 9) return -1;
    return std::strtol(s.substr(0, a).c_str(), nullptr, 10);
}

// ---- registry of in-flight temporary files ----------------------------------------------------

/// Slots hold copies of the paths (a signal handler must not touch memory a thread may be freeing).
/// state: 0 free, 1 being filled or emptied, 2 holds a path.
constexpr int kSlots = 32;
constexpr size_t kPathMax = 4096;
struct Slot {
    std::atomic<int> state{0};
    char path[kPathMax];
};
Slot g_slots[kSlots];

}  // namespace

std::string temporaryFileFor(const std::string& target) { return target + "." + uniqueTag() + ".tmp"; }

std::string temporaryDirectoryFor(const std::string& target, const char* suffix) {
    const fs::path p(target);
    return (p.parent_path() / ("." + p.filename().string() + "." + uniqueTag() + "." + suffix)).string();
}

long temporaryOwnerPid(const std::string& entry, const std::string& targetName, const std::vector<std::string>& suffixes) {
    if (entry.size() > targetName.size() + 1 && entry.compare(0, targetName.size(), targetName) == 0 &&
        entry[targetName.size()] == '.')
        return parseTag(entry.substr(targetName.size() + 1), suffixes);
    const std::string hidden = "." + targetName;
    if (entry.size() > hidden.size() + 1 && entry.compare(0, hidden.size(), hidden) == 0 && entry[hidden.size()] == '.')
        return parseTag(entry.substr(hidden.size() + 1), suffixes);
    return -1;
}

std::string temporaryFileTarget(const std::string& name) {
    const size_t n = name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0 ? name.rfind('.', name.size() - 5)
                                                                                        : std::string::npos;
    if (n == std::string::npos || n == 0) return "";
    const size_t pid = name.rfind('.', n - 1);
    if (pid == std::string::npos || pid == 0) return "";
    const std::string base = name.substr(0, pid);
    return temporaryOwnerPid(name, base, {"tmp"}) >= 0 ? base : "";
}

bool processAlive(long pid) {
    if (pid <= 0) return false;
    return ::kill(pid_t(pid), 0) == 0 || errno != ESRCH;
}

int removeStaleTemporaryFiles(const std::string& target) {
    const fs::path p(target);
    const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    const std::string name = p.filename().string();
    int removed = 0;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string entry = it->path().filename().string();
        // Only the file form `<name>.<pid>.<n>.tmp` (a directory's temporaries are `.<name>.…`).
        if (entry.compare(0, name.size(), name) != 0) continue;
        const long pid = entry.size() > name.size() + 1 && entry[name.size()] == '.'
                             ? parseTag(entry.substr(name.size() + 1), {"tmp"})
                             : -1;
        if (pid < 0 || processAlive(pid)) continue;
        std::error_code ignore;
        if (fs::remove(it->path(), ignore)) ++removed;
    }
    return removed;
}

int registerTemporaryFile(const std::string& path) {
    if (path.size() >= kPathMax) return -1;
    for (int i = 0; i < kSlots; ++i) {
        int expected = 0;
        if (!g_slots[i].state.compare_exchange_strong(expected, 1)) continue;
        std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
        g_slots[i].state.store(2);
        return i;
    }
    return -1;
}

void unregisterTemporaryFile(int slot) {
    if (slot < 0 || slot >= kSlots) return;
    g_slots[slot].state.store(1);
    g_slots[slot].path[0] = '\0';
    g_slots[slot].state.store(0);
}

void removeInFlightTemporaryFiles() noexcept {
    for (Slot& s : g_slots)
        if (s.state.load() == 2) ::unlink(s.path);
}

void crashPoint(const std::string& step) {
    const char* at = std::getenv("RRF_KILL_AT");
    if (at && step == at) std::raise(SIGKILL);
}

}  // namespace rrf
