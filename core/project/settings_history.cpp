// Undo and redo of setting edits (see settings_history.h).
#include "core/project/settings_history.h"

#include <nlohmann/json.hpp>

#include "core/data/sampling_settings_json.h"
#include "core/nn/network_settings_json.h"
#include "core/nn/trainer_config_json.h"
#include "core/predict/prediction_settings_json.h"
#include "core/project/scene_edits.h"
#include "core/render/render_settings_json.h"

namespace rrf {

ProjectSettings ProjectSettings::of(const Project& project) {
    ProjectSettings s;
    s.render = project.render;
    s.sampling = project.sampling;
    s.network = project.network;
    s.trainer = project.trainer;
    s.prediction = project.prediction;
    if (!project.scene.lights.empty()) s.light = project.scene.lightPosition();
    return s;
}

bool ProjectSettings::applyTo(Project& project) const {
    project.render = render;
    project.sampling = sampling;
    project.network = network;
    project.trainer = trainer;
    project.prediction = prediction;
    const bool lightMoved = light && !(*light == project.scene.lightPosition());
    if (lightMoved) moveLight(project, *light);
    return lightMoved;
}

std::string ProjectSettings::fingerprint() const {
    // The project writer's own encodings of the sections (core/project/project.cpp), so two
    // settings that save alike compare alike.
    nlohmann::json j;
    j["render"] = renderSettingsToJson(render);
    if (sampling) j["sampling"] = toJson(*sampling);
    if (network) j["network"] = toJson(*network);
    if (trainer) j["trainer"] = toJson(*trainer);
    j["prediction"] = toJson(prediction);
    if (light) j["light"] = {light->x, light->y, light->z};
    return j.dump();
}

void SettingsHistory::reset(const Project& project) {
    undo_.clear();
    redo_.clear();
    current_ = ProjectSettings::of(project);
    currentPrint_ = current_.fingerprint();
}

bool SettingsHistory::observe(const Project& project) {
    ProjectSettings now = ProjectSettings::of(project);
    std::string print = now.fingerprint();
    if (print == currentPrint_) return false;
    undo_.push_back(std::move(current_));
    if (undo_.size() > limit_) undo_.erase(undo_.begin());
    redo_.clear();
    current_ = std::move(now);
    currentPrint_ = std::move(print);
    return true;
}

std::optional<ProjectSettings> SettingsHistory::step(std::vector<ProjectSettings>& from, std::vector<ProjectSettings>& to) {
    if (from.empty()) return std::nullopt;
    to.push_back(std::move(current_));
    current_ = std::move(from.back());
    from.pop_back();
    currentPrint_ = current_.fingerprint();
    return current_;
}

std::optional<ProjectSettings> SettingsHistory::undo() { return step(undo_, redo_); }

std::optional<ProjectSettings> SettingsHistory::redo() { return step(redo_, undo_); }

}  // namespace rrf
