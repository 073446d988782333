#pragma once
/// Atomic file output: data is written to a temporary file in the destination directory, flushed to
/// disk and renamed over the destination, so readers see either the old file or the complete new
/// one — never a partial file that looks complete. The directory is fsynced after the rename, so
/// the new name survives a power cut too (the rename itself is only durable once its directory is).
/// Errors are OutputErrors (core/util/error.h) that name the destination and what is left there —
/// never the temporary file, a name the user did not choose and will not find. The temporary file is named after the writer's
/// pid (core/util/temp_files.h): a write removes the temporaries that killed writers of the same
/// target left behind, and the CLI's second Ctrl-C unlinks the ones in flight.

#include <cstdio>
#include <string>

#include "core/util/temp_files.h"  // removeInFlightTemporaryFiles, for signal handlers

namespace rrf {

class AtomicFile {
public:
    /// Removes stale temporaries of `path` (dead writers), then opens `<path>.<pid>.<counter>.tmp`
    /// for binary writing. Throws OutputError on failure.
    explicit AtomicFile(std::string path);
    /// Removes the temporary file unless commit() succeeded.
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    /// Appends bytes; throws OutputError (naming the destination) on a short write.
    void write(const void* data, size_t bytes);
    void write(const std::string& s) { write(s.data(), s.size()); }
    /// Flushes, fsyncs and renames onto the destination (crash point "commit <file name>" just
    /// before the rename), then fsyncs the destination's directory. Throws OutputError on failure.
    void commit();

    const std::string& path() const { return path_; }
    const std::string& tempPath() const { return temp_; }
    std::FILE* handle() { return file_; }

private:
    /// Throws OutputError(path_, problem, what the destination holds now).
    [[noreturn]] void fail(const std::string& problem) const;

    std::string path_, temp_;
    std::FILE* file_ = nullptr;
    bool committed_ = false;
    bool existed_ = false;  ///< the destination existed when the write began (what a failure keeps)
    int slot_ = -1;  ///< registerTemporaryFile's slot of temp_
};

/// Makes the entries of directory `dir` (renames into it) durable: fsync of the directory. Returns
/// false where it cannot be opened or synced (some file systems do not support it; callers treat
/// that as best effort: the data itself is already synced).
bool syncDirectory(const std::string& dir);

/// Writes `bytes` to `path` atomically.
void writeFileAtomically(const std::string& path, const std::string& bytes);

/// Reads a whole file; throws std::runtime_error naming the file if it cannot be read.
std::string readFile(const std::string& path);

}  // namespace rrf
