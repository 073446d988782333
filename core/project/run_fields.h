#pragma once
/// The typed parts of a run record (core/project/runs.h): its settings snapshot, its metrics and its
/// timings. Each figure the workbench writes is a field, so a misspelt name fails to compile instead
/// of reading as "unknown" in a table. Only runs_json.cpp turns them into JSON and back, under the key
/// named beside each field; keys this build does not know are kept in `other` and written back as
/// they were, so a newer workbench's runs survive a round trip through an older one.

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include "core/data/sampling_settings.h"
#include "core/nn/network_settings.h"
#include "core/nn/trainer_config.h"
#include "core/project/scene_overrides.h"
#include "core/render/render_settings.h"
#include "core/util/json_text.h"
#include "core/util/vec3.h"

namespace rrf {

/// Every setting that made a run. A render run fills render, lightPosition, sceneHash and
/// sceneOverrides; a training run network, trainer, dataset, sceneHash, sampling and kernel.
struct RunSettings {
    std::optional<RenderSettings> render;          ///< "render" (spp is the target spp)
    std::optional<Vec3> lightPosition;             ///< "light_position"
    std::optional<std::string> sceneHash;          ///< "scene_hash": the scene's content hash in hex
    std::optional<SceneOverrides> sceneOverrides;  ///< "scene_overrides"
    /// "network"; the trainer is `trainer`, held apart as a project holds it.
    std::optional<NetworkSettings> network;
    std::optional<TrainerConfig> trainer;          ///< "trainer"
    std::optional<std::string> dataset;            ///< "dataset", relative to the project directory
    std::optional<SamplingSettings> sampling;      ///< "sampling": the project's section, when it had one
    std::optional<std::string> kernel;             ///< "kernel": the MLP kernel it trained with
    JsonText other;  ///< keys this build does not know
};

/// What a run measured. An unknown figure is empty, never 0. A non-finite double is written as null
/// (JSON has no NaN) and read back as NaN.
struct RunMetrics {
    // Render runs.
    std::optional<int> spp;                       ///< "spp": samples per pixel completed
    std::optional<double> relativeError;          ///< "relative_error": the render's own noise estimate
    std::optional<uint64_t> nonFiniteSamples;     ///< "non_finite_samples": NaN/Inf samples dropped
    std::optional<double> samplesPerSecond;       ///< "samples_per_second"
    // Training runs.
    std::optional<int> networks;                  ///< "networks": networks trained
    std::optional<int> skipped;                   ///< "skipped": networks without enough records
    std::optional<int> epochs;                    ///< "epochs": the last epoch of any network
    std::optional<int> plannedNetworks;           ///< "planned_networks": networks it set out to train
    std::optional<bool> stopped;                  ///< "stopped": the user stopped the training
    std::optional<int> leaves;                    ///< "leaves": kd-tree leaves over all models
    std::optional<int64_t> records;               ///< "records": training records read
    // An evaluation of a training run's models (the global term).
    std::optional<double> relativeRmse;           ///< "relative_rmse"
    std::optional<double> rmse;                   ///< "rmse"
    std::optional<double> mae;                    ///< "mae"
    std::optional<int> evaluatedSpp;              ///< "evaluated_spp": the reference's spp
    std::optional<int> evaluatedWidth;            ///< "evaluated_width": the size the error was measured at
    std::optional<int> evaluatedHeight;           ///< "evaluated_height"
    std::optional<double> relativeRmseNoiseFloor; ///< "relative_rmse_noise_floor": the reference's noise
    std::optional<double> relativeRmseCorrected;  ///< "relative_rmse_corrected": the error less that noise
    std::optional<Vec3> evaluatedLight;           ///< "evaluated_light": the one light evaluated at
    std::optional<int64_t> evaluatedLights;       ///< "evaluated_lights": how many, when several
    // One frame of prediction with the training run's models (median of recent frames).
    std::optional<double> frameSeconds;           ///< "frame_seconds": on the CPU
    std::optional<int> frameWidth;                ///< "frame_width"
    std::optional<int> frameHeight;               ///< "frame_height"
    std::optional<double> glslFrameSeconds;       ///< "glsl_frame_seconds": in GLSL
    std::optional<int> glslFrameWidth;            ///< "glsl_frame_width"
    std::optional<int> glslFrameHeight;           ///< "glsl_frame_height"
    JsonText other;  ///< keys this build does not know
};

/// Seconds per stage of a run.
struct RunTimings {
    std::optional<double> render;    ///< "render": the ground-truth render
    std::optional<double> train;     ///< "train": training wall time
    std::optional<double> generate;  ///< "generate": making the training data, when known
    std::optional<double> evaluate;  ///< "evaluate": the last evaluation of the models
    JsonText other;  ///< keys this build does not know
};

/// `v` when it holds a finite number, else empty (for tables: a figure recorded as null is unknown).
inline std::optional<double> finiteOrNone(const std::optional<double>& v) {
    return v && std::isfinite(*v) ? v : std::nullopt;
}

}  // namespace rrf
