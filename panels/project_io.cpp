#include "panels/project_io.h"

#include <exception>

namespace rrf::panels {

bool loadProjectIntoState(WorkbenchState& state, const std::string& path, std::string& error) {
    Project project;
    try {
        project = loadProjectOrScene(path);
    } catch (const std::exception& e) {
        error = e.what();
        return false;
    }
    state.project = std::move(project);
    state.hasProject = true;
    state.dirty = false;
    state.compareRun = -1;
    state.dataset = DatasetInfo{};  // the previous project's dataset must not feed this one's training
    state.groundTruth = ImageSet{};
    state.compare = ImageSet{};
    state.prediction = ImageSet{};
    state.view.compareSource = CompareSource::Prediction;
    state.training = TrainingInfo{};
    state.evaluation = EvaluationInfo{};
    state.cost = CostInfo{};
    state.render = RenderProgress{};
    state.view.selectedObject = -1;
    state.view.exposure = state.project.render.exposure;
    state.log.info("opened " + path);
    for (const std::string& w : state.project.scene.warnings) state.log.warning(path + ": " + w);
    for (const std::string& w : state.project.warnings) state.log.warning(w);
    return true;
}

void storeWorkbenchSections(WorkbenchState& state) { state.project.render.exposure = state.view.exposure; }

bool saveStateToProject(WorkbenchState& state, const std::string& path, std::string& error) {
    const float exposure = state.project.render.exposure;
    storeWorkbenchSections(state);
    try {
        saveProject(state.project, path);
    } catch (const std::exception& e) {
        state.project.render.exposure = exposure;  // a failed save changes nothing
        error = e.what();
        return false;
    }
    state.dirty = false;
    state.log.info("saved " + path);
    return true;
}

}  // namespace rrf::panels
