#include "panels/project_io.h"

#include <exception>
#include <vector>

namespace rrf::panels {

using nlohmann::json;

bool loadProjectIntoState(WorkbenchState& state, const std::string& path, std::string& error) {
    Project project;
    try {
        project = loadProjectOrScene(path);
    } catch (const std::exception& e) {
        error = e.what();
        return false;
    }
    std::vector<std::string> problems;  // scene_overrides problems arrive as scene warnings
    std::vector<Run> runs = runsFromDoc(project.doc, &problems);
    const LayoutState layout =
        project.doc.contains("layout") ? LayoutState::fromJson(project.doc["layout"]) : LayoutState();

    state.project = std::move(project);
    state.hasProject = true;
    state.dirty = false;
    state.runs = std::move(runs);
    state.layout = layout;
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
    for (const std::string& p : problems) state.log.warning(path + ": " + p);
    return true;
}

void storeWorkbenchSections(WorkbenchState& state) {
    json& doc = state.project.doc;
    if (!doc.is_object()) doc = json::object();
    doc["layout"] = state.layout.toJson();
    storeRunsInDoc(state.runs, doc);
    state.project.render.exposure = state.view.exposure;
}

bool saveStateToProject(WorkbenchState& state, const std::string& path, std::string& error) {
    const json before = state.project.doc;
    const float exposure = state.project.render.exposure;
    storeWorkbenchSections(state);
    try {
        saveProject(state.project, path);
    } catch (const std::exception& e) {
        state.project.doc = before;  // a failed save changes nothing
        state.project.render.exposure = exposure;
        error = e.what();
        return false;
    }
    state.dirty = false;
    state.log.info("saved " + path);
    return true;
}

}  // namespace rrf::panels
