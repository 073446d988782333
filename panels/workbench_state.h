#pragma once
/// State shared by the workbench's panels. The panels read and edit it on the UI thread; anything
/// that needs the window, GL or a background job is not done by a panel but asked for with a
/// Request, which the application (app/gui) carries out after the frame. That keeps every panel
/// testable in a bare ImGui context.

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <imgui.h>

#include "core/eval/error_metrics.h"
#include "core/eval/flip.h"
#include "core/eval/light_grid.h"
#include "core/predict/footprint_mask.h"
#include "core/render/term.h"
#include "core/util/vec3.h"
#include "core/scene/accel.h"
#include "core/data/generator_stats.h"
#include "core/util/image.h"
#include "core/project/project.h"
#include "panels/learning_state.h"
#include "panels/layout.h"
#include "panels/log.h"
#include "core/project/runs.h"
#include "core/pipeline/run_summary.h"

namespace rrf::panels {

/// What the middle view shows: the trained models' prediction or a saved run's images.
/// RunPair: two training runs side by side, prediction A | prediction B | their difference.
enum class CompareSource { Prediction, Run, RunPair };

/// Things panels ask the application to do.
enum class Command {
    NewProject,
    OpenProject,      ///< path
    SaveProject,
    SaveProjectAs,    ///< path
    StartRender,
    CancelRender,
    SceneChanged,     ///< materials or the light changed: rebuild and restart the ground truth
    PredictionChanged,  ///< the project's prediction settings changed: predict again (same ground truth)
    Generate,         ///< generate the training dataset with the project's sampling settings
    CancelGenerate,
    Train,            ///< train the project's networks on the dataset (a run is recorded)
    CancelTrain,      ///< stop training; the networks keep their best epoch and are saved
    Evaluate,         ///< compare the prediction with the ground truth per object and term
    ExportObjectsCsv, ///< path: the Objects table as CSV (empty path: ask)
    RunSweep,         ///< path: what to sweep ("spp", "grid", "dirs", "hidden", "trainer")
    CancelSweep,
    RunPipeline,      ///< path: a preset name (core/pipeline/presets.h): render, generate, train, evaluate
    CancelPipeline,   ///< stop the pipeline's running stage (within a second) and the stages after it
    SaveRun,          ///< record the current ground truth as a run
    ReopenRun,        ///< index: restore the run's settings and show its images as the ground truth
    CompareRun,       ///< index: show the run's images in the compare view, the error against it
    CompareRunPair,   ///< show the predictions of runPair.a and runPair.b side by side
    DeleteRun,        ///< index
    EvaluateLightRegion,  ///< judge the loaded models over lightRegion.counts (Light region panel)
    CancelLightRegion,
    ExportImages,     ///< path: a directory
    ExportScreenshot, ///< path: a PNG file
    ResetLayout,
    Quit,
};

struct Request {
    Command command;
    std::string path;
    int index = -1;
};

/// Direct, indirect and global images of one source (a render, a run, a prediction).
/// What a set of images was made for: the light's centre, the scene (Scene::contentHash, which
/// leaves the light out) and the size. Two sets compare only when their stamps agree.
struct ImageStamp {
    Vec3 light{0.f};
    uint64_t sceneHash = 0;
    int width = 0, height = 0;
    bool operator==(const ImageStamp& o) const {
        return light == o.light && sceneHash == o.sceneHash && width == o.width && height == o.height;
    }
    bool operator!=(const ImageStamp& o) const { return !(*this == o); }
};

struct ImageSet {
    Image direct, indirect, global;
    /// What the images were made for (ground truth, live predictions); none for images whose origin is
    /// not known (a run's stored images), which compare with anything of their size.
    std::optional<ImageStamp> stamp;
    /// Per-pixel, per-channel variance of the mean of each term (index int(Term)): a render's own
    /// noise (the ground truth's snapshots carry it). Empty for sources without it (runs,
    /// predictions): noise floors against them are unknown.
    Image variances[kTermCount];
    /// The footprint mask of the G-buffer these images were rendered for (their light position and
    /// size; core/predict/footprint_mask.h): the pixels every error against them is measured over,
    /// as `rrf evaluate` measures. Null when unknown (e.g. a re-opened run's images).
    std::shared_ptr<const FootprintMask> footprint;
    /// Objects in view the images have no prediction for (a partial model set: a stopped training).
    /// The Views draw them hatched magenta with a legend, never as silent black.
    std::vector<int> withoutNetwork;
    std::string label;      ///< shown above the view, e.g. "ground truth, 64 spp"
    uint64_t revision = 0;  ///< new value whenever the images change (drives the view cache and uploads)

