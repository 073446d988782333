// Undo and redo of setting edits (see settings_history.h).
#include "core/project/settings_history.h"

#include <nlohmann/json.hpp>

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

std::string ProjectSettings::fingerprint() const {
    // The project writer's own encodings of the sections (core/project/project.cpp), so two
    // settings that save alike compare alike.
    nlohmann::json j;
    j["render"] = renderSettingsToJson(render);
    if (sampling) j["sampling"] = sampling->toJson();
    if (network) j["network"] = network->networkJson();
    if (trainer) j["trainer"] = trainer->toJson();
    j["prediction"] = prediction.toJson();
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

std::optional<ProjectSettings> SettingsHistory::undo() {
    if (undo_.empty()) return std::nullopt;
    redo_.push_back(std::move(current_));
    current_ = std::move(undo_.back());
    undo_.pop_back();
    currentPrint_ = current_.fingerprint();
    return current_;
}

std::optional<ProjectSettings> SettingsHistory::redo() {
    if (redo_.empty()) return std::nullopt;
    undo_.push_back(std::move(current_));
    current_ = std::move(redo_.back());
    redo_.pop_back();
    currentPrint_ = current_.fingerprint();
    return current_;
}

}  // namespace rrf
