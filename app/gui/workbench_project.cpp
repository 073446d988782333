// Workbench: what a newly opened project needs of the controllers.
#include "app/gui/workbench.h"

#include <filesystem>

#include "core/pipeline/run_recording.h"

namespace rrf {

namespace fs = std::filesystem;

std::string Workbench::projectDir() const { return ctx_.projectDir(); }

void Workbench::projectOpened() {
    // Stop the previous project's jobs and forget their sessions, so that nothing they finish lands
    // in this project (their workers still complete into the old project's directory). The new
    // ground truth starts converging right away.
    dropJobs();
    // Models belong to the previous project; the last training run's models (if still on disk)
    // drive the prediction of this one.
    prediction_.reset();
    // They are read on a worker; the last evaluation is restored once they are loaded, since it is
    // shown only when it judged them.
    std::error_code ec;
    for (auto it = state_.project.runs.rbegin(); it != state_.project.runs.rend(); ++it) {
        // A stopped run's partial set is shown only when the user chooses it (Compare).
        if (it->kind != "train" || it->artifacts.empty() || isStoppedTrainRun(*it)) continue;
        const fs::path models = fs::path(projectDir()) / fs::path(it->artifacts.front()).parent_path();
        if (fs::exists(models / "models.json", ec)) loadModels(models.string(), nullptr, [this] { evaluation_.restoreEvaluation(); });
        break;
    }
    evaluation_.restoreSweeps();
    history_.reset(state_.project);  // undo never crosses into another project
    sceneChanged(true);
}

}  // namespace rrf
