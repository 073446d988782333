#pragma once
/// recent.json, the workbench's list of recently opened projects (app/gui/user_config.h): a JSON
/// array of absolute paths, most recent first.

#include <cstddef>
#include <string>
#include <vector>

namespace rrf {

/// The paths of `file` that are strings, at most `maxPaths`, in order (other entries are skipped:
/// the list is only a convenience). Throws InputError naming the file when it is unreadable, not
/// JSON or not an array.
std::vector<std::string> readRecentProjectsFile(const std::string& file, size_t maxPaths);
/// Writes `paths` to `file` atomically; throws std::runtime_error naming it on failure.
void writeRecentProjectsFile(const std::string& file, const std::vector<std::string>& paths);

}  // namespace rrf
