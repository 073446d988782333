#include "app/gui/user_config.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "app/gui/recent_projects_file.h"
#include "core/util/error.h"

namespace rrf {

namespace fs = std::filesystem;

std::string userConfigDir() {
    const char* xdg = std::getenv("XDG_CONFIG_HOME");
    if (xdg && *xdg) return (fs::path(xdg) / "rrf-workbench").string();
    const char* home = std::getenv("HOME");
    if (home && *home) return (fs::path(home) / ".config" / "rrf-workbench").string();
    return (fs::temp_directory_path() / "rrf-workbench").string();
}

void RecentProjects::load() {
    paths_.clear();
    std::error_code ec;
    if (!fs::exists(file_, ec)) return;
    try {
        // Entries that are not strings are skipped: the list is only a convenience.
        paths_ = readRecentProjectsFile(file_, kMaxRecent);
    } catch (const InputError&) {
        paths_.clear();
    }
}

bool RecentProjects::add(const std::string& path) {
    std::error_code ec;
    const std::string abs = fs::absolute(path, ec).lexically_normal().string();
    paths_.erase(std::remove(paths_.begin(), paths_.end(), abs), paths_.end());
    paths_.insert(paths_.begin(), abs);
    if (paths_.size() > kMaxRecent) paths_.resize(kMaxRecent);
    try {
        fs::create_directories(fs::path(file_).parent_path(), ec);
        writeRecentProjectsFile(file_, paths_);
        return true;
    } catch (const std::exception&) {
        return false;
    }
}

}  // namespace rrf
