#include "core/project.h"

#include "core/scene_overrides.h"

#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/json_reader.h"
#include "core/scene_json.h"
#include "core/scene_parse.h"

namespace rrf {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr int kProjectVersion = 1;

RenderSettings parseRender(const JsonReader& r) {
    r.checkKeys({"spp", "width", "height", "mode", "seed", "max_depth", "exposure"});
    RenderSettings s;
    s.spp = int(r.integerOr("spp", s.spp, 1, 1 << 30));
    s.width = int(r.integerOr("width", s.width, 0, 16384));
    s.height = int(r.integerOr("height", s.height, 0, 16384));
    if (auto mode = r.find("mode")) {
        const std::string m = mode->string();
        if (m == "nee") s.estimator = Estimator::NEE;
        else if (m == "naive") s.estimator = Estimator::Naive;
        else mode->fail("unknown render mode '" + m + "' (known: nee, naive)");
    }
    if (auto seed = r.find("seed")) s.seed = seed->unsignedInteger();
    s.maxDepth = int(r.integerOr("max_depth", s.maxDepth, 1, 1 << 16));
    s.exposure = r.floatOr("exposure", s.exposure);
    return s;
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

    if (auto render = root.find("render")) p.render = parseRender(*render);
    p.doc = std::move(doc);
    // Edits made in the workbench live in "scene_overrides"; apply them here so that the CLI and the
    // GUI see the same scene (and datasets and models record the same scene hash).
    std::vector<std::string> problems;
    applySceneOverrides(p, problems);
    for (const std::string& m : problems) p.scene.warnings.push_back("scene_overrides: " + m);
    return p;
}

RenderSettings parseRenderSettings(const nlohmann::json& section, const std::string& file, const std::string& where) {
    return parseRender(JsonReader(section, file, where));
}

nlohmann::json renderSettingsToJson(const RenderSettings& s) {
    return json{{"spp", s.spp},
                {"width", s.width},
                {"height", s.height},
                {"mode", s.estimator == Estimator::NEE ? "nee" : "naive"},
                {"seed", s.seed},
                {"max_depth", s.maxDepth},
                {"exposure", s.exposure}};
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

}  // namespace rrf
