#include "panels/project_io.h"

#include <exception>
#include <vector>


namespace rrf::panels {

using nlohmann::json;

json renderSettingsJson(const RenderSettings& s) { return renderSettingsToJson(s); }

bool applyRenderSettingsJson(const json& j, RenderSettings& s) {
    if (!j.is_object()) return false;
    bool ok = true;
    auto integer = [&](const char* key, int& out, int lo, int hi) {
        if (!j.contains(key)) return;
        if (j[key].is_number_integer() && j[key].get<int64_t>() >= lo && j[key].get<int64_t>() <= hi)
            out = j[key].get<int>();
        else ok = false;
    };
    integer("spp", s.spp, 1, 1 << 30);
    integer("width", s.width, 0, 16384);
    integer("height", s.height, 0, 16384);
    integer("max_depth", s.maxDepth, 1, 1 << 16);
    if (j.contains("mode")) {
        const json& m = j["mode"];
        if (m == "nee") s.estimator = Estimator::NEE;
        else if (m == "naive") s.estimator = Estimator::Naive;
        else ok = false;
    }
    if (j.contains("seed")) {
        if (j["seed"].is_number_unsigned()) s.seed = j["seed"].get<uint64_t>();
        else ok = false;
    }
    if (j.contains("exposure")) {
        if (j["exposure"].is_number()) s.exposure = j["exposure"].get<float>();
        else ok = false;
    }
    return ok;
}

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