    bool empty() const { return global.empty(); }
    /// Gives the set a revision no image set has had before. Revisions come from one process-wide
    /// counter, so replacing a set (even by an empty one) can never reproduce a revision the view
    /// cache already holds for different images.
    void touch();
    const Image& term(Term t) const { return t == Term::Direct ? direct : t == Term::Indirect ? indirect : global; }
    Image& term(Term t) { return t == Term::Direct ? direct : t == Term::Indirect ? indirect : global; }
    const Image& variance(Term t) const { return variances[int(t)]; }
};

/// The figures under the Views error map: `rrf evaluate`'s overall row for the shown term (see
/// viewErrorStats in panels/view_model.h, which fills it).
struct ViewErrorStats {
    bool valid = false;    ///< false without a footprint mask or a compared image of the same size
    /// Non-empty when the two sets were made for different lights, scenes or sizes: what the view
    /// waits for instead of showing an error against the wrong ground truth.
    std::string waiting;
    ErrorStats stats;      ///< over the footprint mask's kept pixels, with the ground truth's noise
    FootprintCounts left;  ///< object pixels the mask leaves out, per reason
};

/// The Views' FLIP map: HDR-FLIP (core/eval/flip.h) of the compared image's term against the
/// ground truth's over the ground truth's exposure range, computed on a worker by the application
/// for the image revisions and term it names, which the view shows only while they are the ones on
/// screen (an older map is never shown against newer images).
struct FlipViewMap {
    uint64_t groundTruth = 0, compared = 0;  ///< the ImageSet revisions it was computed from (0: none yet)
    Term term = Term::Global;
    Image map;                 ///< HDR-FLIP per pixel, in [0, 1]
    FlipExposureRange range;   ///< from the ground truth's image
    FlipStats stats;           ///< over the ground truth's footprint mask's kept pixels
    uint64_t revision = 0;     ///< changes whenever a new map arrives
    bool matches(uint64_t gt, uint64_t cmp, Term t) const { return revision && groundTruth == gt && compared == cmp && term == t; }
};

/// The ensemble members' spread of a prediction (core/eval/uncertainty.h), computed on a worker
/// while the Views show it: the relative spread mean_c sd_c / (|pred_c| + 0.01) per pixel.
struct SpreadViewMap {
    uint64_t prediction = 0;   ///< the prediction ImageSet revision it belongs to (0: none yet)
    Image map;                 ///< relative spread per pixel (all channels); 0 where none is known
    float scale = 0.f;         ///< top of its colour scale: the 99th percentile
    uint64_t pixels = 0;       ///< pixels with a known spread
    /// Why there is no map ("the models have no ensemble members' spread"); "" when there is one.
    std::string why;
    uint64_t revision = 0;     ///< changes whenever a new map arrives
    bool matches(uint64_t forPrediction) const { return revision && prediction == forPrediction; }
};

/// A rectangle of image pixels [x0, x1) × [y0, y1) whose figures the Views show beside the whole
/// image's (drawn with the right mouse button in any view). Empty: none.
struct ViewRegion {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool empty() const { return x1 <= x0 || y1 <= y0; }
    bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
    uint64_t pixels() const { return empty() ? 0 : uint64_t(x1 - x0) * uint64_t(y1 - y0); }
    bool operator==(const ViewRegion& o) const { return x0 == o.x0 && y0 == o.y0 && x1 == o.x1 && y1 == o.y1; }
};

/// The distribution of the error view's values over the kept pixels, on log-spaced bins (as tev's
/// log histogram): bin i holds |value| in [10^(lo + i/perDecade), 10^(lo + (i+1)/perDecade)).
struct ErrorHistogram {
    double lo = -5.0;          ///< log10 of the first bin's lower edge
    int perDecade = 4;         ///< bins per decade
    std::vector<uint64_t> counts;
    uint64_t below = 0;        ///< |value| under the first edge, zeros included
    uint64_t above = 0;        ///< |value| at or over the last edge
    uint64_t negative = 0;     ///< values < 0 (a signed map: counted by |value| in the bins too)
    uint64_t total() const;
};

/// Display settings of the three side-by-side views.
struct ViewState {
    Term term = Term::Global;   ///< the radiance term the views show
    /// The error map between the compared image and the ground truth: core's per-pixel metric
    /// (core/eval/error_metrics.h, mean over R, G, B), the quantity `rrf evaluate` reports.
    ErrorMapKind metric = ErrorMapKind::Relative;
    /// The error view shows the perceptual HDR-FLIP map (flipMap) instead of `metric`.
    bool flip = false;
    FlipViewMap flipMap;        ///< published by the application while `flip` is on
    float exposure = 0.f;       ///< stops
    float errorMax = 0.25f;     ///< top of the false-colour scale
    float zoom = 1.f;           ///< view pixels per image pixel, relative to fitting the pane
    float panX = 0.f, panY = 0.f;  ///< image-space centre offset in image pixels
    CompareSource compareSource = CompareSource::Prediction;
    bool highlight = true;      ///< dim everything but the selected object
    bool leafOverlay = false;   ///< tint the compared view by kd-tree leaf (Leaves panel)
    /// The compared view shows the ensemble members' relative spread (spreadMap) instead of the
    /// prediction: uncertainty without a reference.
    bool spread = false;
    SpreadViewMap spreadMap;    ///< published by the application while `spread` is on
    int selectedObject = -1;
    int hoverX = -1, hoverY = -1;  ///< image pixel under the mouse, -1 when none
    ViewErrorStats errorStats;  ///< published by the ViewModel each frame
    bool histogram = false;     ///< the error view's log histogram under the figures
    ErrorHistogram errorHistogram;  ///< published by the ViewModel (empty without an error map)
    ViewRegion region;          ///< the region of interest (empty: none)
    /// The region's figures, published by the ViewModel: the same statistics as errorStats over
    /// the kept pixels inside the region, and the FLIP map's over them while it is shown
    /// (regionFlip.pixels = 0 otherwise).
    ViewErrorStats regionStats;
    FlipStats regionFlip;
    /// A right-button drag in progress: the view it started in (-1: none) and its first pixel.
    int regionDragView = -1, regionAnchorX = 0, regionAnchorY = 0;
    /// A drag of the light's handle in progress: the view it started in (-1: none) and where the
    /// light was then (the drag's plane goes through it: core/scene/light_drag.h).
    int lightDragView = -1;
    Vec3 lightDragStart{0.f};
    /// Where each view drew the light's handle in the last frame (screen pixels), for scripts and
    /// tests that drag it as a user would; NaN where it drew none.
    ImVec2 lightHandle[3] = {{NAN, NAN}, {NAN, NAN}, {NAN, NAN}};
    /// The view shown when the pane is too small for three readable views side by side
    /// (ViewsLayout::single): ViewModel::kReference, kCompared or kError, picked above it.
    int singleView = 2;
    /// Where the Views panel drew in frame `drawnFrame` (screen pixels): its toolbar (every control
    /// above the views) and each view's image area (zero size for a view not drawn). Overlays use
    /// them to cover images, never controls (panels/frame_overlay.h); tests to measure.
    int drawnFrame = -1;
    ImVec2 toolbarMin{0, 0}, toolbarMax{0, 0};
    ImVec2 viewMin[3] = {}, viewMax[3] = {};
};

/// Progress of the ground-truth render, as last published by its job.
struct RenderProgress {
    bool running = false;
    /// The last render stopped before its target (the user stopped it, or an edit replaced it).
    bool cancelled = false;
    int spp = 0, targetSpp = 0;
    /// The image's relative noise: the relative RMSE noise floor of the global term over the
    /// footprint mask (core/eval/reference_noise.h, the error a perfect prediction would show against
    /// this image), computed on the render worker per pass. NaN while unknown (fewer than 2 spp).
    double relativeNoise = std::numeric_limits<double>::quiet_NaN();
    double seconds = 0.0;
    double etaSeconds = -1.0;
    double samplesPerSecond = 0.0;
};

/// The last generated dataset: where it is and what the generator did (records per object, cells
/// and rays that made no record).
struct DatasetInfo {
    bool running = false;
    double progress = 0.0;
    std::string path;  ///< empty until a dataset was written
    int inputCount = 0;  ///< network inputs per record of that dataset (0 = unknown)
    std::vector<std::string> objectNames;  ///< the scene's objects when it was generated (index = id)
    GeneratorStats generator;
    double seconds = 0.0;
    /// What the dataset at `path` was generated with, so the coverage table can say it is stale.
    std::optional<SamplingSettings> madeWith;
    uint64_t sceneHash = 0;      ///< Scene::contentHash() it was generated for (0 = unknown)
    bool lastCancelled = false;  ///< the generation after it was cancelled (nothing was written)
};

/// A problem (or warning) shown where the user is looking, besides the Log: in the status bar and
/// at the top of the panel it concerns, until dismissed or replaced by a newer one.
struct Notice {
    LogLevel level = LogLevel::Error;
    std::string panel;  ///< the tab it concerns ("Training", "Project", ...); empty: status bar only
    std::string text;
};

/// The one-click pipeline (render → generate → train → evaluate) as its progress display shows it.
struct PipelineInfo {
    /// The preset the next run applies (core/pipeline/presets.h); "" (the default) runs the project's
    /// settings as the Sampling and Network panels show them, unchanged.
    std::string preset;
    bool running = false;
    std::string stage;             ///< "render", "generate", "train", "evaluate" while running
    int stageIndex = 0;            ///< 0..3, the stage's place in the pipeline
    double fraction = 0.0;         ///< overall fraction done, stages weighted by their estimates
    double etaSeconds = -1.0;      ///< overall time left; -1 while unknown
    double seconds = 0.0;          ///< wall time so far (the whole run once it ended)
    std::string outcome;           ///< how the last run ended ("done in 52 s", "stopped in train", ...)
};

/// Two training runs compared side by side (runs table A / B): their models' predictions at the
/// current light and, when a ground truth is shown, their per-object errors against it.
struct RunPair {
    int a = -1, b = -1;            ///< indices into project.runs, -1 = not chosen
    bool running = false;          ///< the job predicting them runs
    ImageSet imagesA, imagesB;     ///< the predictions (labels name the runs)
    /// Per-object errors of each against the ground truth (valid = false without one).
    EvaluationInfo errorsA, errorsB;
    std::string nameA, nameB;      ///< run names at the time of the comparison
};

/// The Light region panel (panels/light_region_panel.cpp): the loaded models' error over a grid of
/// light positions spanning the light region (core/eval/light_grid.h), the grid the next evaluation
/// uses, and its job.
struct LightRegionInfo {
    /// Grid points along x, y and z of the next evaluation, each 1 … kMaxCount.
    int counts[3] = {4, 2, 4};
    static constexpr int kMaxCount = 8;
    bool running = false;
    double progress = 0.0;
    std::optional<LightGridMap> map;     ///< the last finished evaluation
    std::string modelsDir;               ///< the models it judged
    std::string outDir;                  ///< where its files are
    int width = 0, height = 0;           ///< its references' size
    int object = -1;                     ///< shown: -1 the global figure, else an object id
};

/// Where a panel's actions and edits go, and nothing else of the state: the application's request
/// queue, the unsaved-changes flag, the Log and the notice. Panels that ask for work or edit the
/// project get one in their view (panels/panel_views.h); WorkbenchState's own request() and
/// notify() go through it, so there is one definition of each.
struct PanelActions {
    std::vector<Request>& requests;
    bool& dirty;
    Log& log;
    std::optional<Notice>& notice;

