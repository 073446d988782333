#pragma once
/// What the workbench's controllers (pipeline, training, prediction, ...) share: the panels' state
/// they publish their snapshots into, the job runner their sessions start jobs on, and the project's
/// file situation. The Workbench owns it and hands each controller a reference; a controller keeps
/// its own job sessions and bookkeeping and writes only its own sections of the state.
/// UI thread only.

#include <functional>
#include <string>

#include "app/gui/job_runner.h"
#include "panels/workbench_state.h"

namespace rrf {

/// How a stage job started by a controller ended, told once to whoever started it (the pipeline):
/// `delivered` is true when the job produced its result (a dataset written, a complete model set
/// saved, an evaluation made, a ground truth converged), false when it was stopped, refused or failed.
using StageDone = std::function<void(bool delivered)>;

struct ControllerContext {
    panels::WorkbenchState& state;
    JobRunner& jobs;
    /// The project has no file of its own yet (New): nothing may be stored next to it.
    bool untitled = false;

    /// The open project's directory (the working directory without a project): where data, runs,
    /// models and sweeps go.
    std::string projectDir() const;
    /// True when outputs may be stored next to the project: it has a file of its own.
    bool savedProject() const { return !untitled && !state.project.path.empty(); }
};

}  // namespace rrf
