#include "core/util/memory_budget.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include <sys/resource.h>

#include "core/util/error.h"

namespace rrf {

namespace {
constexpr uint64_t kUnknown = std::numeric_limits<uint64_t>::max();

uint64_t memAvailable() {
    std::ifstream in("/proc/meminfo");
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
}  // namespace

uint64_t availableMemoryBytes() {
    return std::min({memAvailable(), limitOf(RLIMIT_AS), limitOf(RLIMIT_DATA)});
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

uint64_t saturatingProduct(uint64_t a, uint64_t b, uint64_t c) {
    uint64_t ab = 0, abc = 0;
    if (__builtin_mul_overflow(a, b, &ab) || __builtin_mul_overflow(ab, c, &abc)) return kUnknown;
    return abc;
}

}  // namespace rrf
