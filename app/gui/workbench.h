#pragma once
/// The workbench application: the host window with menu bar, split panes and tabs, the modals, the
/// background jobs and the GL textures of the views. Panels (panels/) draw and edit the state and
/// queue Requests; this class carries them out between frames. UI thread only.

#include <chrono>
#include <memory>
#include <string>
#include <tuple>

#include "app/gui/frame_stats.h"
#include "app/gui/gl_texture.h"
#include "app/gui/job_runner.h"
#include "app/gui/job_session.h"
#include "app/gui/live_prediction.h"
#include "app/gui/prediction_draft.h"
#include "app/gui/render_session.h"
#include "app/gui/shortcuts.h"
#include "core/pipeline/run_recording.h"
#include "core/project/settings_history.h"
#include "app/gui/user_config.h"
#include "panels/file_dialog.h"
#include "panels/view_model.h"
#include "panels/workbench_state.h"

namespace rrf {

struct GeneratedDataset;
struct TrainingOutcome;
struct TrainingLive;
struct EvaluationOutcome;
struct TimedPrediction;
struct CpuFrame;
struct LightGridResult;
struct SweepOutcome;
struct SweepResult;
struct PairOutcome;
struct LeafOverlay;

class Workbench {
public:
    /// `configDir`: per-user directory for recent.json.
    explicit Workbench(const std::string& configDir);
    ~Workbench();

    /// Opens a project or bare scene. A file that cannot be read is reported in the log and in a
    /// modal, and the open project stays; returns false then.
    bool openProject(const std::string& path);
    /// Saves to `path` (empty: the project's own path, or Save As when it has none).
    bool saveProject(const std::string& path = {});

    /// One frame: pick up job results, draw the workspace, carry out requests, upload textures.
    void frame();

    /// The user (or the window manager) asked to quit. Returns true when it may happen now;
    /// with unsaved changes it opens the "Unsaved changes" modal and returns false.
    bool requestQuit();
    /// What the "Unsaved changes" prompt asks about: the one guard of quitting, opening a project
    /// (File > Open, Recent, the Project panel) and starting a new one.
    enum class UnsavedChoice { Save, Discard, Cancel };
    /// Opens `path` (empty: the Open dialog) once unsaved changes are saved or discarded; with
    /// unsaved changes it asks first (Save / Discard / Cancel), as quitting does.
    void requestOpen(const std::string& path);
    /// True while the "Unsaved changes" prompt waits for an answer.
    bool unsavedPromptOpen() const { return pending_.kind != PendingAction::None; }
    /// Answers the prompt (its buttons call this; so do scripts): Save saves and then carries out
    /// the action (not when saving fails), Discard carries it out, Cancel forgets it.
    void answerUnsavedPrompt(UnsavedChoice choice);
    /// True once the user confirmed quitting (from the modal or the File menu).
    bool quitConfirmed() const { return quitConfirmed_; }
    /// Window title: "RRF Workbench - <project>" with "*" for unsaved changes.
    std::string title() const;
    /// A screenshot path requested from the menu (empty if none); cleared by the call.
    std::string takeScreenshotRequest();

