#include "app/gui/user_workspace.h"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace rrf {

namespace fs = std::filesystem;

std::string userDataDir() {
    const char* xdg = std::getenv("XDG_DATA_HOME");
    if (xdg && *xdg) return (fs::path(xdg) / "rrf-workbench").string();
    const char* home = std::getenv("HOME");
    if (home && *home) return (fs::path(home) / ".local" / "share" / "rrf-workbench").string();
    return (fs::temp_directory_path() / "rrf-workbench-data").string();
}

std::string userWorkspaceProject(const std::string& bundledProjectFile, bool& created) {
    created = false;
    const fs::path bundled = fs::absolute(bundledProjectFile);
    const fs::path source = bundled.parent_path();
    const fs::path target = fs::path(userDataDir()) / "projects" / source.filename();
    const fs::path project = target / bundled.filename();
    std::error_code ec;
    if (fs::exists(project, ec)) return project.string();
    // Copied into a fresh sibling first and renamed into place, so an interrupted first start never
    // leaves a half-copied project that later starts would open as it is.
    const fs::path staging = target.parent_path() / (source.filename().string() + ".partial");
    fs::remove_all(staging, ec);
    fs::create_directories(staging.parent_path(), ec);
    if (!ec) fs::copy(source, staging, fs::copy_options::recursive, ec);
    if (!ec) fs::rename(staging, target, ec);
    if (ec) {
        const std::string why = ec.message();  // before the clean-up reuses an error code
        std::error_code cleanup;
        fs::remove_all(staging, cleanup);
        throw std::runtime_error("cannot copy the bundled project " + source.string() + " into the workspace " +
                                 target.string() + ": " + why);
    }
    created = true;
    return project.string();
}

}  // namespace rrf
