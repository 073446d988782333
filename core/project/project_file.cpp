#include "core/project/project_file.h"

#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "core/eval/reference_settings_json.h"
#include "core/nn/object_network_overrides.h"
#include "core/project/pane_layout_json.h"
#include "core/project/runs_json.h"
#include "core/project/scene_overrides_json.h"
#include "core/data/sampling_settings_json.h"
#include "core/nn/network_settings_json.h"
#include "core/nn/object_network_overrides_json.h"
#include "core/nn/trainer_config_json.h"
#include "core/predict/prediction_settings_json.h"
#include "core/render/render_settings_json.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/util/json_reader.h"
#include "core/scene/scene_json.h"
#include "core/scene/scene_parse.h"

namespace rrf {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr int kProjectVersion = 1;

/// Top-level keys this build reads into typed fields; any other key is kept in otherSections.
bool isKnownSection(const std::string& key) {
    for (const char* k : {"rrf_project", "name", "scene", "render", "sampling", "network", "trainer", "prediction",
                          "reference", "runs", "layout", "scene_overrides"})
        if (key == k) return true;
    return false;
}

/// Writes the typed sections into `doc`. Absent optional sections stay absent (their absence means
/// "the front end's defaults"); workbench records are written only when there are some.
void writeSections(const Project& p, json& doc) {
    doc["render"] = renderSettingsToJson(p.render);
    if (p.sampling) doc["sampling"] = toJson(*p.sampling);
    if (p.network) doc["network"] = toJson(*p.network);
    if (p.trainer) doc["trainer"] = toJson(*p.trainer);
    doc["prediction"] = toJson(p.prediction);
    if (toJson(p.reference) != toJson(ReferenceSettings())) doc["reference"] = toJson(p.reference);
    if (!p.runs.empty()) doc["runs"] = runsToJson(p.runs);
    doc["layout"] = toJson(p.layout);
    if (!p.overrides.empty()) doc["scene_overrides"] = toJson(p.overrides);
}

/// Absolute, lexically normalised form of `p` (no symlink resolution: the user's spelling of the
/// directory layout is what relative references are written against).
fs::path absoluteNormal(const fs::path& p) { return fs::absolute(p.empty() ? fs::path(".") : p).lexically_normal(); }

/// Re-expresses `ref` (relative to `oldDir`) relative to `newDir`; absolute refs stay absolute.
std::string rebase(const std::string& ref, const std::string& oldDir, const std::string& newDir) {
    const fs::path r(ref);
    if (r.is_absolute()) return ref;
    const fs::path target = absoluteNormal(fs::path(resolvePath(oldDir, ref)));
    const fs::path rel = target.lexically_relative(absoluteNormal(fs::path(newDir)));
    // lexically_relative gives up across roots; an absolute path is then the only faithful answer.
    return rel.empty() ? target.generic_string() : rel.generic_string();
}

/// OBJ references inside an embedded scene are relative to the project file, so they move with it.
void rebaseEmbeddedScene(json& scene, const std::string& oldDir, const std::string& newDir) {
    if (!scene.is_object() || !scene.contains("shapes") || !scene["shapes"].is_array()) return;
    for (json& shape : scene["shapes"]) {
        if (shape.is_object() && shape.contains("file") && shape["file"].is_string())
            shape["file"] = rebase(shape["file"].get<std::string>(), oldDir, newDir);
    }
}

/// Parses the sections after "scene" into `p` (the scene is loaded already).
void readSections(const JsonReader& root, Project& p) {
    if (const auto name = root.find("name")) p.name = name->string();
    if (const auto render = root.find("render")) p.render = parseRenderSettings(*render);
    if (const auto sampling = root.find("sampling")) p.sampling = samplingSettingsFromJson(*sampling);
    // Per-object network entries and the gather's "objects" are the scene's object names (loaded already).
    std::vector<std::string> objectNames;
    for (const Object& o : p.scene.objects) objectNames.push_back(o.name);
    if (const auto network = root.find("network")) p.network = networkSettingsFromJson(*network, &objectNames);
    if (const auto trainer = root.find("trainer")) p.trainer = trainerConfigFromJson(*trainer);
    if (const auto prediction = root.find("prediction")) {
        p.prediction = predictionSettingsFromJson(*prediction);
        for (size_t i = 0; i < p.prediction.gather.objects.size(); ++i)
            requireSceneObjectName(prediction->at("gather").at("objects").at(i), p.prediction.gather.objects[i],
                                   objectNames);
    }
    if (const auto reference = root.find("reference")) p.reference = referenceSettingsFromJson(*reference);
    if (const auto runs = root.find("runs")) p.runs = readRuns(*runs, p.warnings);
    if (const auto layout = root.find("layout")) p.layout = paneLayoutFromJson(*layout, p.warnings);
    if (const auto overrides = root.find("scene_overrides")) {
        p.overrides = sceneOverridesFromJson(*overrides, p.warnings);
        std::vector<std::string> problems;
        applySceneOverrides(p.overrides, p.scene, problems);
        for (const std::string& m : problems) p.scene.warnings.push_back("scene_overrides: " + m);
    }
    json other = json::object();
    for (auto it = root.value().begin(); it != root.value().end(); ++it)
        if (!isKnownSection(it.key())) other[it.key()] = it.value();
    p.otherSections = jsonText(other);
}

}  // namespace

