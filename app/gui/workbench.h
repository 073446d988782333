#pragma once
/// The workbench application: the host window with menu bar, split panes and tabs, the modals, the
/// file dialogs, the status bar and the GL textures of the views, composed of the controllers that
/// own the project and the background jobs: ProjectController (the project file and the
/// unsaved-changes prompt), GroundTruthController (the render), TrainingController (data and
/// training), PredictionController (the live prediction, its drafts and overlays),
/// EvaluationController (evaluations, run pairs, light grids, sweeps), PipelineController (the
/// one-click chain) and RunsController (saving, comparing and re-opening runs; image export). Panels (panels/) draw and edit the state and queue Requests; this class carries
/// them out between frames, mostly by handing them to a controller. UI thread only.

#include <array>
#include <chrono>
#include <functional>
#include <memory>
#include <string>

#include "app/gui/frame_stats.h"
#include "app/gui/gl_texture.h"
#include "app/gui/job_runner.h"
#include "app/gui/job_session.h"
#include "app/gui/controller_context.h"
#include "app/gui/evaluation_controller.h"
#include "app/gui/ground_truth_controller.h"
#include "app/gui/picking_controller.h"
#include "app/gui/pipeline_controller.h"
#include "app/gui/project_controller.h"
#include "app/gui/runs_controller.h"
#include "app/gui/prediction_controller.h"
#include "app/gui/shortcuts.h"
#include "app/gui/training_controller.h"
#include "core/project/settings_history.h"
#include "app/gui/user_config.h"
#include "panels/file_dialog.h"
#include "panels/view_model.h"
#include "panels/workbench_state.h"

namespace rrf {

class Workbench {
public:
    /// `configDir`: per-user directory for recent.json.
    explicit Workbench(const std::string& configDir);
    ~Workbench();

    /// Opens a project or bare scene. A file that cannot be read is reported in the log and in a
    /// modal, and the open project stays; returns false then.
    bool openProject(const std::string& path) { return project_.open(path); }
    /// Saves to `path` (empty: the project's own path, or Save As when it has none).
    bool saveProject(const std::string& path = {}) { return project_.save(path); }

    /// One frame: pick up job results, draw the workspace, carry out requests, upload textures.
    void frame();

    /// The user (or the window manager) asked to quit. Returns true when it may happen now;
    /// with unsaved changes it opens the "Unsaved changes" modal and returns false.
    bool requestQuit();
    /// What the "Unsaved changes" prompt asks about: the one guard of quitting, opening a project
    /// (File > Open, Recent, the Project panel) and starting a new one.
    using UnsavedChoice = ProjectController::UnsavedChoice;
    /// Opens `path` (empty: the Open dialog) once unsaved changes are saved or discarded; with
    /// unsaved changes it asks first (Save / Discard / Cancel), as quitting does.
    void requestOpen(const std::string& path) { project_.whenSaved({ProjectController::PendingAction::Open, path}); }
    /// True while the "Unsaved changes" prompt waits for an answer.
    bool unsavedPromptOpen() const { return project_.promptOpen(); }
    /// Answers the prompt (its buttons call this; so do scripts): Save saves and then carries out
    /// the action (not when saving fails), Discard carries it out, Cancel forgets it.
    void answerUnsavedPrompt(UnsavedChoice choice) { project_.answer(choice); }
    /// True once the user confirmed quitting (from the modal or the File menu).
    bool quitConfirmed() const { return project_.quitConfirmed(); }
    /// Window title: "RRF Workbench - <project>" with "*" for unsaved changes.
    std::string title() const { return project_.title(); }
    /// A screenshot path requested from the menu (empty if none); cleared by the call.
    std::string takeScreenshotRequest();

