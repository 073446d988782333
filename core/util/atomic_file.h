#pragma once
/// Atomic file output: data is written to a temporary file in the destination directory, flushed to
/// disk and renamed over the destination, so readers see either the old file or the complete new
/// one — never a partial file that looks complete. The temporary file is named after the writer's
/// pid (core/util/temp_files.h): a write removes the temporaries that killed writers of the same
/// target left behind, and the CLI's second Ctrl-C unlinks the ones in flight.

#include <cstdio>
#include <string>

#include "core/util/temp_files.h"  // removeInFlightTemporaryFiles, for signal handlers

namespace rrf {

class AtomicFile {
public:
    /// Removes stale temporaries of `path` (dead writers), then opens `<path>.<pid>.<counter>.tmp`
    /// for binary writing. Throws std::runtime_error on failure.
    explicit AtomicFile(std::string path);
    /// Removes the temporary file unless commit() succeeded.
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    /// Appends bytes; throws std::runtime_error (naming the file) on a short write.
    void write(const void* data, size_t bytes);
    void write(const std::string& s) { write(s.data(), s.size()); }
    /// Flushes, fsyncs and renames onto the destination (crash point "commit <file name>" just
    /// before the rename). Throws on failure.
    void commit();

    const std::string& path() const { return path_; }
    const std::string& tempPath() const { return temp_; }
    std::FILE* handle() { return file_; }

private:
    std::string path_, temp_;
    std::FILE* file_ = nullptr;
    bool committed_ = false;
    int slot_ = -1;  ///< registerTemporaryFile's slot of temp_
};

/// Writes `bytes` to `path` atomically.
void writeFileAtomically(const std::string& path, const std::string& bytes);

/// Reads a whole file; throws std::runtime_error naming the file if it cannot be read.
std::string readFile(const std::string& path);

}  // namespace rrf
