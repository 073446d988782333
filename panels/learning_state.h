#pragma once
/// State of the learning side of the workbench: the training job's live loss curves, the last
/// evaluation's per-object errors and the accuracy-versus-time series of sweeps. The application
/// (app/gui) fills these from the snapshots its worker jobs publish; the Training, Objects and Cost
/// panels only read them (and their own view options), so they draw in a bare ImGui context.

#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/eval/break_even.h"
#include "core/eval/error_metrics.h"
#include "panels/plot.h"
#include "core/predict/footprint_mask.h"
#include "core/render/term.h"
#include "core/util/vec3.h"
#include "core/project/runs.h"

namespace rrf::panels {

/// The training job as last published.
struct TrainingInfo {
    bool running = false;
    double progress = 0.0;       ///< epochs done / epochs budgeted over all networks
    double seconds = 0.0;        ///< wall time since the job started
    int epoch = 0;               ///< latest epoch of any network
    double step = 0.0;           ///< μ (LM) or learning rate (Adam) of the latest epoch
    std::string trainer;         ///< "levenberg_marquardt" or "adam"
    std::vector<LossCurve> curves;  ///< one per network, in the order they first reported
    std::string runId;           ///< the run the job records (also its directory under runs/)
    std::string modelsDir;       ///< models of the last finished training (absolute path)
    /// The user stopped the last training: its `networks` of `plannedNetworks` form a partial
    /// model set, recorded as run `partialRun` (index into project.runs, -1 none) but not shown
    /// unless the user chooses it; the prediction keeps the last complete set.
    bool stopped = false;
    int networks = 0, plannedNetworks = 0;
    int partialRun = -1;
};

/// One leaf of a loaded model's kd-tree (core/nn/partition_tree.h), a row of the Leaves panel.
struct LeafRow {
    int objectId = -1;
    std::string object, target;
    int leaf = 0, leafCount = 1, depth = 0;
    int64_t records = 0;  ///< training records in the leaf
    double error = 0;     ///< validation relative RMSE of the leaf's network (NaN: no validation set)
};

/// The loaded models' trees, and the leaf of every view pixel for the Views "leaf" overlay.
struct LeavesInfo {
    std::vector<LeafRow> rows;     ///< by object, target, leaf
    std::vector<int> pixelLeaf;    ///< per view pixel: leaf number in its object's tree, −1 none
    int width = 0, height = 0;     ///< size of pixelLeaf's image
    uint64_t forPrediction = 0;    ///< ImageSet revision of the prediction pixelLeaf was made for
    uint64_t revision = 0;         ///< changes whenever pixelLeaf changes
};

/// Display options of the loss plot.
struct TrainingView {
    bool aggregate = false;      ///< one mean curve instead of one per network
    bool showTrain = true, showValidation = true;
    PlotView plot;               ///< zoom and pan of the loss plot (auto-fit until the user zooms)
    /// Curves hidden by a click on their legend entry (their labels, LossCurve::label()).
    std::vector<std::string> hidden;
    // Filled by the panel each frame (read by tests and by the hover read-out):
    float plotMinX = 0, plotMinY = 0, plotMaxX = 0, plotMaxY = 0;  ///< plot rectangle on screen
    double yLo = 0, yHi = 0;     ///< log10 of the y range (decade aligned)
    int hoverCurve = -1, hoverEpoch = -1;  ///< nearest point under the mouse, -1 when none
};

/// One row of the per-object error table.
struct ObjectErrorRow {
    int objectId = -1;
    std::string name;
    ErrorStats stats;
    /// Mean HDR-FLIP over the object's compared pixels (core/eval/flip_evaluation.h): global term
    /// rows only, NaN for the other terms or without FLIP figures.
    double flip = std::numeric_limits<double>::quiet_NaN();
    uint64_t samples = 0;        ///< training records of the object (all its networks)
    double trainSeconds = 0.0;   ///< training time of the object's networks
};

/// Result of the last evaluation (prediction vs ground truth at one light position).
struct EvaluationInfo {
    bool running = false;
    bool valid = false;
    std::string modelsDir;       ///< the models it judged (absolute), to tell whether they are the ones shown
    Vec3 lightPosition{0.f};
    int referenceSpp = 0;
    /// The ground truth carried its per-pixel variance of the mean: noise floors and corrected
    /// figures are numbers (otherwise NaN, shown "unknown", never 0).
    bool referenceNoiseKnown = false;
    FootprintCounts footprint;   ///< object pixels left out of the statistics, per reason
    double seconds = 0.0;
    /// Rows per term, indexed with int(Term). The statistics are core's (errorStatsWithNoise through
    /// rrf::evaluate, each with the reference's noise floor and the corrected figure), the figures
    /// `rrf evaluate` reports.
    std::vector<ObjectErrorRow> rows[kTermCount];
    ErrorStats overall[kTermCount];
    bool available[kTermCount] = {false, false, false};
    /// FLIP of the global term over all compared object pixels (NaN without FLIP figures): mean
    /// HDR-FLIP, its noise floor (the ground truth against itself plus a draw of its noise; NaN
    /// when its variance is unknown) and mean LDR-FLIP.
    double flipHdr = std::numeric_limits<double>::quiet_NaN();
    double flipNoiseFloor = std::numeric_limits<double>::quiet_NaN();
    double flipLdr = std::numeric_limits<double>::quiet_NaN();
    /// The ensemble members' spread against the true error (core/eval/uncertainty.h), global term:
    /// Spearman's rank correlation over all objects and per object ("name rho" pairs); NaN and
    /// empty when the models have no members' spread.
    double spreadSpearman = std::numeric_limits<double>::quiet_NaN();
    double spreadRelative = std::numeric_limits<double>::quiet_NaN();  ///< mean relative spread
    std::vector<std::pair<std::string, double>> spreadSpearmanPerObject;
};

/// One object of two runs compared side by side (Objects panel while the Views show a run pair):
/// each run's relative RMSE against the ground truth (NaN when that run has no row for it).
struct PairedObjectRow {
    int objectId = -1;
    std::string name;
    double a = std::numeric_limits<double>::quiet_NaN(), b = std::numeric_limits<double>::quiet_NaN();
    double noiseFloor = std::numeric_limits<double>::quiet_NaN();  ///< the ground truth's, the same for both
};

/// Columns of the Objects table, also the sort keys.
/// Each RMSE comes with the ground truth's noise floor and the corrected (noise subtracted) figure;
/// bias is the signed relative mean (the RMSE's spread has no sign), relMSE and SMAPE are the
/// literature's figures (core/eval/error_metrics.h); FLIP the perceptual one (HDR-FLIP, global term).
enum class ObjectColumn {
    Object,
    Rmse,
    RmseNoiseFloor,
    RmseCorrected,
    RelativeRmse,
    RelativeNoiseFloor,
    RelativeCorrected,
    Bias,
    RelMse,
    RelMseCorrected,
    Smape,
    Flip,
    Mae,
    Max,
    Pixels,
    Samples,
    TrainSeconds,
    Count
};

struct ObjectsView {
    ObjectColumn sortColumn = ObjectColumn::Object;
    bool ascending = true;
};

/// One point of the Cost panel. All points of one sweep are measured against one reference at one
/// resolution (core/pipeline/sweep.h), so they compare; the error is comparableError() (the relative
/// RMSE of the global term with the reference's noise subtracted; raw when that noise is unknown).
struct CostPoint {
    static constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
    double seconds = 0.0;        ///< path tracer: render time; model: one-off cost (data + training)
    double error = 0.0;          ///< comparableError(): what the plot and the break-even use
    std::string label;           ///< the setting, e.g. "16", "20,10"
    bool corrected = true;       ///< `error` is noise-corrected (false: raw, the noise being unknown)
    double rawError = kUnknown;  ///< raw relative RMSE
    double spp = 0.0;            ///< path tracer: samples per pixel
    double frameSeconds = kUnknown;      ///< model: one CPU frame of prediction
    /// model: one GLSL frame, the GPU time of its passes (GL timer queries, measured in the workbench)
    double glslFrameSeconds = kUnknown;
    std::string resolution{};            ///< runs: the size the error was measured at, e.g. "256x256"
};

/// What a series' points are.
enum class CostKind {
    Models,      ///< one trained model per point: one-off cost, per-frame times, a break-even
    PathTracer,  ///< the path tracer at increasing spp: render time
    Runs,        ///< the project's evaluated training runs (each against its own ground truth)
};

struct CostSeries {
    std::string name;            ///< e.g. "sweep hidden", "path tracer (sweep hidden)"; keys its colour
    std::vector<CostPoint> points;
    CostKind kind = CostKind::Models;
    /// Models: the name of the path-tracer series measured against the same reference (the break-
    /// even is read off it); empty when there is none.
    std::string pathTracer{};
    /// The reference's relative RMSE noise floor (NaN: unknown), drawn as a dashed line.
    double noiseFloor = CostPoint::kUnknown;
    std::string reference{};     ///< e.g. "64x64, reference 256 spp"
    /// The image size every point was measured at ("64x64"); empty when the points differ (runs).
    std::string resolution{};
};

/// Sweeps run in this session and the sweep job's state.
struct CostInfo {
    bool running = false;
    double progress = 0.0;
    std::vector<CostSeries> sweeps;
};

struct CostView {
    int what = 0;                ///< index into kSweepKinds (core/pipeline/sweep.h)
    /// The project's runs are each evaluated against their own ground truth, so they do not compare
    /// with the sweeps' points: shown only on request.
    bool showRuns = false;
    PlotView plot;               ///< zoom and pan of the cost plot (auto-fit until the user zooms)
    std::vector<std::string> hidden;  ///< series hidden by a click on their legend entry (names)
    int hoverSeries = -1, hoverPoint = -1;
    // Filled by the panel each frame (read by tests):
    std::vector<std::string> breakEvenLines;  ///< the break-even sentences shown under the plot
    /// Markers drawn in the plot and listed in its key, each as shape + "F" (filled) or "h" (hollow):
    /// 'o' circle, 's' square, 'd' diamond, 't' triangle, 'x' cross.
    std::string shapesDrawn, keyShapes;
    float plotMinX = 0, plotMinY = 0, plotMaxX = 0, plotMaxY = 0;  ///< plot rectangle on screen
};

}  // namespace rrf::panels