    /// Starts the ground-truth render of the current scene (refused while one runs).
    bool startRender() { return groundTruth_.start(); }
    bool renderRunning() const { return groundTruth_.running(); }
    /// A scene edit asked for a new render that has not started yet (the old one stops, or the
    /// edits of a drag have not rested).
    bool renderRestartPending() const { return groundTruth_.restartPending(); }
    /// The render has ended and its last snapshot is what the views show (a render that ends after
    /// this frame's poll is not running but not shown yet).
    bool renderShown() const { return groundTruth_.shown(); }
    /// Asks the running render (if any) to stop; it stops at its next pass boundary.
    void cancelRender() { groundTruth_.cancel(); }
    /// The run actions (RunsController): save the ground truth as a run, compare with a run,
    /// re-open a run, export the images on screen.
    bool saveRun() { return runs_.saveRun(); }
    bool compareRun(int index) { return runs_.compareRun(index); }
    /// Predicts the models of training runs runPair.a and runPair.b at the current light (and judges
    /// each against the ground truth, when there is one) on a worker; the Views then show A | B |
    /// difference and the Objects panel their per-object errors side by side.
    bool compareRunPair() { return evaluation_.compareRunPair(); }
    bool reopenRun(int index) { return runs_.reopenRun(index); }
    bool exportImages(const std::string& dir) { return runs_.exportImages(dir, viewModel_.error()); }
    /// Starts the data generator with the project's sampling settings, writing
    /// <project dir>/data/dataset.rrfd (refused while a conflicting job runs).
    bool startGenerate() { return training_.startGenerate(); }
    bool generateRunning() const { return training_.generateRunning(); }
    /// Trains the project's networks on the generated dataset (or <project dir>/data/dataset.rrfd);
    /// `maxEpochs` > 0 overrides the trainer's epoch limit. When done the models are saved under
    /// runs/<run>/models, a "train" run is recorded and the models drive the live prediction.
    bool startTrain(int maxEpochs = 0) { return training_.startTrain(maxEpochs); }
    bool trainRunning() const { return training_.trainRunning(); }
    /// Loads a model directory for the live prediction (GLSL, else CPU). `preloaded`: the set a
    /// worker already read from `dir` (a finished training), so only the GL upload is left;
    /// without it the set is read on a worker first. The upload follows a frame whose status bar
    /// says shaders are compiled (PredictionController::loadModels); `then` runs once the models
    /// drive the prediction.
    bool loadModels(const std::string& dir, std::shared_ptr<const ModelSet> preloaded = nullptr,
                    std::function<void()> then = nullptr) {
        return prediction_.loadModels(dir, std::move(preloaded), std::move(then));
    }
    /// True while something the UI asked for is read or built on a worker and has not arrived:
    /// the picking map, a model set, a run's images (what the scripts' "wait": "loads" waits for).
    bool loadsPending() const { return picking_.pending() || prediction_.modelsLoading() || runs_.loading(); }
    /// Compares the prediction with the ground truth per object and term (fills the Objects panel).
    bool startEvaluate() { return evaluation_.startEvaluate(); }
    bool evaluateRunning() const { return evaluation_.evaluateRunning(); }
    /// A manual training finished and its models wait to be evaluated (once the ground truth of the
    /// current light is rendered), so every run gets its error without pressing Evaluate.
    bool evaluationPending() const { return evaluation_.evaluationPending(); }
    /// What the shortcut `action` does (its key, its menu item).
    void performShortcut(ShortcutAction action);
    const SettingsHistory& settingsHistory() const { return history_; }
    bool helpOpen() const { return helpOpen_; }
    /// Frames in which the status bar showed the idle line although the pipeline was running.
    int statusIdleWhilePipeline() const { return statusIdleWhilePipeline_; }
    /// Whether the live prediction on screen is a draft (the light moved less than kDraftRestSeconds ago).
    bool draftShown() const { return prediction_.draftShown(); }
    /// The live prediction's controller (read-only: tests and the script's checks).
    /// Makes the live prediction's GL worker (PredictionController::startGlWorker): main thread,
    /// once, before the first frame.
    void startGlWorker() { prediction_.startGlWorker(); }
    const PredictionController& prediction() const { return prediction_; }
    /// Writes the Objects table (the views' term, the table's sort order) as CSV, atomically.
    bool exportObjectsCsv(const std::string& path) { return evaluation_.exportObjectsCsv(path); }
    /// The one-click pipeline (PipelineController): applies `preset` (core/pipeline/presets.h) to the
    /// project's data and network settings, then renders the ground truth (or keeps a finished one),
    /// generates the dataset, trains and evaluates, one job after the other, each the same job its
    /// own button starts. Refused (false, with a notice) without a saved project or while a job runs.
    bool startPipeline(const std::string& preset) { return pipeline_.start(preset); }
    /// The pipeline with the settings in effect (no preset applied); `label` names them in its
    /// display and log (a script that shrank a preset's sizes).
    bool runPipeline(const std::string& label) { return pipeline_.run(label); }
    /// Stops the running stage's job (its job stops within a second) and the stages after it.
    void cancelPipeline() { pipeline_.cancel(); }
    bool pipelineRunning() const { return pipeline_.running(); }
    /// Runs a cost sweep of one of the kinds in kSweepKinds (core/pipeline/sweep.h) with interactive sizes.
    bool startSweep(const std::string& what) { return evaluation_.startSweep(what); }
    bool sweepRunning() const { return evaluation_.sweepRunning(); }
    /// The Light region panel's evaluation of the loaded models (app/gui/evaluation_light_grid.cpp).
    bool startLightGrid() { return evaluation_.startLightGrid(); }
    bool lightGridRunning() const { return evaluation_.lightGridRunning(); }

