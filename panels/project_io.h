#pragma once
/// Loading a project into the workbench state and saving it back. No GL or window code, so the
/// save → reopen round trip is testable without a display.

#include <string>

#include "panels/workbench_state.h"

namespace rrf::panels {

/// Loads `path` (project or bare scene). On success replaces the state's project, clears dirty and
/// the images, logs the loader's warnings, and returns true. A file that does not load (unreadable,
/// malformed JSON, a bad value in a settings section) leaves the state untouched (the open project
/// is not lost), puts the message (file, JSON pointer, what was expected) in `error` and returns false.
bool loadProjectIntoState(WorkbenchState& state, const std::string& path, std::string& error);

/// Saves the project atomically to `path`. On success clears dirty; on failure leaves the state as
/// it was and returns false with `error` set.
bool saveStateToProject(WorkbenchState& state, const std::string& path, std::string& error);

/// Copies what the workbench keeps outside the project (the views' exposure) into it, so that the
/// project is what a save would write (for autosave copies and tests).
void storeWorkbenchSections(WorkbenchState& state);

}  // namespace rrf::panels