    /// Starts the ground-truth render of the current scene (refused while one runs).
    bool startRender();
    bool renderRunning() const;
    /// The render has ended and its last snapshot is what the views show (a render that ends after
    /// this frame's poll is not running but not shown yet).
    bool renderShown() const;
    /// Asks the running render (if any) to stop; it stops at its next pass boundary.
    void cancelRender();
    /// Records the current ground truth as a run (files under <project dir>/runs/<id>/).
    bool saveRun();
    bool compareRun(int index);
    /// Predicts the models of training runs runPair.a and runPair.b at the current light (and judges
    /// each against the ground truth, when there is one) on a worker; the Views then show A | B |
    /// difference and the Objects panel their per-object errors side by side.
    bool compareRunPair();
    bool reopenRun(int index);
    bool exportImages(const std::string& dir);
    /// Starts the data generator with the project's sampling settings, writing
    /// <project dir>/data/dataset.rrfd (refused while a conflicting job runs).
    bool startGenerate();
    bool generateRunning() const;
    /// Trains the project's networks on the generated dataset (or <project dir>/data/dataset.rrfd);
    /// `maxEpochs` > 0 overrides the trainer's epoch limit. When done the models are saved under
    /// runs/<run>/models, a "train" run is recorded and the models drive the live prediction.
    bool startTrain(int maxEpochs = 0);
    bool trainRunning() const;
    /// Loads a model directory for the live prediction (GLSL, else CPU). `preloaded`: the set a
    /// worker already read from `dir` (a finished training), so only the GL upload is left here.
    bool loadModels(const std::string& dir, std::shared_ptr<const ModelSet> preloaded = nullptr);
    /// Recomputes the Views leaf overlay (leaf per pixel) when it is on and the prediction changed.
    void updateLeafOverlay();
    /// The Views' FLIP map while it is selected: one worker at a time for the images on screen
    /// (app/gui/workbench_flip.cpp).
    void updateFlipMap();
    /// The Views' spread map while it is on: one worker at a time for the prediction on screen
    /// (app/gui/workbench_spread.cpp).
    void updateSpreadMap();
    /// Compares the prediction with the ground truth per object and term (fills the Objects panel).
    bool startEvaluate();
    bool evaluateRunning() const;
    /// A manual training finished and its models wait to be evaluated (once the ground truth of the
    /// current light is rendered), so every run gets its error without pressing Evaluate.
    bool evaluationPending() const { return evaluateAfterTrain_; }
    /// What the shortcut `action` does (its key, its menu item).
    void performShortcut(ShortcutAction action);
    const SettingsHistory& settingsHistory() const { return history_; }
    bool helpOpen() const { return helpOpen_; }
    /// Frames in which the status bar showed the idle line although the pipeline was running.
    int statusIdleWhilePipeline() const { return statusIdleWhilePipeline_; }
    /// Whether the live prediction on screen is a draft (the light moved less than kDraftRestSeconds ago).
    bool draftShown() const { return draftShown_; }
    /// Writes the Objects table (the views' term, the table's sort order) as CSV, atomically.
    bool exportObjectsCsv(const std::string& path);
    /// The one-click pipeline: applies `preset` (core/pipeline/presets.h) to the project's data and
    /// network settings, then renders the ground truth (or keeps a finished one), generates the
    /// dataset, trains and evaluates, one job after the other, each the same job its own button
    /// starts. state().pipeline shows one progress display (overall fraction weighted by the stages'
    /// estimates, current stage, ETA); the trained models become a run in the runs table with their
    /// evaluation. Refused (false, with a notice) without a saved project or while a job runs.
    bool startPipeline(const std::string& preset);
    /// The pipeline with the settings in effect (no preset applied); `label` names them in its
    /// display and log (a script that shrank a preset's sizes).
    bool runPipeline(const std::string& label);
    /// Stops the running stage's job (its job stops within a second) and the stages after it.
    void cancelPipeline();
    bool pipelineRunning() const { return pipeline_.stage != PipelineStage::Idle; }
    /// Runs a cost sweep of one of the kinds in kSweepKinds (core/pipeline/sweep.h) with interactive sizes.
    bool startSweep(const std::string& what);
    bool sweepRunning() const;
    /// The Light region panel's evaluation of the loaded models (app/gui/workbench_light_grid.cpp).
    bool startLightGrid();
    bool lightGridRunning() const;
    /// The Cost panel's series of the project's sweeps on disk (<project dir>/sweeps/*.json), as they
    /// were when they finished: called when a project is opened.
    void restoreSweeps();

    /// True while something changes without input (a job or the pipeline runs, a mouse button is
    /// held): the window then redraws at its frame rate, otherwise it waits for events.
    bool busy() const;
    /// The UI thread's frame times (the window loop adds each frame's work time).
    FrameStats& frameStats() { return frameStats_; }
    /// The live prediction's recent frame times (seconds): GLSL frames on the UI thread where the
    /// GLSL path runs, else the CPU jobs'.
    const std::vector<double>& predictionSeconds() const {
        return frameSeconds_[live_.usesGlsl() ? kGlslFrames : kCpuFrames];
    }
    /// The recent draft frames' prediction times while the light was dragged (seconds).
    const std::vector<double>& draftSeconds() const { return draftSeconds_; }

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
    void newProjectFromScene(const std::string& scenePath);

