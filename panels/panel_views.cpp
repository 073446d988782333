#include "panels/panel_views.h"

namespace rrf::panels {

EstimateInputs estimateInputs(const WorkbenchState& state) {
    return {state.project, state.render, state.dataset, state.availableMemory};
}

ProjectPanelView projectPanelView(WorkbenchState& state) {
    return {state.project, state.hasProject, state.recent, state.runNames, state.runPair, state.compareRun, state.actions()};
}

ScenePanelView scenePanelView(WorkbenchState& state) {
    return {state.project, state.hasProject, state.view.selectedObject, state.actions()};
}

SamplingPanelView samplingPanelView(WorkbenchState& state) {
    return {state.project, state.hasProject, state.dataset, estimateInputs(state), state.actions()};
}

NetworkPanelView networkPanelView(WorkbenchState& state) {
    return {state.project, state.hasProject, state.dataset, estimateInputs(state), state.actions()};
}

ViewsPanelView viewsPanelView(WorkbenchState& state) {
    return {state.view,      state.project,      state.images(), state.render,
            state.pickAccel, state.viewTextures, state.actions()};
}

TrainingPanelView trainingPanelView(WorkbenchState& state) {
    return {state.training, state.trainingView, state.project.runs, state.hasProject, state.actions()};
}

ObjectsPanelView objectsPanelView(WorkbenchState& state) {
    return {state.evaluation, state.runPair, state.view, state.training.modelsDir, state.objectsView, state.actions()};
}

CostPanelView costPanelView(WorkbenchState& state) {
    return {state.cost, state.costView, state.project.runs, state.hasProject, state.actions()};
}

LightRegionPanelView lightRegionPanelView(WorkbenchState& state) {
    return {state.lightRegion, state.project, state.hasProject, state.training.modelsDir, state.actions()};
}

LeavesPanelView leavesPanelView(WorkbenchState& state) { return {state.leaves, state.project, state.view}; }

LogPanelView logPanelView(WorkbenchState& state) { return {state.log}; }

PipelineBarView pipelineBarView(WorkbenchState& state) {
    return {state.pipeline, state.hasProject, estimateInputs(state), state.actions()};
}

}  // namespace rrf::panels
