#pragma once
/// Entry points of the workbench panels, one per file in panels/. Each draws into the current
/// ImGui window (a pane's tab) and edits the WorkbenchState; actions that need the application
/// (files, jobs, GL) are queued as Requests.

#include "panels/workbench_state.h"

namespace rrf::panels {

/// Project: name, file, render settings, recent projects and the runs table.
void drawProjectPanel(WorkbenchState& state);
/// Scene: objects, materials (editable), lights, the movable light's position, derived effects.
void drawScenePanel(WorkbenchState& state);
/// Sampling: jitter grid, N_dir, spp per record, seed, light; estimates before and coverage after.
void drawSamplingPanel(WorkbenchState& state);
/// Views: ground truth | compared image | error map, synchronised zoom/pan and read-out.
void drawViewsPanel(WorkbenchState& state);
/// Log: messages and errors, copy to clipboard.
void drawLogPanel(WorkbenchState& state);

}  // namespace rrf::panels
