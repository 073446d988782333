#include "panels/log.h"

#include <chrono>
#include <cstdio>

namespace rrf::panels {

namespace log_detail {
namespace {
double nowSeconds() {
    using namespace std::chrono;
    return duration<double>(steady_clock::now().time_since_epoch()).count();
}
// Bounded so that a job that reports in a tight loop cannot grow the log without limit.
constexpr size_t kMaxEntries = 5000;
}  // namespace
}  // namespace log_detail

Log::Log() : start_(log_detail::nowSeconds()) {}

void Log::add(LogLevel level, const std::string& text) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (entries_.size() >= log_detail::kMaxEntries)
        entries_.erase(entries_.begin(), entries_.begin() + log_detail::kMaxEntries / 10);
    entries_.push_back({level, log_detail::nowSeconds() - start_, text});
    ++revision_;
    if (level == LogLevel::Error) ++errors_;
}

std::vector<LogEntry> Log::entries() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return entries_;
}

uint64_t Log::revision() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return revision_;
}

size_t Log::errorCount() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return errors_;
}

void Log::clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.clear();
    errors_ = 0;
    ++revision_;
}

std::string Log::text() const {
    std::string out;
    char stamp[48];
    for (const LogEntry& e : entries()) {
        std::snprintf(stamp, sizeof stamp, "[%8.2f s] %s: ", e.time, logLevelName(e.level));
        out += stamp;
        out += e.text;
        out += '\n';
    }
    return out;
}

const char* logLevelName(LogLevel level) {
    switch (level) {
        case LogLevel::Info: return "info";
        case LogLevel::Warning: return "warning";
        case LogLevel::Error: return "error";
    }
    return "info";
}

}  // namespace rrf::panels