    void pollRender();
    void pollGenerate();
    void pollTrain();
    void pollEvaluate();
    /// Starts the evaluation a manual training asked for when its ground truth is ready, or says why
    /// it cannot be made (a notice on the Training panel).
    void pollEvaluateAfterTrain();
    /// state().availableMemory from the machine, about once a second.
    void refreshAvailableMemory();
    void pollPredict();
    void pollSweep();
    void pollLightGrid();
    /// Adds `r`'s series to the Cost panel, named "sweep <what>" (" #n" for the n-th of a kind).
    void addSweepSeries(const SweepResult& r);
    /// Moves the pipeline to its next stage once the current one delivered, publishes its progress.
    void pollPipeline();
    enum class PipelineStage { Idle, Render, Generate, Train, Evaluate };
    /// Starts `stage`'s job; false (the pipeline ends with `why`) when it is refused.
    bool beginPipelineStage(PipelineStage stage);
    void endPipeline(const std::string& outcome);
    /// Why the pipeline cannot start now ("" when it can).
    std::string pipelineRefusal() const;
    /// Logs the jobs that ended since the last frame (finished, stopped or failed).
    void logFinishedJobs();
    /// Cancels every session's job and forgets it, so nothing a previous project's job finishes
    /// lands in the project opened now.
    void dropJobs();
    /// A finished training run: records it as a run and loads its models.
    void trainingFinished(TrainingOutcome& outcome);
    /// Brings the middle view's prediction up to date with the scene's light (GLSL now, or a CPU job).
    void refreshPrediction();
    /// The CPU prediction as a job (the fallback path, and the glossy gather after a GLSL frame).
    void startCpuPrediction(const Camera& camera);
    bool predictRunning() const;
    /// Adds the CPU prediction's images to an export directory (no-op without models).
    bool exportPrediction(const std::string& dir);
    /// Re-opens / compares a training run (project.runs[index]): restores its network and trainer
    /// settings and loads its models.
    bool loadTrainRun(const Run& run);
    /// The dataset training reads: this session's, else the project's data/dataset.rrfd if present.
    std::string datasetPath() const;
    /// The scene changed. `geometryChanged` false means materials or the movable light only: the
    /// light is not in the BVH, so the picking BVH and the object-id buffer stay valid then.
    void sceneChanged(bool restartRender, bool geometryChanged = true);
    void rebuildPicking();
    void autosave();
    void showError(const std::string& title, const std::string& message);
    /// One panel request; `sceneEdited` collects scene edits so a frame restarts the render once.
    void handleRequest(const panels::Request& r, bool& sceneEdited);
    std::string projectDir() const;

    panels::WorkbenchState state_;
    JobRunner jobs_;
    panels::ViewModel viewModel_;
    GlTexture textures_[3];
    panels::FileDialog dialog_;
    DialogPurpose dialogPurpose_ = DialogPurpose::None;
    RecentProjects recent_;

