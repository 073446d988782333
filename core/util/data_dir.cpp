#include "core/util/data_dir.h"

#include <cstdlib>
#include <stdexcept>
#include <system_error>

namespace fs = std::filesystem;

namespace rrf {

fs::path executableDir() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (ec || exe.empty()) return {};
    return exe.parent_path();
}

std::vector<fs::path> dataDirCandidates(const fs::path& exeDir, const char* envOverride) {
    if (envOverride && *envOverride) return {fs::path(envOverride)};
    if (exeDir.empty()) return {};
    // lexically_normal turns <prefix>/bin/../share into <prefix>/share, so messages name the real place.
    return {(exeDir / "share" / "rrf-workbench").lexically_normal(),
            (exeDir / ".." / "share" / "rrf-workbench").lexically_normal()};
}

bool isDataDir(const fs::path& dir) {
    std::error_code ec;
    return fs::is_directory(dir / "shaders", ec) && fs::is_directory(dir / "projects", ec);
}

fs::path findDataDir(const std::vector<fs::path>& candidates) {
    for (const fs::path& dir : candidates)
        if (isDataDir(dir)) return dir;
    std::string looked;
    for (const fs::path& dir : candidates) looked += (looked.empty() ? "" : ", ") + dir.string();
    if (looked.empty()) looked = "nowhere: the executable's directory is unknown (/proc/self/exe unreadable)";
    throw std::runtime_error(std::string("no RRF Workbench data directory (one holding shaders/ and projects/); looked in ") +
                             looked + "; set " + kDataDirVariable +
                             " to the share/rrf-workbench directory of a build or an installation");
}

fs::path dataDir() {
    const char* env = std::getenv(kDataDirVariable);
    if (env && *env && !isDataDir(env))
        throw std::runtime_error(std::string(kDataDirVariable) + "=" + env +
                                 ": not an RRF Workbench data directory (expected shaders/ and projects/ in it)");
    return findDataDir(dataDirCandidates(executableDir(), env));
}

fs::path shaderDir() { return dataDir() / "shaders"; }

fs::path bundledProject(const std::string& name) { return dataDir() / "projects" / name / "project.json"; }

}  // namespace rrf
