#pragma once
/// Temporary files and directories of writes in progress: how they are named, how the leftovers of
/// dead processes are found and removed, a registry of the ones in flight that a signal handler can
/// delete, and named crash points that tests use to kill a writer at a chosen step.
///
/// Names carry the writer's pid: a file `<name>.<pid>.<n>.tmp` beside its target, a directory
/// `.<name>.<pid>.<n>.tmp` (or `.old`) beside the directory it replaces. A temporary whose pid is no
/// longer alive belongs to a killed writer; the next write to the same target removes it. A pid
/// that is alive (even if reused by an unrelated process) keeps its temporaries: removing a live
/// writer's file would be worse than leaving a dead one a little longer.

#include <string>
#include <vector>

namespace rrf {

/// The name of a fresh temporary file for `target` (a path): `<target>.<pid>.<n>.tmp`, n counting
/// up within this process.
std::string temporaryFileFor(const std::string& target);

/// The name of a fresh temporary sibling of directory `target` (a path without a trailing
/// separator): `<parent>/.<name>.<pid>.<n>.<suffix>` with suffix "tmp" or "old".
std::string temporaryDirectoryFor(const std::string& target, const char* suffix);

/// The pid in `entry` (a file name) if it is a temporary of `targetName` as named above (file or
/// directory form, any suffix in `suffixes`), else -1.
long temporaryOwnerPid(const std::string& entry, const std::string& targetName, const std::vector<std::string>& suffixes);

/// The target's name if `name` is a temporary file's name (`<target>.<pid>.<n>.tmp`), else "".
std::string temporaryFileTarget(const std::string& name);

/// True if process `pid` exists (kill(pid, 0) does not fail with ESRCH).
bool processAlive(long pid);

/// Removes the temporaries of `target` (file form, suffix "tmp") left in its directory by
/// processes that are no longer alive. Returns how many it removed; never throws (a leftover that
/// cannot be removed is left for the next write).
int removeStaleTemporaryFiles(const std::string& target);

/// Registers a temporary path being written, so removeInFlightTemporaryFiles() can delete it.
/// Returns a slot for unregisterTemporaryFile, or -1 when all slots are taken (the file then is
/// only cleaned up by removeStaleTemporaryFiles after this process has died).
int registerTemporaryFile(const std::string& path);
/// Forgets the path in `slot` (from registerTemporaryFile; -1 is ignored).
void unregisterTemporaryFile(int slot);

/// Unlinks every registered temporary file. Async-signal-safe (atomics and unlink(2) only): the
/// CLI calls it from its signal handler before a second Ctrl-C kills the process, so an interrupt
/// leaves no half-written temporary behind.
void removeInFlightTemporaryFiles() noexcept;

/// A named step of a multi-file write at which a test may kill the process: if the environment
/// variable RRF_KILL_AT equals `step`, the process raises SIGKILL here (no cleanup runs, as with
/// a power cut or `kill -9`). Without the variable this costs one getenv.
void crashPoint(const std::string& step);

}  // namespace rrf
