#include "app/gui/user_config.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "core/util/atomic_file.h"
#include "core/util/json_reader.h"

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
        const nlohmann::json j = readJsonFile(file_);
        const JsonReader list(j, file_);
        const size_t n = list.requireArray();
        // Entries that are not strings are skipped: the list is only a convenience.
        for (size_t i = 0; i < n && paths_.size() < kMaxRecent; ++i)
            if (list.at(i).value().is_string()) paths_.push_back(list.at(i).string());
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
        writeFileAtomically(file_, nlohmann::json(paths_).dump(2) + "\n");
        return true;
    } catch (const std::exception&) {
        return false;
    }
}

}  // namespace rrf