    void request(Command c, std::string path = {}, int index = -1) const {
        requests.push_back({c, std::move(path), index});
    }
    void markDirty() const { dirty = true; }
    /// Logs `text` and makes it the notice shown in the status bar and in `panel`.
    void notify(LogLevel level, const std::string& panel, const std::string& text) const {
        log.add(level, text);
        notice = Notice{level, panel, text};
    }
};

/// The image sets the three views choose from, and the choice between them: which set is the
/// reference (left view) and which the compared one (middle view) for a CompareSource. One
/// definition for WorkbenchState and the Views panel's view.
struct ViewImages {
    const ImageSet& groundTruth;
    const ImageSet& compare;
    const ImageSet& prediction;
    const RunPair& runPair;

    /// The images of the middle view: the prediction, the compared run, or run B of a pair.
    const ImageSet& compared(CompareSource source) const {
        return source == CompareSource::Run       ? compare
               : source == CompareSource::RunPair ? runPair.imagesB
                                                  : prediction;
    }
    /// The images of the left view, what the error map measures against: the ground truth, or run A
    /// of a pair.
    const ImageSet& reference(CompareSource source) const {
        return source == CompareSource::RunPair ? runPair.imagesA : groundTruth;
    }
};

/// Name for titles: the project's name, else its file name, else "untitled" (also without a project).
std::string projectDisplayName(const Project& project, bool hasProject);

struct WorkbenchState {
    /// The open project: its typed sections (settings, runs, pane layout, scene overrides) are what
    /// the panels edit.
    Project project;
    bool hasProject = false;
    bool dirty = false;  ///< unsaved changes

