// ProjectController (project_controller.h): project files (open, new, save, autosave, recent) and the
// "Unsaved changes" prompt.
#include "app/gui/project_controller.h"

#include <filesystem>

#include "core/pipeline/run_recording.h"
#include "core/project/project_file.h"
#include "panels/project_io.h"

namespace rrf {

namespace fs = std::filesystem;

namespace {
constexpr auto kAutosaveInterval = std::chrono::minutes(2);

std::string autosavePath(const std::string& projectPath) { return projectPath + ".autosave.json"; }
}  // namespace

ProjectController::ProjectController(ControllerContext& ctx, const std::string& configDir)
    : ctx_(ctx),
      state_(ctx.state),
      recent_((fs::path(configDir) / "recent.json").string()),
      lastAutosave_(std::chrono::steady_clock::now()) {
    recent_.load();
    state_.recent = recent_.paths();
}

std::string ProjectController::title() const {
    std::string t = "RRF Workbench - " + state_.projectName();
    if (state_.dirty) t += " *";
    return t;
}

bool ProjectController::whenSaved(PendingAction action) {
    if (!state_.dirty) {
        carryOut(action);
        return true;
    }
    pending_ = std::move(action);
    promptRequested_ = true;
    return false;
}

void ProjectController::carryOut(const PendingAction& action) {
    switch (action.kind) {
        case PendingAction::Quit: quitConfirmed_ = true; break;
        case PendingAction::Open:
            if (action.path.empty()) {
                if (chooseFile) chooseFile(false);
            } else {
                open(action.path);
            }
            break;
        case PendingAction::New:
            if (chooseFile) chooseFile(true);
            break;
        case PendingAction::None: break;
    }
}

void ProjectController::answer(UnsavedChoice choice) {
    const PendingAction action = std::move(pending_);
    pending_ = PendingAction{};
    if (choice == UnsavedChoice::Cancel) return;
    // An untitled project's Save opens Save As instead and returns false: the action waits for the
    // user to ask again rather than discarding the work.
    if (choice == UnsavedChoice::Save && !save()) return;
    carryOut(action);
}

bool ProjectController::takePromptRequest() {
    const bool requested = promptRequested_;
    promptRequested_ = false;
    return requested;
}

bool ProjectController::open(const std::string& path) {
    std::string error;
    if (!panels::loadProjectIntoState(state_, path, error)) {
        if (onError) onError("Cannot open project", error + (state_.hasProject ? "\n\nThe open project was kept." : ""));
        return false;
    }
    ctx_.untitled = false;
    if (!recent_.add(path)) state_.log.warning("could not update the recent projects list");
    state_.recent = recent_.paths();
    std::error_code ec;
    const std::string autosave = autosavePath(path);
    if (fs::exists(autosave, ec) && fs::last_write_time(autosave, ec) > fs::last_write_time(path, ec))
        state_.log.warning("an autosave copy newer than the project exists: " + autosave +
                           " (open it to recover unsaved work)");
    // The other controllers drop the previous project's jobs and take up this one.
    if (onOpened) onOpened();
    lastAutosave_ = std::chrono::steady_clock::now();
    return true;
}

void ProjectController::newFromScene(const std::string& scenePath) {
    if (!open(scenePath)) return;
    // A new project references the scene and has no file yet: the first Save asks where.
    ctx_.untitled = true;
    state_.project.name = "untitled";
    state_.dirty = true;
}

bool ProjectController::save(const std::string& requested) {
    if (!state_.hasProject) return false;
    if (requested.empty() && (ctx_.untitled || state_.project.path.empty())) {
        state_.request(panels::Command::SaveProjectAs);
        return false;
    }
    const std::string path = requested.empty() ? state_.project.path : requested;
    std::string error;
    if (!panels::saveStateToProject(state_, path, error)) {
        if (onError) onError("Cannot save project", error);
        return false;
    }
    ctx_.untitled = false;
    std::error_code ec;
    fs::remove(autosavePath(path), ec);  // the real file is now at least as new
    recent_.add(path);
    state_.recent = recent_.paths();
    state_.notify(panels::LogLevel::Info, "", "saved " + path);
    return true;
}

void ProjectController::autosave() {
    const auto now = std::chrono::steady_clock::now();
    if (now - lastAutosave_ < kAutosaveInterval) return;
    lastAutosave_ = now;
    if (!state_.dirty || ctx_.untitled || !state_.hasProject || state_.project.path.empty()) return;
    // Save a copy so the project itself (and its path) stay as the user left them.
    panels::storeWorkbenchSections(state_);
    Project copy = state_.project;
    try {
        rrf::saveProject(copy, autosavePath(state_.project.path));
        state_.log.info("autosaved to " + autosavePath(state_.project.path));
    } catch (const std::exception& e) {
        state_.log.warning(std::string("autosave failed: ") + e.what());
    }
}

}  // namespace rrf
