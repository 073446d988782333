#pragma once
/// Project file: a JSON document that references (or embeds) a scene and holds the settings of every
/// stage. The document is typed: every section is parsed once, by loadProjectOrScene
/// (core/project/project_file.h), into the fields below, which are the only live copy; saveProject
/// writes them back. Top-level sections this build does not know are kept verbatim (otherSections)
/// so a newer program's sections survive a round trip.
/// The format is described in docs/file-formats.md.

#include <optional>
#include <string>
#include <vector>

#include "core/data/sampling_settings.h"
#include "core/eval/reference_settings.h"
#include "core/nn/network_settings.h"
#include "core/nn/object_training.h"
#include "core/nn/trainer_config.h"
#include "core/predict/prediction_settings.h"
#include "core/project/pane_layout.h"
#include "core/project/runs.h"
#include "core/project/scene_overrides.h"
#include "core/render/render_settings.h"
#include "core/scene/scene.h"
#include "core/util/json_text.h"

namespace rrf {

struct Project {
    std::string path;           ///< where the project was loaded from / will be saved to
    std::string name;           ///< "name": display name; empty = none
    std::string sceneRef;       ///< scene file relative to the project dir; empty if embedded
    JsonText sceneJson;         ///< the embedded scene (when sceneRef is empty), written back as given
    Scene scene;                ///< the loaded scene with `overrides` applied
    SceneOverrides overrides;   ///< "scene_overrides": the workbench's edits of the scene
    RenderSettings render;      ///< "render"
    /// "sampling"; empty when the file has none: SamplingSettings' defaults then apply
    /// (rrf pipeline --quick uses smaller sizes), and the section stays absent on save.
    std::optional<SamplingSettings> sampling;
    /// "network": hidden layers, activation, targets, inputs, encoding, per-object entries and
    /// partition; empty when the file has none (see `sampling`). The trainer is `trainer`, held
    /// apart; trainingOptions() joins the two where a training starts.
    std::optional<NetworkSettings> network;
    /// "trainer"; empty when the file has none: TrainerConfig::projectDefault() then applies, and
    /// the section stays absent on save (as it does when only "network" was edited).
    std::optional<TrainerConfig> trainer;
    PredictionSettings prediction;  ///< "prediction"
    /// "reference": how converged the references of the project's store must be and their size
    /// (core/eval/reference_store.h); written when it differs from the defaults.
    ReferenceSettings reference;
    std::vector<Run> runs;          ///< "runs"
    PaneLayout layout;              ///< "layout": the workbench's pane sizes
    /// Top-level sections this build does not know (an object), kept only for load/save round trips.
    JsonText otherSections;
    /// Problems in the workbench's own sections (layout, runs, scene_overrides) that did not stop the
    /// load, each naming the file and the JSON pointer. Problems applying the overrides to the scene
    /// are in scene.warnings.
    std::vector<std::string> warnings;

    /// The sampling settings in effect (SamplingSettings' defaults when the file has none).
    SamplingSettings samplingOrDefault() const { return sampling.value_or(SamplingSettings()); }
    /// The network settings in effect: the section's values, its defaults where absent.
    /// The targets follow the prediction: indirect networks beside exact direct light (the default),
    /// separate direct and indirect ones when direct light is learned.
    NetworkSettings networkOrDefault() const {
        NetworkSettings s = network.value_or(NetworkSettings());
        // Learned direct light needs direct networks: indirect-only targets (the default, or written by
        // the Network panel while direct light was exact) become separate direct and indirect ones.
        if (prediction.direct == PredictionSettings::Direct::Network && s.options.targets == TargetMode::Indirect)
            s.options.targets = TargetMode::Separate;
        return s;
    }
    /// The trainer in effect: the "trainer" section, TrainerConfig::projectDefault() where absent.
    TrainerConfig trainerOrDefault() const { return trainer.value_or(TrainerConfig::projectDefault()); }
    /// What a training of every object with the project's settings is: networkOrDefault()'s network
    /// trained by trainerOrDefault().
    ObjectTrainingOptions trainingOptions() const { return {networkOrDefault().options, trainerOrDefault()}; }
};

}  // namespace rrf
