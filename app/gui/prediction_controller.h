#pragma once
/// The trained models' prediction as a controller: the live prediction of the middle view (GLSL on
/// the GL worker, app/gui/live_prediction.h, or CPU Predict jobs), the light-drag drafts
/// (prediction_draft.h), the frame times recorded in the models' training run, and the Views'
/// overlays computed from the prediction on workers: the leaf overlay, the FLIP map
/// (prediction_flip.cpp) and the spread map (prediction_spread.cpp). It owns the LivePrediction and
/// those job sessions and publishes state.prediction, state.leaves, state.view.flipMap and
/// state.view.spreadMap. UI thread only.

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "app/gl/program_binary_cache.h"
#include "app/gui/controller_context.h"
#include "app/gui/job_session.h"
#include "app/gui/live_prediction.h"
#include "app/gui/prediction_draft.h"
#include "app/gui/read_back.h"
#include "core/pipeline/run_recording.h"

namespace rrf {

struct CpuFrame;
struct LeafOverlay;
struct TimedPrediction;

class PredictionController {
public:
    explicit PredictionController(ControllerContext& ctx);
    ~PredictionController();

    /// Loads a model directory for the live prediction (GLSL, else CPU). `preloaded`: the set a
    /// worker already read from `dir` (a finished training), so only the GL upload is left.
    /// Without it the set is read on a worker (a ReadBack job: 10-30 ms for small sets, far more
    /// for big ones, issue 29). Either way the GL upload starts in the next frame's poll(), after a
    /// frame that says so (uploadPending()), and the GL worker compiles the shaders while the UI
    /// goes on (glslBuilding()); the view keeps the prediction it had meanwhile, and a newer load replaces one in flight. `then` runs once the models drive
    /// the prediction (not when the load failed). Returns false only for an empty `dir`; a load that
    /// fails says so in the log and at the Project panel.
    bool loadModels(const std::string& dir, std::shared_ptr<const ModelSet> preloaded = nullptr,
                    std::function<void()> then = nullptr);
    /// Makes the GL worker of the live prediction (app/gl/gl_worker.h) now, on the main thread
    /// before the window is shown, rather than when the first models load (a new context takes
    /// tens of ms). Without one (no context could be made) the log says so and models run on the CPU.
    void startGlWorker();
    /// True while a model set is being read on a worker, waits for its GL upload or is uploaded.
    bool modelsLoading() const { return modelRead_.pending() || upload_.has_value() || building_.has_value(); }
    /// True while a model set waits for its GL upload, which starts in the next frame's poll():
    /// this frame says first that shaders are compiled (the status bar's note, which stays while
    /// glslBuilding()).
    bool uploadPending() const { return upload_.has_value(); }
    /// True while the GL worker builds the predictor of new models and compiles its programs.
    bool glslBuilding() const { return building_.has_value(); }
    /// The status bar has shown the note of the pending upload in this frame.
    void uploadAnnounced() { uploadAnnounced_ = upload_.has_value(); }
    /// Model sets uploaded, and how many of them after a frame that announced the upload.
    int uploads() const { return uploads_; }
    int announcedUploads() const { return announcedUploads_; }
    /// Forgets the models (another project was opened), and a set still being read or uploaded.
    void reset() {
        modelRead_.drop();
        upload_.reset();
        building_.reset();
        live_.reset();
        bands_ = BandedFrame{};
    }
    /// Brings the middle view's prediction up to date with the scene's light (GLSL now, or a CPU job).
    void refresh();
    /// The views' object-id map was replaced (it is built on a worker, app/gui/picking_controller.h):
    /// the prediction's objects without a network are found again from it.
    void objectIdsChanged();
    /// Each frame: takes a finished CPU frame, predicts again when the light moved meanwhile, and
    /// keeps the leaf overlay current.
    void poll();
    /// The Views' FLIP map while it is selected: one worker at a time for the images on screen.
    void updateFlipMap();
    /// The Views' spread map while it is on: one worker at a time for the prediction on screen.
    void updateSpreadMap();
    /// Renders the full-quality frame once the light has rested after a drag.
    void finishDraft();
    /// True while a full-quality GLSL frame is being rendered in bands (app/gui/prediction_bands.h):
    /// the frames must keep coming until it is shown.
    bool bandsPending() const { return bands_.active; }
    /// The GLSL programs of the last model load: how many came from the binary cache, how many were
    /// compiled (both 0 where the driver offers no binary format, or the load fell back to the CPU).
    const ProgramBinaryCache::Counts& lastLoadPrograms() const { return lastLoadPrograms_; }
    /// The last full-quality GLSL frame shown: its device seconds, its bands and its longest band's
    /// wall seconds on the GL worker (0 before any): what tests check instead of frame times.
    struct BandedFrameSummary {
        double gpuSeconds = 0.0, longestBand = 0.0;
        int bands = 0;
    };
    const BandedFrameSummary& lastFullFrame() const { return lastFullFrame_; }

