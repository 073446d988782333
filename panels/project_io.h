#pragma once
/// Loading a project into the workbench state and saving it back, including the sections the
/// workbench owns: "layout" (pane sizes), "runs" and "scene_overrides". No GL or window code, so the
/// save → reopen round trip is testable without a display.

#include <string>

#include "panels/workbench_state.h"

namespace rrf::panels {

/// Loads `path` (project or bare scene). On success replaces the state's project, runs and layout,
/// clears dirty and the images, logs loader warnings, and returns true. On failure the state is left
/// untouched (the open project is not lost), `error` holds the message and false is returned.
bool loadProjectIntoState(WorkbenchState& state, const std::string& path, std::string& error);

/// Writes the workbench sections into project.doc and saves atomically to `path`. On success clears
/// dirty; on failure leaves the state as it was and returns false with `error` set.
bool saveStateToProject(WorkbenchState& state, const std::string& path, std::string& error);

/// The project document as it would be saved (for autosave copies and tests).
void storeWorkbenchSections(WorkbenchState& state);

}  // namespace rrf::panels
