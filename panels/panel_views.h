#pragma once
/// What each panel draws and edits, stated in one place: a small view per panel, references into
/// the WorkbenchState (which owns the data; the application's controllers publish into it) plus the
/// PanelActions a panel that asks for work or edits the project needs. A panel's entry point
/// (panels/panels.h) takes its view, so what a panel can touch is visible in its signature; one
/// builder per panel makes the view from the state, and the application and the tests both call
/// the panels through these builders. A value member (hasProject, compareRun) is read-only to the
/// panel; the state's sub-structs that several panels share (ViewState, TrainingInfo, ...) are
/// passed whole.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "panels/workbench_state.h"

namespace rrf::panels {

/// What the time estimates and the generator's memory check read (panels/pipeline_controls.h):
/// the project's settings and scene, the last render's rate, the last dataset and the memory left.
struct EstimateInputs {
    const Project& project;
    const RenderProgress& render;
    const DatasetInfo& dataset;
    uint64_t availableMemory;
};

/// Project panel: the project's name, file, render settings and runs (renamed in place), the runs
/// A/B pair, the run shown in the compare view, and the recent projects.
struct ProjectPanelView {
    Project& project;
    bool hasProject;
    const std::vector<std::string>& recent;
    ShortRunNames& runNames;  ///< the runs table's names, kept between frames
    RunPair& runPair;
    int compareRun;           ///< index into project.runs shown in the compare view, -1 = none
    PanelActions actions;
};

/// Scene panel: the project's scene (materials and the light edited through the project) and the
/// selected object.
struct ScenePanelView {
    Project& project;
    bool hasProject;
    int& selectedObject;  ///< ViewState::selectedObject
    PanelActions actions;
};

/// Sampling panel: the project's sampling settings, the last dataset's coverage, and the estimates'
/// inputs.
struct SamplingPanelView {
    Project& project;
    bool hasProject;
    const DatasetInfo& dataset;
    EstimateInputs estimates;
    PanelActions actions;
};

/// Network panel and its edit helpers: the project's network, trainer and prediction settings, the
/// dataset's input count, and the estimates' inputs.
struct NetworkPanelView {
    Project& project;
    bool hasProject;
    const DatasetInfo& dataset;
    EstimateInputs estimates;
    PanelActions actions;
};

/// Views panel: the view settings and what the views show, the light (moved by its handle), the
/// views' textures and the picking accel for the read-out.
struct ViewsPanelView {
    ViewState& view;
    Project& project;
    ViewImages images;
    const RenderProgress& render;
    const std::shared_ptr<const Accel>& pickAccel;
    const ImTextureID* viewTextures;  ///< WorkbenchState::viewTextures (3; null entries draw nothing)
    PanelActions actions;
    const ImageSet& reference() const { return images.reference(view.compareSource); }
    const ImageSet& compared() const { return images.compared(view.compareSource); }
};

/// Training panel: the training's progress and curves, the plot's settings, and the project's runs
/// (the last run's curves when this session trained nothing).
struct TrainingPanelView {
    const TrainingInfo& training;
    TrainingView& trainingView;
    const std::vector<Run>& runs;
    bool hasProject;
    PanelActions actions;
};

/// Objects panel: the last evaluation's table, the run pair's, the view's term and selection, and
/// the loaded models it must match.
struct ObjectsPanelView {
    const EvaluationInfo& evaluation;
    const RunPair& runPair;
    ViewState& view;
    const std::string& modelsDir;  ///< TrainingInfo::modelsDir: the models loaded ("" = none)
    ObjectsView& objectsView;
    PanelActions actions;
};

/// Cost panel: the sweeps (cleared from its toolbar), the plot's settings and the project's runs.
struct CostPanelView {
    CostInfo& cost;
    CostView& costView;
    const std::vector<Run>& runs;
    bool hasProject;
    PanelActions actions;
};

/// Light region panel: its grid and map, the project (the light moved by a click), the loaded models.
struct LightRegionPanelView {
    LightRegionInfo& lightRegion;
    Project& project;
    bool hasProject;
    const std::string& modelsDir;  ///< TrainingInfo::modelsDir: the models loaded ("" = none)
    PanelActions actions;
};

/// Leaves panel: the loaded models' leaves, the error goal's network settings, and the view's
/// selection and leaf tint.
struct LeavesPanelView {
    const LeavesInfo& leaves;
    const Project& project;
    ViewState& view;
};

/// Log panel: the log.
struct LogPanelView {
    Log& log;
};

/// The pipeline bar (panels/pipeline_controls.h): its preset and progress, and the estimates' inputs.
struct PipelineBarView {
    PipelineInfo& pipeline;
    bool hasProject;
    EstimateInputs estimates;
    PanelActions actions;
};

// One builder per view: what each panel is given of the state.
EstimateInputs estimateInputs(const WorkbenchState& state);
ProjectPanelView projectPanelView(WorkbenchState& state);
ScenePanelView scenePanelView(WorkbenchState& state);
SamplingPanelView samplingPanelView(WorkbenchState& state);
NetworkPanelView networkPanelView(WorkbenchState& state);
ViewsPanelView viewsPanelView(WorkbenchState& state);
TrainingPanelView trainingPanelView(WorkbenchState& state);
ObjectsPanelView objectsPanelView(WorkbenchState& state);
CostPanelView costPanelView(WorkbenchState& state);
LightRegionPanelView lightRegionPanelView(WorkbenchState& state);
LeavesPanelView leavesPanelView(WorkbenchState& state);
LogPanelView logPanelView(WorkbenchState& state);
PipelineBarView pipelineBarView(WorkbenchState& state);

}  // namespace rrf::panels
