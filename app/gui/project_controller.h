#pragma once
/// The project file as a controller: open, new from a scene, save, autosave, the recent projects
/// list, and the "Unsaved changes" prompt that guards quitting, opening and starting a new project.
/// It publishes the project into the state (state.project, hasProject, dirty, recent) and the
/// prompt's pending action; the Workbench draws the prompt and the file dialogs, and does what a
/// newly opened project needs of the other controllers (onOpened). UI thread only.

#include <chrono>
#include <functional>
#include <string>

#include "app/gui/controller_context.h"
#include "app/gui/user_config.h"

namespace rrf {

class ProjectController {
public:
    /// `configDir`: per-user directory for recent.json.
    ProjectController(ControllerContext& ctx, const std::string& configDir);

    /// Opens a project or bare scene. A file that cannot be read is reported (onError) and the open
    /// project stays; returns false then.
    bool open(const std::string& path);
    /// Opens a scene file as a new project that has no file of its own yet (the first Save asks where).
    void newFromScene(const std::string& scenePath);
    /// Saves to `path` (empty: the project's own path, or Save As when it has none).
    bool save(const std::string& path = {});
    /// Each frame: every two minutes, a copy of a project with unsaved changes beside its file.
    void autosave();
    /// Window title: "RRF Workbench - <project>" with "*" for unsaved changes.
    std::string title() const;

    /// What the "Unsaved changes" prompt asks about.
    enum class UnsavedChoice { Save, Discard, Cancel };
    /// An action waiting for the prompt.
    struct PendingAction {
        enum Kind { None, Quit, Open, New } kind = None;
        std::string path;  ///< Open: the project (empty: ask with the dialog)
    };
    /// Carries out `action` now when nothing is unsaved, else keeps it and opens the prompt.
    /// Returns true when it was carried out now.
    bool whenSaved(PendingAction action);
    /// Answers the prompt: Save saves and then carries out the action (not when saving fails),
    /// Discard carries it out, Cancel forgets it.
    void answer(UnsavedChoice choice);
    /// True while the prompt waits for an answer.
    bool promptOpen() const { return pending_.kind != PendingAction::None; }
    const PendingAction& pending() const { return pending_; }
    /// True once, the frame after the prompt was asked for: the Workbench opens its popup then.
    bool takePromptRequest();
    /// True once quitting was confirmed (nothing unsaved, or answered).
    bool quitConfirmed() const { return quitConfirmed_; }
    void confirmQuit() { quitConfirmed_ = true; }

    /// The project was opened (state.project is the new one): the Workbench drops the old project's
    /// jobs, loads its models and sweeps and starts its ground truth.
    std::function<void()> onOpened;
    /// A file could not be opened or saved: title and message for the error modal.
    std::function<void(const std::string& title, const std::string& message)> onError;
    /// An action needs a file chosen: the Open dialog (`newProject` false) or the scene for New.
    std::function<void(bool newProject)> chooseFile;

private:
    void carryOut(const PendingAction& action);

    ControllerContext& ctx_;
    panels::WorkbenchState& state_;  ///< ctx_.state: what the controller publishes into
    RecentProjects recent_;
    PendingAction pending_;
    bool promptRequested_ = false;  ///< open the prompt's popup next frame
    bool quitConfirmed_ = false;
    std::chrono::steady_clock::time_point lastAutosave_;
};

}  // namespace rrf