    /// Primary-ray picking on the UI thread (one ray per hover); rebuilt on a worker when the
    /// geometry changes (app/gui/picking_controller.h): null until the first build has arrived.
    std::shared_ptr<const Accel> pickAccel;
    /// Object id per camera pixel (pixel centres, -1 = background or light), for highlighting.
    std::vector<int> objectIds;
    int idWidth = 0, idHeight = 0;
    uint64_t idsRevision = 0;  ///< bumped whenever objectIds is replaced (a map of the same size too)

    ImageSet groundTruth;
    ImageSet compare;     ///< a run's images ("Compare" in the runs table)
    ImageSet prediction;  ///< the trained models' prediction at the current light position
    RenderProgress render;
    DatasetInfo dataset;
    TrainingInfo training;
    TrainingView trainingView;
    EvaluationInfo evaluation;
    LeavesInfo leaves;  ///< the loaded models' kd-tree leaves (Leaves panel, leaf overlay)
    ObjectsView objectsView;
    CostInfo cost;
    CostView costView;
    LightRegionInfo lightRegion;
    ViewState view;
    /// GL textures of the three views, set by the application (null in tests: nothing is drawn).
    ImTextureID viewTextures[3] = {nullptr, nullptr, nullptr};

    /// Bytes this process may still allocate (core/util/memory_budget.h), refreshed by the
    /// application about once a second so controls can refuse a run that cannot fit before it starts.
    uint64_t availableMemory = UINT64_MAX;

