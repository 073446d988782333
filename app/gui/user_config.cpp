#include "app/gui/user_config.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/util/atomic_file.h"

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
    std::ifstream in(file_);
    if (!in) return;
    try {
        const nlohmann::json j = nlohmann::json::parse(in);
        if (!j.is_array()) return;
        for (const auto& p : j)
            if (p.is_string() && paths_.size() < kMaxRecent) paths_.push_back(p.get<std::string>());
    } catch (const std::exception&) {
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
