#include "panels/project_io.h"

#include <exception>
#include <filesystem>

#include "core/project/project_file.h"
#include "core/project/project_files.h"
#include "core/pipeline/run_recording.h"

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
    state.lightRegion = LightRegionInfo{};  // its map and cells are the previous project's lights
    state.render = RenderProgress{};
    state.runPair = RunPair{};
    state.notice.reset();  // it spoke of the previous project's state
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
    const std::vector<Run> runs = state.project.runs;
    storeWorkbenchSections(state);
    // Save As to another directory: the runs, references and dataset come along (hard links, else
    // copies), so every run re-opens from the new place; artifacts outside the project are relinked.
    const std::string oldDir = projectDirectory(state.project);
    const std::string newDir = std::filesystem::absolute(std::filesystem::path(path)).parent_path().string();
    CarriedFiles carried;
    if (!state.project.path.empty()) carried = carryProjectFiles(oldDir, newDir, state.project.runs);
    try {
        saveProject(state.project, path);
    } catch (const std::exception& e) {
        state.project.render.exposure = exposure;  // a failed save changes nothing
        state.project.runs = runs;
        error = e.what();
        return false;
    }
    state.dirty = false;
    state.log.info("saved " + path);
    if (carried.linked + carried.copied + carried.relinked > 0)
        state.log.info("carried the project's files to " + newDir + ": " + std::to_string(carried.linked) + " linked, " +
                       std::to_string(carried.copied) + " copied, " + std::to_string(carried.relinked) +
                       " paths outside the project relinked");
    for (const std::string& p : carried.problems) state.log.warning("Save As: not carried: " + p);
    // This session's dataset now lives (also) under the new directory.
    const std::string rel = state.dataset.path.empty() ? std::string() : projectRelative(oldDir, state.dataset.path);
    if (!rel.empty() && rel.rfind("data/", 0) == 0) state.dataset.path = (std::filesystem::path(newDir) / rel).string();
    return true;
}

}  // namespace rrf::panels