    int compareRun = -1;  ///< index into project.runs shown in the compare view, -1 = none
    /// The runs table's short names, recomputed when the runs' ids or names change (not per frame).
    ShortRunNames runNames;
    RunPair runPair;
    PipelineInfo pipeline;
    std::vector<std::string> recent;
    Log log;
    std::optional<Notice> notice;  ///< the newest undismissed problem (panels/status_text.h draws it)
    std::vector<Request> requests;
    /// A tab the application wants in front ("Training", "Objects", ...); cleared once shown.
    std::string focusTab;

    /// The request queue, dirty flag, Log and notice as a panel's view holds them.
    PanelActions actions() { return {requests, dirty, log, notice}; }
    void request(Command c, std::string path = {}, int index = -1) { actions().request(c, std::move(path), index); }
    void markDirty() { dirty = true; }
    /// Logs `text` and makes it the notice shown in the status bar and in `panel`.
    void notify(LogLevel level, const std::string& panel, const std::string& text) { actions().notify(level, panel, text); }
    /// Name for titles (projectDisplayName).
    std::string projectName() const { return projectDisplayName(project, hasProject); }
    /// The image sets the views choose from.
    ViewImages images() const { return {groundTruth, compare, prediction, runPair}; }
    /// The images of the middle view (ViewImages::compared for view.compareSource).
    const ImageSet& compared() const { return images().compared(view.compareSource); }
    /// The images of the left view (ViewImages::reference for view.compareSource).
    const ImageSet& reference() const { return images().reference(view.compareSource); }
};

}  // namespace rrf::panels