    /// True while something changes without input (a job or the pipeline runs, a mouse button is
    /// held): the window then redraws at its frame rate, otherwise it waits for events.
    bool busy() const;
    /// The UI thread's frame times (the window loop adds each frame's work time).
    FrameStats& frameStats() { return frameStats_; }
    /// The live prediction's recent frame times (seconds): GLSL frames on the UI thread where the
    /// GLSL path runs, else the CPU jobs'.
    const std::vector<double>& predictionSeconds() const { return prediction_.frameSeconds(); }
    /// The recent draft frames' prediction times while the light was dragged (seconds).
    const std::vector<double>& draftSeconds() const { return prediction_.draftSeconds(); }

    panels::WorkbenchState& state() { return state_; }
    JobRunner& jobs() { return jobs_; }

private:
    enum class DialogPurpose { None, Open, SaveAs, New, ExportImages, ExportScreenshot, ExportObjectsCsv };

    void drawHost();
    void drawMenuBar();
    void drawStatusBar();
    void drawModals();
    /// The frame-time overlay (View > Frame time overlay, F3): last, median and 95th percentile.
    void drawFrameOverlay();
    void handleRequests();
    void openDialog(DialogPurpose purpose);
    void dialogConfirmed(const std::string& path);

    /// state().availableMemory from the machine, about once a second.
    void refreshAvailableMemory();
    /// The pipeline's stages as their owners offer them (PipelineController::StageHooks).
    std::array<PipelineController::StageHooks, PipelineController::kStages> pipelineStages();
    /// Logs the jobs that ended since the last frame (finished, stopped or failed).
    void logFinishedJobs();
    /// Cancels every session's job and forgets it, so nothing a previous project's job finishes
    /// lands in the project opened now.
    void dropJobs();
    /// The scene changed. `geometryChanged` false means materials or the movable light only: the
    /// light is not in the BVH, so the picking BVH and the object-id buffer stay valid then.
    void sceneChanged(bool restartRender, bool geometryChanged = true);
    /// A project was opened (ProjectController::onOpened): the controllers drop the previous
    /// project's jobs and take up this one (its last models, its sweeps, its ground truth).
    void projectOpened();
    void showError(const std::string& title, const std::string& message);
    /// One panel request; `sceneEdited` collects scene edits so a frame restarts the render once.
    void handleRequest(const panels::Request& r, bool& sceneEdited);
    std::string projectDir() const;

    panels::WorkbenchState state_;
    JobRunner jobs_;
    ControllerContext ctx_{state_, jobs_};
    panels::ViewModel viewModel_;
    GlTexture textures_[3];
    panels::FileDialog dialog_;
    DialogPurpose dialogPurpose_ = DialogPurpose::None;

    bool helpOpen_ = false;  ///< the Help window (F1)
    SettingsHistory history_;  ///< undo/redo of setting edits (observed once per settled frame)
    void applySettings(const std::optional<ProjectSettings>& settings, const char* what);
    int statusIdleWhilePipeline_ = 0;  ///< frames whose status bar said idle while the pipeline ran
    // The controllers, each owning its jobs (job_session.h) and publishing its sections of state_.
    GroundTruthController groundTruth_{ctx_};
    PickingController picking_{ctx_};  ///< the views' picking BVH and object-id map, built on a worker
    PredictionController prediction_{ctx_};
    TrainingController training_{ctx_, prediction_.live()};
    EvaluationController evaluation_{ctx_, prediction_};
    ProjectController project_;
    PipelineController pipeline_;
    RunsController runs_{ctx_, groundTruth_, prediction_, [this] { sceneChanged(false); }};
    std::chrono::steady_clock::time_point memoryCheckedAt_{};

    bool aboutModal_ = false;
    std::string errorTitle_, errorMessage_;
    bool errorModal_ = false;
    std::string screenshotRequest_;
    FrameStats frameStats_;
    bool frameOverlay_ = false;
};

}  // namespace rrf
