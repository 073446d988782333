#include "core/project/project.h"

#include "core/project/scene_overrides.h"

#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>

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

}  // namespace

Project loadProjectOrScene(const std::string& path) {
    Project p;
    p.path = path;
    const std::string dir = directoryOf(path);
    json doc = readJsonFile(path);
    const JsonReader root(doc, path);
    root.requireObject();

    if (!doc.contains("scene")) {
        if (!doc.contains("shapes"))
            root.fail("neither a project (no 'scene' field) nor a scene file (no 'shapes' field)");
        // A bare scene: wrap it in a project that references it, with default settings. Saving
        // back to `path` is refused by saveProject so the scene file cannot be overwritten.
        p.scene = parseSceneAt(root, dir);
        p.sceneRef = fs::path(path).filename().generic_string();
        p.doc = json{{"rrf_project", kProjectVersion},
                     {"name", fs::path(path).stem().string()},
                     {"scene", p.sceneRef},
                     {"render", renderSettingsToJson(p.render)}};
        return p;
    }

    const JsonReader version = root.at("rrf_project");
    const int64_t v = version.integer(1, std::numeric_limits<int>::max());
    if (v != kProjectVersion)
        version.fail("unsupported project version " + std::to_string(v) + " (this build reads version " +
                     std::to_string(kProjectVersion) + ")");
    if (auto name = root.find("name")) name->string();

    const JsonReader sceneField = root.at("scene");
    if (sceneField.value().is_string()) {
        p.sceneRef = sceneField.string();
        if (p.sceneRef.empty()) sceneField.fail("scene file name must not be empty");
        const std::string scenePath = resolvePath(dir, p.sceneRef);
        if (!std::ifstream(scenePath))
            sceneField.fail("cannot open scene file '" + scenePath + "'");
        p.scene = loadScene(scenePath);
    } else if (sceneField.isObject()) {
        p.sceneJson = sceneField.value();
        p.scene = parseSceneAt(sceneField, dir);
    } else {
        sceneField.fail("expected a scene file name (string) or an embedded scene (object), got " +
                        JsonReader::describe(sceneField.value()));
    }

    if (root.has("render")) p.render = parseRenderSettings(doc.at("render"), path);
    p.doc = std::move(doc);
    // Edits made in the workbench live in "scene_overrides"; apply them here so that the CLI and the
    // GUI see the same scene (and datasets and models record the same scene hash).
    std::vector<std::string> problems;
    applySceneOverrides(p, problems);
    for (const std::string& m : problems) p.scene.warnings.push_back("scene_overrides: " + m);
    return p;
}

void saveProject(Project& project, const std::string& path) {
    const std::string oldDir = directoryOf(project.path);
    const std::string newDir = directoryOf(path);
    json doc = project.doc.is_object() ? project.doc : json::object();
    if (!doc.contains("rrf_project")) doc["rrf_project"] = kProjectVersion;
    doc["render"] = renderSettingsToJson(project.render);

    std::string newRef;
    json newSceneJson = project.sceneJson;
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

    std::string text;
    try {
        text = doc.dump(2) + "\n";
    } catch (const json::exception& e) {
        throw std::runtime_error(path + ": cannot serialise project: " + e.what());
    }
    writeFileAtomically(path, text);
    // Only after a successful write does the in-memory project follow the file.
    project.doc = std::move(doc);
    project.path = path;
    project.sceneRef = newRef;
    project.sceneJson = std::move(newSceneJson);
}

SamplingSettings samplingSettingsOf(const Project& project) {
    if (!project.doc.is_object() || !project.doc.contains("sampling")) return {};
    return SamplingSettings::fromJson(project.doc.at("sampling"), project.path);
}

NetworkSettings networkSettingsOf(const Project& project) {
    const json& d = project.doc;
    const json empty = json::object();
    if (!d.is_object()) return NetworkSettings::fromJson(empty, nullptr, project.path);
    return NetworkSettings::fromJson(d.contains("network") ? d.at("network") : empty,
                                     d.contains("trainer") ? &d.at("trainer") : nullptr, project.path);
}

void storeNetworkSettings(const NetworkSettings& settings, Project& project) {
    project.doc["network"] = settings.networkJson();
    project.doc["trainer"] = settings.trainerJson();
}

PredictionSettings predictionSettingsOf(const Project& project) {
    if (project.doc.is_object() && project.doc.contains("prediction"))
        return PredictionSettings::fromJson(project.doc.at("prediction"), project.path);
    return {};
}

}  // namespace rrf
