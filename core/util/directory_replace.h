#pragma once
/// Replacing a directory of files that belong together (a model set, a render's images and their
/// metadata, a reference-store entry) as a whole: the new set is written into a temporary sibling
/// directory and swapped with the old one by a single rename, so a reader — or a writer killed at
/// any step, or a full disk — leaves either the complete old set or the complete new one, never a
/// mixture of both.
///
/// Steps (each a crash point of core/util/temp_files.h, for tests):
///   1. leftovers of killed writers of the same target are removed (a directory swapped out by the
///      two-rename fallback below is put back first if the target is missing);
///   2. `fill` writes the new set into `.<name>.<pid>.<n>.tmp` beside the target (plainly, with
///      core/util/staged_files.h's writeStagedFile: every file there is fsynced, together, before step 4);
///   3. entries of the old directory that are not members of the set (a user's notes, another
///      program's output) are hard-linked (copied where links fail) into the new one, so replacing
///      the set never deletes them;                                        — "replace <name>: before swap"
///   4. renameat2(RENAME_EXCHANGE) swaps the two directories atomically; where the file system
///      cannot exchange, the old one is renamed aside and the new one into place ("between
///      renames"), and a failed second rename puts the old one back;        — "replace <name>: after swap"
///   5. the old set, now at the temporary name, is removed.

#include <functional>
#include <string>

namespace rrf {

/// Replaces directory `target` (created with its parents if missing) with the set `fill` writes
/// into the directory whose path it is given. `isMember(name)` says whether an entry of the old
/// directory belongs to the set (and is dropped) rather than being kept. Throws std::runtime_error
/// naming the directory if the target is not a directory, is the current working directory or
/// contains it (it cannot be swapped away under the process), or a step fails; the old set is then
/// untouched. What `fill` throws propagates after the temporary directory is removed, its message
/// naming the target instead of the temporary directory (`out/gt/global.exr: write failed: No
/// space left on device; the previous contents of 'out/gt' are kept`): OutputError and InputError
/// keep their type, other std::runtime_errors become std::runtime_error and std::invalid_arguments
/// std::invalid_argument, anything else is rethrown as it is. The parent directory is fsynced after
/// the swap (core/util/atomic_file.h's syncDirectory).
void replaceDirectory(const std::string& target, const std::function<bool(const std::string& name)>& isMember,
                      const std::function<void(const std::string& staging)>& fill);

/// Removes the temporary siblings of directory `target` left by writers that are no longer alive,
/// putting back a set that the two-rename fallback had moved aside if the target is missing.
/// Returns how many it removed or restored; never throws.
int removeStaleDirectoryTemporaries(const std::string& target);

}  // namespace rrf
