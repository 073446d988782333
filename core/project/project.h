#pragma once
/// Project file: a JSON document that references (or embeds) a scene and holds the settings of every
/// stage. Typed settings live in structs; sections owned by later stages (sampling, network, trainer,
/// runs, layout) are kept as JSON so that every module parses its own section and nothing is lost
/// on a load/save round trip.

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "core/data/sampling_settings.h"
#include "core/nn/network_settings.h"
#include "core/predict/predictor.h"
#include "core/render/render_settings.h"
#include "core/scene/scene.h"

namespace rrf {

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

/// Serialises `project` (typed settings written back into project.doc) and writes it atomically
/// (temporary file + rename). Throws std::runtime_error on I/O failure.
void saveProject(Project& project, const std::string& path);

/// The project's "sampling" section (defaults when absent). Throws InputError for bad values.
SamplingSettings samplingSettingsOf(const Project& project);
/// The project's "network" and "trainer" sections (defaults where absent).
NetworkSettings networkSettingsOf(const Project& project);
/// Writes `settings` back into the project's "network" and "trainer" sections.
void storeNetworkSettings(const NetworkSettings& settings, Project& project);
/// The project's "prediction" section (defaults when absent).
PredictionSettings predictionSettingsOf(const Project& project);

}  // namespace rrf
