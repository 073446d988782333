#pragma once
/// The per-user workspace: where the workbench keeps the projects it opens by itself. A first start
/// without a project argument copies the bundled Cornell box (read-only data, perhaps inside the
/// checkout or an installed tree) into $XDG_DATA_HOME/rrf-workbench/projects/<name>/ (else
/// ~/.local/share/rrf-workbench/...) and opens that copy, so runs, datasets, sweeps and autosaves
/// land in the user's workspace and the bundled project is never edited in place.

#include <string>

namespace rrf {

/// The per-user data directory: $XDG_DATA_HOME/rrf-workbench, else ~/.local/share/rrf-workbench,
/// else <temp>/rrf-workbench-data (not created here).
std::string userDataDir();

/// The workspace copy of the bundled project file `bundledProjectFile` (<dir>/<name>/project.json):
/// <userDataDir>/projects/<name>/<file name>. On first use the bundled project's directory is
/// copied there (every file, recursively) and `created` is set; a copy that exists already is used
/// as it is (the user's work in it is kept). Throws std::runtime_error naming the directory when
/// the copy cannot be made.
std::string userWorkspaceProject(const std::string& bundledProjectFile, bool& created);

}  // namespace rrf