    // One session per kind of job (job_session.h). render_ and train live hold what the UI shows
    // while the job runs; the sessions deliver each job's result once it has ended.
    std::shared_ptr<RenderSession> render_;  ///< the current ground truth's render (snapshots, outputs)
    JobSession<void> renderJob_{jobs_, JobKind::Render, state_.log};
    uint64_t renderRevision_ = 0;
    panels::ImageStamp renderStamp_;  ///< what the current render's images are of (light, scene, size)
    JobSession<GeneratedDataset> generateJob_{jobs_, JobKind::Generate, state_.log};
    std::shared_ptr<TrainingLive> trainLive_;  ///< loss curves of the running training, for the plot
    JobSession<TrainingOutcome> trainJob_{jobs_, JobKind::Train, state_.log};
    uint64_t trainRevision_ = 0;
    JobSession<EvaluationOutcome> evaluateJob_{jobs_, JobKind::Evaluate, state_.log};
    JobSession<TimedPrediction> predictJob_{jobs_, JobKind::Predict, state_.log};
    /// Recent per-frame prediction times of the loaded models (seconds), whose median is recorded
    /// in their training run (runs table: "frame ms").
    /// Recent frame times per kind (a GLSL frame and the CPU frame after it are different figures),
    /// and the frames noted since each median was last recorded in the run.
    static constexpr int kGlslFrames = 0, kCpuFrames = 1;
    std::vector<double> frameSeconds_[2];
    size_t framesSinceRecorded_[2] = {0, 0};
    void noteFrameSeconds(FramePath path, double seconds, int width, int height);
    bool predictPending_ = false;  ///< the light moved while a CPU prediction ran
    /// The last CPU frame of the loaded models (app/gui/cpu_frame.h): an evaluation of the same
    /// models, settings and ground truth reuses it; a manual Train's evaluation waits for it.
    std::shared_ptr<const CpuFrame> lastCpuFrame_;
    /// Light-drag drafts (app/gui/prediction_draft.h): the light position of the last GLSL frame,
    /// whether one was rendered for the loaded models, whether the view shows a draft and when
    /// that draft was rendered (the full frame follows kDraftRestSeconds later), draft frame times.
    Vec3 predictedLight_{};
    bool predictedOnce_ = false;
    bool draftShown_ = false;
    bool helpOpen_ = false;  ///< the Help window (F1)
    SettingsHistory history_;  ///< undo/redo of setting edits (observed once per settled frame)
    void applySettings(const std::optional<ProjectSettings>& settings, const char* what);
    int statusIdleWhilePipeline_ = 0;  ///< frames whose status bar said idle while the pipeline ran
    std::chrono::steady_clock::time_point draftTime_{};
    std::vector<double> draftSeconds_;
    int draftDivisor_ = kMaxDraftDivisor;  ///< resolution divisor of the next draft (adapts to its time)
    /// Renders the full-quality frame once the light has rested after a drag.
    void finishDraft();
    JobSession<SweepOutcome> sweepJob_{jobs_, JobKind::Sweep, state_.log};
    JobSession<LightGridResult> lightGridJob_{jobs_, JobKind::LightGrid, state_.log};
    JobSession<PairOutcome> pairJob_{jobs_, JobKind::Compare, state_.log};
    void pollRunPair();
    /// The Views' leaf overlay, computed on a worker (a G-buffer and a leaf lookup per pixel).
    JobSession<LeafOverlay> overlayJob_{jobs_, JobKind::Overlay, state_.log};
    uint64_t overlayFor_ = 0;  ///< the prediction revision the last overlay job was started for
    /// The Views' FLIP map (HDR-FLIP of the compared image against the ground truth), on a worker.
    JobSession<panels::FlipViewMap> flipJob_{jobs_, JobKind::Overlay, state_.log};
    /// What the last FLIP job was started for (ground truth and compared revisions, term).
    std::tuple<uint64_t, uint64_t, Term> flipFor_{0, 0, Term::Global};
    uint64_t flipMaps_ = 0;  ///< FLIP maps delivered (their revisions)
    /// The Views' spread map (the ensemble members' relative spread of the prediction), on a worker.
    JobSession<panels::SpreadViewMap> spreadJob_{jobs_, JobKind::Spread, state_.log};
    uint64_t spreadFor_ = 0;   ///< the prediction revision the last spread job was started for
    uint64_t spreadMaps_ = 0;  ///< spread maps delivered (their revisions)
    LivePrediction live_;
    /// Results each kind of job delivered so far: the pipeline advances when its stage's count grew
    /// and fails when the job ended without one (stopped, refused, failed).
    uint64_t datasetsDelivered_ = 0, trainingsCompleted_ = 0, evaluationsDelivered_ = 0;
    bool evaluateAfterTrain_ = false;  ///< see evaluationPending()
    std::chrono::steady_clock::time_point memoryCheckedAt_{};
    struct PipelineRun {
        PipelineStage stage = PipelineStage::Idle;
        uint64_t mark = 0;                  ///< the stage's delivery count when it started
        double weights[4] = {0, 0, 0, 0};   ///< estimated seconds per stage (render, generate, train, evaluate)
        double spent[4] = {0, 0, 0, 0};     ///< measured seconds of the stages done (0: skipped)
        std::chrono::steady_clock::time_point start, stageStart;
        bool cancelled = false;
        std::string preset;
    } pipeline_;
    bool restartRender_ = false;   ///< a scene edit arrived while the old render was stopping
    bool untitled_ = false;        ///< the project has no file of its own yet (New)

    /// An action waiting for the "Unsaved changes" prompt.
    struct PendingAction {
        enum Kind { None, Quit, Open, New } kind = None;
        std::string path;  ///< Open: the project (empty: ask with the dialog)
    };
    /// Carries out `action` now when nothing is unsaved, else keeps it and opens the prompt.
    /// Returns true when it was carried out now.
    bool whenSaved(PendingAction action);
    void carryOut(const PendingAction& action);
    PendingAction pending_;
    bool unsavedModal_ = false;  ///< open the prompt's popup next frame
    bool quitConfirmed_ = false, aboutModal_ = false;
    std::string errorTitle_, errorMessage_;
    bool errorModal_ = false;
    std::string screenshotRequest_;
    FrameStats frameStats_;
    bool frameOverlay_ = false;
    std::chrono::steady_clock::time_point lastAutosave_;
};

}  // namespace rrf