Project loadProjectOrScene(const std::string& path) {
    Project p;
    p.path = path;
    const std::string dir = directoryOf(path);
    const json doc = readJsonFile(path);
    const JsonReader root(doc, path);
    root.requireObject();

    if (!doc.contains("scene")) {
        if (!doc.contains("shapes"))
            root.fail("neither a project (no 'scene' field) nor a scene file (no 'shapes' field)");
        // A bare scene: wrap it in a project that references it, with default settings. Saving
        // back to `path` is refused by saveProject so the scene file cannot be overwritten.
        p.scene = parseSceneAt(root, dir);
        p.sceneRef = fs::path(path).filename().generic_string();
        p.name = fs::path(path).stem().string();
        return p;
    }

    const JsonReader version = root.at("rrf_project");
    const int64_t v = version.integer(1, std::numeric_limits<int>::max());
    if (v != kProjectVersion)
        version.fail("unsupported project version " + std::to_string(v) + " (this build reads version " +
                     std::to_string(kProjectVersion) + ")");

    const JsonReader sceneField = root.at("scene");
    if (sceneField.value().is_string()) {
        p.sceneRef = sceneField.string();
        if (p.sceneRef.empty()) sceneField.fail("scene file name must not be empty");
        const std::string scenePath = resolvePath(dir, p.sceneRef);
        if (!std::ifstream(scenePath))
            sceneField.fail("cannot open scene file '" + scenePath + "'");
        p.scene = loadScene(scenePath);
    } else if (sceneField.isObject()) {
        p.sceneJson = jsonText(sceneField.value());
        p.scene = parseSceneAt(sceneField, dir);
    } else {
        sceneField.fail("expected a scene file name (string) or an embedded scene (object), got " +
                        JsonReader::describe(sceneField.value()));
    }
    readSections(root, p);
    return p;
}

void saveProject(Project& project, const std::string& path) {
    const std::string oldDir = directoryOf(project.path);
    const std::string newDir = directoryOf(path);
    json doc = parseJsonText(project.otherSections);
    doc["rrf_project"] = kProjectVersion;
    if (!project.name.empty()) doc["name"] = project.name;

    std::string newRef;
    json newSceneJson = parseJsonText(project.sceneJson);
    if (!project.sceneRef.empty()) {
        const fs::path sceneFile = absoluteNormal(fs::path(resolvePath(oldDir, project.sceneRef)));
        if (sceneFile == absoluteNormal(fs::path(path)))
            throw std::runtime_error(path + ": refusing to save the project over its own scene file; choose another name");
        newRef = rebase(project.sceneRef, oldDir, newDir);
        doc["scene"] = newRef;
    } else {
        rebaseEmbeddedScene(newSceneJson, oldDir, newDir);
        doc["scene"] = newSceneJson;
    }
    writeSections(project, doc);

    std::string text;
    try {
        text = doc.dump(2) + "\n";
    } catch (const json::exception& e) {
        throw std::runtime_error(path + ": cannot serialise project: " + e.what());
    }
    writeFileAtomically(path, text);
    // Only after a successful write does the in-memory project follow the file.
    project.path = path;
    project.sceneRef = newRef;
    project.sceneJson = jsonText(newSceneJson);
}

std::string sectionText(const RenderSettings& s) { return renderSettingsToJson(s).dump(); }
std::string sectionText(const SamplingSettings& s) { return toJson(s).dump(); }
std::string sectionText(const NetworkSettings& s) { return toJson(s).dump(); }
std::string sectionText(const TrainerConfig& s) { return toJson(s).dump(); }
std::string sectionText(const PredictionSettings& s) { return toJson(s).dump(); }

}  // namespace rrf
