#pragma once
/// Project file: a JSON document that references (or embeds) a scene and holds the settings of every
/// stage. Typed settings live in structs; sections owned by later stages (sampling, network, trainer,
/// runs, layout) are kept as JSON so that every module parses its own section and nothing is lost
/// on a load/save round trip.

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "core/scene.h"

namespace rrf {

enum class Estimator { NEE, Naive };

/// Ground-truth render settings ("render" section).
struct RenderSettings {
    int spp = 64;              ///< samples per pixel
    int width = 0, height = 0; ///< 0 = the scene camera's size
    Estimator estimator = Estimator::NEE;
    uint64_t seed = 1;
    int maxDepth = 64;         ///< hard bound on path length (Russian roulette ends paths before)
    float exposure = 0.f;      ///< stops, for PNG output
};

struct Project {
    std::string path;           ///< where the project was loaded from / will be saved to
    std::string sceneRef;       ///< scene file relative to the project dir; empty if embedded
    nlohmann::json sceneJson;   ///< the embedded scene (when sceneRef is empty)
    Scene scene;                ///< the loaded scene
    RenderSettings render;
    nlohmann::json doc;         ///< the whole document, including sections other modules own
};

/// Loads a project file, or a bare scene file (a document with "shapes" and no "scene" key), in
/// which case default settings are used. Throws InputError naming the file and JSON path.
Project loadProjectOrScene(const std::string& path);

/// The "render" section for `s` (every key written).
nlohmann::json renderSettingsToJson(const RenderSettings& s);
/// Parses a "render" section (missing keys keep their defaults). Throws InputError naming `file`
/// and the JSON path (`where` is the section's own path) for unknown keys or bad values.
RenderSettings parseRenderSettings(const nlohmann::json& section, const std::string& file,
                                   const std::string& where = "/render");

/// Serialises `project` (typed settings written back into project.doc) and writes it atomically
/// (temporary file + rename). Throws std::runtime_error on I/O failure.
void saveProject(Project& project, const std::string& path);

}  // namespace rrf
