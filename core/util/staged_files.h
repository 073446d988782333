#pragma once
/// Files written into a staging directory that is swapped into place as a whole
/// (core/util/directory_replace.h). Inside a private staging directory no reader can see a partial
/// file, so a member needs neither its own temporary name nor its own fsync and rename: it is
/// written plainly, and the directory's files are made durable together, once, just before the
/// swap. Saving a set then costs its bytes plus one flush of them, not two fsyncs per file (a model
/// set of many leaves took seconds of fsyncs for kilobytes of data, issue 29).

#include <string>

namespace rrf {

/// Writes `bytes` to `path` (a file inside a staging directory) without syncing it; crash point
/// "commit <file name>" (core/util/temp_files.h) after the write, as AtomicFile has before its
/// rename. Throws OutputError naming `path` on failure.
void writeStagedFile(const std::string& path, const std::string& bytes);

/// Makes every regular file directly in `dir`, and the directory's entries, durable: the files'
/// fsyncs run concurrently (a journalling file system commits them together), then one fsync of
/// the directory. A file whose data cannot be flushed (an I/O error, a full disk or quota that
/// shows only now) throws OutputError naming it, as AtomicFile::commit does, so the set is not
/// swapped in; the directory's own fsync is best effort (syncDirectory).
void syncStagedDirectory(const std::string& dir);

/// Test seam: what syncStagedDirectory calls to flush one file (`fd` open read-only on `path`):
/// 0 on success, else -1 with errno set, as fsync(2). A failing flush (EIO, ENOSPC) cannot be
/// provoked on a healthy disk, so tests install one that fails for a chosen member. Null (the
/// default) restores fsync. Set it only while no sync runs.
using StagedFileFlush = int (*)(int fd, const char* path);
void setStagedFileFlushForTesting(StagedFileFlush flush);

}  // namespace rrf
