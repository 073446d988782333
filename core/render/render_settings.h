#pragma once
/// Ground-truth render settings (the project's "render" section) and the estimator choice shared by
/// the path tracer, the data generator and the references.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/scene/effects.h"
#include "core/scene/scene.h"

namespace rrf {

/// The light-transport estimators. NEE and Naive are the path tracer's (core/render/path_tracer.h),
/// BDPT the bidirectional path tracer (core/render/bdpt.h). Auto is a setting, never an estimator
/// that runs: chooseEstimator() turns it into one from the scene's effects.
enum class Estimator { NEE, Naive, BDPT, Auto };

/// "nee" | "naive" | "bdpt" | "auto": the one spelling of project files, flags, outputs and keys.
const char* estimatorName(Estimator e);
/// The estimator spelled `name`; nullopt for anything else (each reader reports it in its terms).
std::optional<Estimator> parseEstimator(std::string_view name);
/// "nee, naive, bdpt, auto", for messages and help texts.
const char* estimatorNames();
/// {"nee", "naive", "bdpt", "auto"}: the values a setting or flag may take (readers' choice lists).
const std::vector<std::string>& estimatorChoices();

/// The estimator that runs and why (printed by the CLI, recorded in render.json and datasets).
struct EstimatorChoice {
    Estimator estimator = Estimator::NEE;
    std::string reason;
};
/// `requested` itself unless it is Auto; Auto picks BDPT where glossy lobes can carry light from an
/// emitter to a diffuse surface (Effects::caustics) and the path tracer's NEE elsewhere.
EstimatorChoice chooseEstimator(Estimator requested, const Effects& effects);

/// Bytes a width × height render holds at its peak: the per-pixel sums twice (committed and the pass
/// being added, core/render/renderer.h) and two snapshots of six float RGB images (means and
/// variances of the three terms: the renderer's and the one being written out).
uint64_t renderMemoryBytes(int width, int height);

/// Throws SettingError("image size", ...) with the estimate when renderMemoryBytes(width, height)
/// exceeds the memory available to the process (core/util/memory_budget.h).
void requireRenderMemory(int width, int height);

/// Ground-truth render settings ("render" section; its JSON is render/render_settings_json.h's).
struct RenderSettings {
    int spp = 64;              ///< samples per pixel
    int width = 0, height = 0; ///< 0 = the scene camera's size
    Estimator estimator = Estimator::Auto;
    uint64_t seed = 1;
    int maxDepth = 64;         ///< hard bound on path length (Russian roulette ends paths before)
    float exposure = 0.f;      ///< stops, for PNG output
};

}  // namespace rrf
