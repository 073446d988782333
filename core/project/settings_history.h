#pragma once
/// Undo and redo of the project's setting edits (issue 29: Ctrl+Z / Ctrl+Shift+Z), as a researcher
/// expects of any editor: the render, sampling, network, trainer and prediction settings and the
/// movable light's position. Material edits, runs, layout and files are not part of it.
///
/// The history observes the project once per settled frame (no mouse button held, so a slider or a
/// light drag is one step); a difference from the last observed settings is one undo step. An undo
/// returns the settings to apply, and the application applies them (restarting what depends on
/// them); a new edit after an undo drops the redo steps, as editors do.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/project/project.h"

namespace rrf {

/// The undoable part of a project.
struct ProjectSettings {
    RenderSettings render;
    std::optional<SamplingSettings> sampling;
    std::optional<NetworkSettings> network;
    std::optional<TrainerConfig> trainer;
    PredictionSettings prediction;
    std::optional<Vec3> light;  ///< the movable light's centre (none without lights)

    static ProjectSettings of(const Project& project);
    /// Sets `project`'s settings to these (the light moved with moveLight); returns whether the
    /// light moved, which restarts what depends on the scene.
    bool applyTo(Project& project) const;
    /// The settings as the project file writes them: equal fingerprints, equal settings.
    std::string fingerprint() const;
};

class SettingsHistory {
public:
    /// At most `limit` undo steps are kept (the oldest go first).
    explicit SettingsHistory(size_t limit = 200) : limit_(limit) {}

    /// Forgets every step and starts from `project` (a project opened or created).
    void reset(const Project& project);
    /// Records a change of `project`'s settings since the last observation as one undo step;
    /// returns whether there was one.
    bool observe(const Project& project);
    /// The settings before the last step (nullopt when there is none); the current ones become a
    /// redo step. The history holds the returned settings as current: applied as they are, the
    /// next observe sees no new edit.
    std::optional<ProjectSettings> undo();
    /// The settings the last undo left (nullopt when there is none).
    std::optional<ProjectSettings> redo();

    size_t undoSteps() const { return undo_.size(); }
    size_t redoSteps() const { return redo_.size(); }

private:
    /// Makes the last of `from` current and the current settings the last of `to`.
    std::optional<ProjectSettings> step(std::vector<ProjectSettings>& from, std::vector<ProjectSettings>& to);

    size_t limit_;
    std::vector<ProjectSettings> undo_, redo_;
    ProjectSettings current_;
    std::string currentPrint_;
};

}  // namespace rrf
