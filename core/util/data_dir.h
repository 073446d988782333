#pragma once
/// Where the programs (rrf, rrf-workbench, the benchmarks) find their read-only data: the GLSL
/// shaders and the bundled projects. Nothing is compiled in, so a build tree and an installed tree
/// both work from any working directory.
///
/// The data directory holds `shaders/` and `projects/`. It is the first of these that holds both:
///   1. `$RRF_DATA_DIR`, when that variable is set and not empty (then it is the only candidate: an
///      explicit choice that is wrong is reported, never silently replaced by another directory);
///   2. `<executable dir>/share/rrf-workbench` — the build tree, which CMake fills next to the
///      executables at build time (target rrf_data);
///   3. `<executable dir>/../share/rrf-workbench` — an installed tree (`<prefix>/bin/rrf` with
///      `<prefix>/share/rrf-workbench`, as `cmake --install` lays it out).

#include <filesystem>
#include <string>
#include <vector>

namespace rrf {

/// Name of the environment variable that overrides the data directory.
inline constexpr const char* kDataDirVariable = "RRF_DATA_DIR";

/// Directory of the running executable (read from /proc/self/exe), or an empty path where that
/// cannot be read.
std::filesystem::path executableDir();

/// The directories findDataDir() tries, in order: only `envOverride` when it is non-null and not
/// empty, otherwise `exeDir`/share/rrf-workbench and `exeDir`/../share/rrf-workbench (none when
/// `exeDir` is empty).
std::vector<std::filesystem::path> dataDirCandidates(const std::filesystem::path& exeDir, const char* envOverride);

/// True when `dir` holds both a `shaders/` and a `projects/` directory.
bool isDataDir(const std::filesystem::path& dir);

/// The first candidate that is a data directory. Throws std::runtime_error naming every place it
/// looked (and the override variable) when none is.
std::filesystem::path findDataDir(const std::vector<std::filesystem::path>& candidates);

/// The data directory of this process: findDataDir(dataDirCandidates(executableDir(),
/// getenv(RRF_DATA_DIR))). Throws std::runtime_error naming the variable and its value when
/// RRF_DATA_DIR is set to something else than a data directory, or findDataDir's error. Looked up
/// on every call (cheap), so a changed variable takes effect.
std::filesystem::path dataDir();

/// `dataDir()/shaders`.
std::filesystem::path shaderDir();

/// The project file of a bundled project: `dataDir()/projects/<name>/project.json`.
std::filesystem::path bundledProject(const std::string& name);

/// Name of the bundled project the programs open when none is given.
inline constexpr const char* kDefaultProject = "cornell-box";

}  // namespace rrf
