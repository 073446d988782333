#pragma once
/// Per-user workbench settings outside any project: the config directory
/// ($XDG_CONFIG_HOME/rrf-workbench, else ~/.config/rrf-workbench) with imgui.ini and the list of
/// recently opened projects (recent.json, app/gui/recent_projects_file.h).

#include <string>
#include <vector>

namespace rrf {

/// The per-user config directory (not created here).
std::string userConfigDir();

/// Recently opened projects, most recent first, at most `kMaxRecent`.
class RecentProjects {
public:
    static constexpr size_t kMaxRecent = 10;

    explicit RecentProjects(std::string file) : file_(std::move(file)) {}
    /// Reads the list; a missing or damaged file gives an empty list (it is only a convenience).
    void load();
    /// Moves `path` (made absolute) to the front and saves; returns false if saving failed.
    bool add(const std::string& path);
    const std::vector<std::string>& paths() const { return paths_; }

private:
    std::string file_;
    std::vector<std::string> paths_;
};

}  // namespace rrf