    /// Forgets every job (a project was closed): nothing they still produce arrives.
    void drop();
    /// Adds the CPU prediction's images to an export directory (true without models: nothing to add).
    bool exportImages(const std::string& dir);

    const LivePrediction& live() const { return live_; }
    /// The last CPU frame of the loaded models (app/gui/cpu_frame.h): an evaluation of the same
    /// models, settings and ground truth reuses it.
    std::shared_ptr<const CpuFrame> lastCpuFrame() const { return lastCpuFrame_; }
    bool predictRunning() const { return predictJob_.running(); }
    /// Whether the prediction on screen is a draft (the light moved less than kDraftRestSeconds ago).
    bool draftShown() const { return draftShown_; }
    /// The live prediction's recent frame times (seconds): GLSL frames where the GLSL path runs,
    /// else the CPU jobs'.
    const std::vector<double>& frameSeconds() const { return frameSeconds_[live_.usesGlsl() ? kGlslFrames : kCpuFrames]; }
    /// The recent draft frames' prediction times while the light was dragged (seconds).
    const std::vector<double>& draftSeconds() const { return draftSeconds_; }

    /// True while a CPU frame the light asked for must wait (the Workbench: while a training runs,
    /// which needs the cores); null: never.
    std::function<bool()> holdCpuFrames;

private:
    /// Starts the GL upload of a model set read from `dir` (GLSL programs, the network texture) on
    /// the GL worker; `readSeconds`: how long reading it took, for the log.
    bool uploadModels(const std::string& dir, std::shared_ptr<const ModelSet> models, double readSeconds,
                      std::function<void()> then);
    /// Once the GL worker has built the predictor: what new models reset, the log line, the first
    /// frame, and the load's `then`.
    void finishUpload();
    /// Shows the full-quality frame whose `last` band has just finished.
    void finishBands(LivePrediction::Rows& last);
    /// The CPU prediction as a job (the fallback path, and the glossy gather after a GLSL frame).
    void startCpuPrediction(const Camera& camera);
    /// Recomputes the leaf overlay (leaf per pixel) when it is on and the prediction changed.
    void updateLeafOverlay();
    /// Starts the full-quality GLSL frame of `camera` at the current light and settings, rendered
    /// a band per UI frame by renderBand().
    void startBands(const Camera& camera);
    /// Renders the next band of the full-quality frame; shows the frame once its last band is done.
    void renderBand();
    /// Shows GLSL `images` of the current light as the prediction (a draft or a full frame).
    void showGlsl(Image images[kTermCount], const Camera& camera, bool draft);
    /// Adds a frame time of the loaded models; their median goes into the models' training run.
    void noteFrameSeconds(FramePath path, double seconds, int width, int height);

