#pragma once
/// The workbench's message log: informational messages, warnings and errors from the UI thread and
/// from background jobs. Thread-safe, because job workers report while the UI thread draws.

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace rrf::panels {

enum class LogLevel { Info, Warning, Error };

struct LogEntry {
    LogLevel level = LogLevel::Info;
    double time = 0.0;  ///< seconds since the log was created
    std::string text;
};

class Log {
public:
    Log();

    void info(const std::string& text) { add(LogLevel::Info, text); }
    void warning(const std::string& text) { add(LogLevel::Warning, text); }
    void error(const std::string& text) { add(LogLevel::Error, text); }
    void add(LogLevel level, const std::string& text);

    /// A copy of the entries (the UI draws from the copy so workers are never blocked by drawing).
    std::vector<LogEntry> entries() const;
    /// Increases with every message; lets a view scroll to the bottom only when something arrived.
    uint64_t revision() const;
    size_t errorCount() const;
    void clear();
    /// All entries as plain text, one line each ("[12.3 s] error: ..."), for the clipboard.
    std::string text() const;

private:
    mutable std::mutex mutex_;
    std::vector<LogEntry> entries_;
    uint64_t revision_ = 0;
    size_t errors_ = 0;
    double start_ = 0.0;
};

/// "info", "warning" or "error".
const char* logLevelName(LogLevel level);

}  // namespace rrf::panels