    ControllerContext& ctx_;
    panels::WorkbenchState& state_;  ///< ctx_.state: what the controller publishes into
    LivePrediction live_;
    JobSession<TimedPrediction> predictJob_;
    bool predictPending_ = false;  ///< the light moved while a CPU prediction ran
    std::shared_ptr<const CpuFrame> lastCpuFrame_;
    /// Recent frame times per kind (a GLSL frame and the CPU frame after it are different figures),
    /// and the frames noted since each median was last recorded in the run.
    static constexpr int kGlslFrames = 0, kCpuFrames = 1;
    std::vector<double> frameSeconds_[2];
    size_t framesSinceRecorded_[2] = {0, 0};
    /// Light-drag drafts (app/gui/prediction_draft.h): the light position of the last GLSL frame,
    /// whether one was rendered for the loaded models, whether the view shows a draft and when
    /// that draft was rendered (the full frame follows kDraftRestSeconds later), draft frame times.
    Vec3 predictedLight_{};
    bool predictedOnce_ = false;
    bool draftShown_ = false;
    std::chrono::steady_clock::time_point draftTime_{};
    std::vector<double> draftSeconds_;
    int draftDivisor_ = kMaxDraftDivisor;  ///< resolution divisor of the next draft (adapts to its time)
    /// The full-quality GLSL frame in progress (app/gui/prediction_bands.h): what it is of, the image
    /// rows done (from the bottom), the next band's rows, its GPU seconds and wall seconds so far.
    struct BandedFrame {
        bool active = false;
        Camera camera;
        Vec3 light{0.f};
        PredictionSettings settings;
        int rowsDone = 0, bandRows = 1, bands = 0;
        int rowsInFlight = 0;  ///< rows of the band the GL worker is rendering
        double gpuSeconds = 0.0, wallSeconds = 0.0, longestBand = 0.0;
    };
    BandedFrame bands_;
    double secondsPerRow_ = 0.0;  ///< wall seconds per row of the last full frame (0: none yet)
    bool fullFrameLogged_ = false;  ///< the first full frame of the loaded models was logged
    BandedFrameSummary lastFullFrame_;
    /// The Views' leaf overlay, computed on a worker (a G-buffer and a leaf lookup per pixel).
    JobSession<LeafOverlay> overlayJob_;
    uint64_t overlayFor_ = 0;  ///< the prediction revision the last overlay job was started for
    /// The Views' FLIP map (HDR-FLIP of the compared image against the ground truth), on a worker.
    JobSession<panels::FlipViewMap> flipJob_;
    /// What the last FLIP job was started for (ground truth and compared revisions, term).
    std::tuple<uint64_t, uint64_t, Term> flipFor_{0, 0, Term::Global};
    uint64_t flipMaps_ = 0;  ///< FLIP maps delivered (their revisions)
    /// The Views' spread map (the ensemble members' relative spread of the prediction), on a worker.
    JobSession<panels::SpreadViewMap> spreadJob_;
    uint64_t spreadFor_ = 0;   ///< the prediction revision the last spread job was started for
    uint64_t spreadMaps_ = 0;  ///< spread maps delivered (their revisions)
    ProgramBinaryCache::Counts lastLoadPrograms_{};  ///< lastLoadPrograms()
    /// A model set read from disk on a worker (loadModels without a preloaded set).
    struct ReadModels {
        std::shared_ptr<const ModelSet> models;
        std::string error;  ///< why it could not be read (names the file)
        double seconds = 0.0;
    };
    ReadBack<ReadModels> modelRead_;
    /// A set read (or trained) and waiting for its GL upload in the next poll() (uploadPending()).
    struct PendingUpload {
        std::string dir;
        std::shared_ptr<const ModelSet> models;
        double readSeconds = 0.0;
        uint64_t sceneHash = 0;  ///< the scene it was checked against
        std::function<void()> then;
        int polls = 0;  ///< polls it has waited without a frame that announced it
    };
    std::optional<PendingUpload> upload_;
    /// A set whose predictor the GL worker is building (finishUpload()).
    struct Building {
        std::string dir;
        double readSeconds = 0.0;
        std::function<void()> then;
    };
    std::optional<Building> building_;
    bool uploadAnnounced_ = false;
    int uploads_ = 0, announcedUploads_ = 0;
    /// Does the pending upload (poll()).
    void uploadPendingModels();
};

}  // namespace rrf
