#pragma once
/// What accuracy costs in time (docs/design.md §15): a series of runs that varies one setting and
/// records, per setting, the wall time of each stage and the error per object and overall against a
/// path-traced reference. The CLI writes the rows as CSV and JSON; the GUI's Cost panel reads the same.
///
///   spp      path-tracer error vs samples per pixel and render time, against a high-spp reference
///            with another seed (one progressive render, snapshots at each value); the log-log slope of
///            RMSE vs spp is fitted (Monte Carlo: −0.5, the 1/√N line)
///   grid     data-generation grid vs prediction error, with generate/train/predict times; a value is
///            "nx,ny,nz" as the project's "grid": [nx, ny, nz] (e.g. "4,4,4"); the directions per
///            viewpoint stay the sampling settings'
///   dirs     directions per viewpoint (N_dir, e.g. "200") vs prediction error, on the sampling grid
///   hidden   hidden sizes vs training time, inference time and error (one dataset); a value is
///            "20,10" as the project's "hidden": [20, 10]
///   trainer  "lm" vs "adam": error and training time, plus each network's loss-vs-time curve recorded
///            by the epoch callback
///   goal     the error goal (validation relative RMSE, e.g. "0.05"): the trainer's error_goal and the
///            kd-tree's partition goal together (one dataset)
///   leaves   the most kd-tree leaves per network (e.g. "4"; "1" = one network per object), with the
///            project's partition depth, goal and min records per weight (one dataset)
///   record_spp  the most paths per training record (the adaptive sampler's max_spp, e.g. "256"; a
///            value below the sampling's spp also lowers spp: fixed paths), new data for each point
///   encoding the networks' input encoding (network.encoding) by name (nn/encoding_presets.h, e.g.
///            "raw", "frequency", "hash_grid"), with the training settings' layers and trainer (one
///            dataset); a trainable encoding under Levenberg–Marquardt is refused before anything runs
///   ensemble networks averaged per leaf (network.ensemble, nn/ensemble.h, e.g. "4"), with the training
///            settings' layers (one dataset); a trainable encoding is refused before anything runs
///
/// Every model row records its networks' parameters (MLP weights and encoding parameters, all
/// leaves) and model bytes (the float64 payload of its model files: parameters and scalers).
///
/// Each value is one setting, spelled as outside a JSON file everywhere else (integers, comma-
/// separated lists); every value is read before anything runs, and a bad one throws SettingError
/// naming "sweep values" (an unknown kind: "sweep dimension").
///
/// Comparable by construction: every point — path tracer and model alike — is measured against the
/// same reference at the same resolution and held-out light position (heldOutLightPositions(region,
/// 1, seed)), on the global term over the object pixels the footprint mask keeps
/// (core/predict/footprint_mask.h), each error with the reference's noise floor and the corrected
/// figure. Model sweeps also render the path tracer's series (SweepOptions::pathTracerSpp, another
/// seed than the reference) so that every model row has its break-even (core/eval/break_even.h):
/// the spp and seconds the path tracer needs for the model's corrected error, beside the model's
/// one-off cost (data + training) and its per-frame prediction time. Everything is deterministic
/// except the recorded times.

#include <atomic>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/eval/break_even.h"
#include "core/eval/error_metrics.h"
#include "core/eval/reference_store.h"
#include "core/pipeline/sweep_values.h"
#include "core/nn/model_set.h"
#include "core/nn/object_training.h"
#include "core/predict/predictor.h"
#include "core/data/data_generator.h"
#include "core/data/sampling_settings.h"
#include "core/predict/footprint_mask.h"
#include "core/util/json_text.h"

namespace rrf {

struct SweepOptions {
    std::string what;                 ///< one of kSweepKinds
    std::vector<std::string> values;  ///< one setting each ("16", "4,4,4", "20,10", "lm", "0.05"); empty = defaultSweepValues(what)
    int width = 128, height = 128;    ///< image size of references and predictions
    int referenceSpp = 0;             ///< without a store: 0 = 1024 for spp, 256 otherwise
    /// When set, the one reference every point is measured against comes from this store, converged
    /// to `referenceTarget` (reused by later sweeps of the same scene, light and size); otherwise it
    /// is rendered at `referenceSpp`.
    ReferenceStore* store = nullptr;
    NoiseTarget referenceTarget;
    SamplingSettings sampling;        ///< data generation (grid sweeps replace nx/ny/nz, dirs directions, record_spp max_spp)
    ObjectTrainingOptions training;   ///< networks, trainer and partition (hidden/trainer/goal/leaves sweeps replace theirs)
    PredictionSettings prediction;
    uint64_t seed = 1;                ///< held-out light position and the path tracer's render seed
    /// The path tracer's series rendered for the break-even of model sweeps (every kind but spp), against the same reference; empty = none. An spp sweep's own rows are its series.
    std::vector<int> pathTracerSpp = {1, 2, 4, 8, 16, 32, 64, 128, 256};
    /// Keep each model row's trained networks (SweepRow::models), e.g. to time the GLSL predictor on
    /// them where a GL context exists (the workbench does).
    bool keepModels = false;
    const std::atomic<bool>* cancel = nullptr;
    std::function<void(const std::string&)> log;  ///< progress lines (may be empty)
    /// The fraction of runSweep's work done, in [0, 1] and never decreasing (may be empty): the
    /// reference's convergence first (kSweepReferenceShare of the whole), then the shared dataset,
    /// then one equal share per task (the path tracer's series, each point), so a front end's
    /// progress bar and ETA move with the work instead of with the count of log lines.
    std::function<void(double)> progress;
};

/// The share of a sweep's progress its reference takes (converging it is often the longest part on
/// a fresh scene; a stored one is reused at once) and the share of the shared dataset.
constexpr double kSweepReferenceShare = 0.3, kSweepDataShare = 0.1;

/// One term's error of a model row beside the global term the row is measured on (sweep files:
/// "<term>_relative_rmse", "…_noise_floor", "…_corrected"; the noise figures NaN when unknown).
struct SweepTermFigures {
    double relativeRmse = 0;
    double relativeRmseNoiseFloor = 0;
    double relativeRmseCorrected = 0;
};

/// One epoch of one network in a trainer sweep's loss-vs-time curve.
struct SweepCurvePoint {
    int object = -1;
    std::string target;     ///< "global" | "direct" | "indirect" | "joint"
    int epoch = 0;
    double seconds = 0;     ///< wall time since training started
    double trainLoss = 0;
    double validationLoss = 0;  ///< NaN when the validation set is empty
};

/// What a row records beside its errors and times (a sweep file's row "extra"): each figure is set
/// only where the kind of row measures it, so a file written from them holds the same keys.
struct SweepRowFigures {
    // Model rows: the networks' size and training work (all leaves).
    std::optional<int64_t> parameters;   ///< MLP weights and encoding parameters
    std::optional<int64_t> modelBytes;   ///< float64 payload of the model files (parameters and scalers)
    std::optional<int64_t> leaves;       ///< how far the kd-trees grew (goal and leaves sweeps)
    std::optional<int64_t> leafEpochs;   ///< every member's epochs summed over the leaves
    std::optional<uint64_t> pixelsWithoutNetwork;
    std::optional<uint64_t> nonFinitePredictionValues;
    /// Model rows: the direct and indirect terms' errors where the reference has them.
    std::optional<SweepTermFigures> direct, indirect;
    /// Path-tracer rows: samples dropped because they were NaN/Inf.
    std::optional<uint64_t> nonFiniteSamplesDropped;
    // Points with their own data (grid, dirs, record_spp).
    std::optional<uint64_t> records;
    std::optional<double> meanRecordSpp;  ///< paths traced per record
    std::optional<uint64_t> recordsAtSppCap;
    /// Trainer sweeps: each network's loss against time, networks in (object, target) order.
    std::optional<std::vector<SweepCurvePoint>> curve;
    /// Keys of a sweep file this build does not know (or cannot read), written back as they were.
    JsonText other;
    /// Equal figure by figure; NaN equals NaN (an unknown figure read back is still unknown).
    bool operator==(const SweepRowFigures& o) const;
    bool operator!=(const SweepRowFigures& o) const { return !(*this == o); }
};

/// What a sweep records beside its rows (a sweep file's top-level "extra").
struct SweepResultFigures {
    /// spp sweeps: the fitted log-log slope of RMSE vs spp, raw and noise-corrected (NaN when unknown).
    std::optional<double> loglogSlopeRmse, loglogSlopeRmseCorrected;
    /// Sweeps on one shared dataset: the seconds generating it took.
    std::optional<double> generateSeconds;
    JsonText other;  ///< keys this build does not know, as in SweepRowFigures
};

struct SweepRow {
    static constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
    std::string setting;
    std::vector<std::pair<std::string, double>> stageSeconds;  ///< in stage order
    ErrorStats overall;                                        ///< global term, footprint-mask pixels
    std::vector<ErrorStats> perObject;                         ///< global term, index = object id
    /// Path-tracer rows: samples per pixel (0 for model rows).
    int spp = 0;
    /// Model rows: the one-off cost, data generation + training (seconds); NaN for path-tracer rows.
    double oneOffSeconds = kUnknown;
    /// Model rows: one frame of CPU prediction at the sweep's resolution (G-buffer + networks + exact
    /// direct light where chosen), seconds; NaN for path-tracer rows.
    double frameSeconds = kUnknown;
    /// Model rows: one frame of GLSL prediction (render + read-back), seconds; NaN unless a front end
    /// with a GL context measured it (core has no GL).
    double glslFrameSeconds = kUnknown;
    /// Model rows: where the path tracer of the same sweep reaches this row's comparableError().
    BreakEven breakEven;
    /// Model rows with SweepOptions::keepModels: the networks that were evaluated.
    std::shared_ptr<const ModelSet> models;
    SweepRowFigures extra;  ///< records, parameters, curves, …
};

/// Whether `row` is a model row: its one-off cost (data + training) is known; NaN for the path tracer's rows.
bool isModelRow(const SweepRow& row);

struct SweepResult {
    std::string what;
    Vec3 lightPosition{0.f};
    int width = 0, height = 0;   ///< resolution of the reference and of every point
    int referenceSpp = 0;
    double referenceSeconds = 0;
    /// The reference's relative RMSE noise floor (global term, footprint mask; core/eval/reference_noise.h):
    /// the dashed line below which no error against it is measurable. NaN when unknown.
    double relativeNoiseFloor = SweepRow::kUnknown;
    std::vector<SweepRow> rows;
    /// Model sweeps: the path tracer's series against the same reference (spp order). For an spp
    /// sweep it is empty: the rows are the series (pathTracerRows()).
    std::vector<SweepRow> pathTracer;
    SweepResultFigures extra;  ///< e.g. the log-log slope for spp
    bool cancelled = false;
};

/// Runs the sweep. Throws SettingError for an unknown kind or a malformed value (before rendering).
/// One process running every task of the sweep below in order: checkedSweepOptions,
/// obtainSweepReference, the shared dataset, runSweepTasks(all), joinSweepParts.
SweepResult runSweep(const Scene& scene, const SweepOptions& options);

// ---- a sweep in tasks, for running them in several processes (`mpirun -n N rrf sweep`, docs/cluster.md) ----
// runSweep runs the same functions in one process, so any split of the tasks joins into its result:
// rows, errors and break-evens equal; only the recorded times differ.

/// One task of a sweep. A model sweep's task 0 is the path tracer's series (SweepOptions::pathTracerSpp,
/// possibly empty), task k ≥ 1 the k-th value (a point: data where it makes its own, training,
/// prediction, errors); an spp sweep is one task, its series (one progressive render whose snapshots
/// are the values, which cannot be split by value without rendering the largest spp again).
struct SweepTask {
    std::string label;             ///< "path tracer", the value ("20,10"), "spp series"
    bool series = false;           ///< a path-tracer series (task 0)
    int maxSpp = 0;                ///< series: the largest spp it renders
    bool newData = false;          ///< a point that generates its own data (grid, dirs, record_spp)
    SamplingSettings sampling;     ///< a point's data: its own (newData) or the shared dataset's
    ObjectTrainingOptions training;  ///< a point's networks
};

/// `options` with the default values filled in and every value read (SettingError as runSweep), after
/// checking that the scene has a light (InputError).
SweepOptions checkedSweepOptions(const Scene& scene, const SweepOptions& options);
/// The tasks of a checked sweep, in order.
std::vector<SweepTask> sweepTasks(const SweepOptions& checked);
/// The held-out light position every point is measured at (heldOutLightPositions(…, 1, seed)).
Vec3 sweepLightPosition(const Scene& scene, const SweepOptions& checked);
/// How the sweep's reference is rendered: its size, spp (the fixed spp without a store; the store
/// converges from the same seed) and seed, which no render it judges uses.
RenderOptions sweepReferenceOptions(const SweepOptions& checked);
/// The reference of the sweep: from checked.store converged to its target, or rendered at the fixed
/// spp (sweepReferenceOptions); logged through checked.log.
/// `progress`, if given, receives the store's convergence reports (not called without a store).
Reference obtainSweepReference(const Scene& scene, const SweepOptions& checked,
                               const std::function<void(const ReferenceProgress&)>& progress = {});
/// Whether the points train on one dataset generated with checked.sampling (hidden, trainer, goal,
/// leaves, encoding); the others make their own (grid, dirs, record_spp) or none (spp).
bool sweepSharesData(const SweepOptions& checked);

/// What every task of a sweep measures against, obtained once.
struct SweepInputs {
    Reference reference;
    /// The pixels every error is measured over: the footprint mask of the reference's G-buffer.
    FootprintMask footprint;
    /// The shared dataset when sweepSharesData, else null.
    std::shared_ptr<const GeneratedData> data;
};
/// The inputs of a checked sweep from its reference and (network sweeps) its shared dataset.
SweepInputs sweepInputs(const Scene& scene, const SweepOptions& checked, Reference reference,
                        std::shared_ptr<const GeneratedData> data);

/// What some of a sweep's tasks produced.
struct SweepPart {
    std::vector<int> tasks;                   ///< the tasks run, ascending
    std::vector<std::vector<SweepRow>> rows;  ///< per task run: a series' rows, a point's one row; none where cancelled
    bool cancelled = false;
};

/// Runs `tasks` (ascending indices into sweepTasks) of a checked sweep, each with all threads, logging
/// as runSweep does; a point's break-even is logged only when this part also ran the series (task 0).
/// SweepRow::models is kept (keepModels) but not sent by encodeSweepPart. `taskDone`, if given, is
/// called with the number of this part's tasks finished after each one.
SweepPart runSweepTasks(const Scene& scene, const SweepOptions& checked, const SweepInputs& inputs,
                        const std::vector<int>& tasks, const std::function<void(int)>& taskDone = {});

/// Joins parts that together ran every task once, in any order, into runSweep's result: rows in the
/// order of the values (spp: ascending spp), every model row's break-even against the joined series,
/// the series' fitted slopes, the shared dataset's generate seconds. Throws std::runtime_error naming
/// the task when one is missing or was run twice.
SweepResult joinSweepParts(const Scene& scene, const SweepOptions& checked, const SweepInputs& inputs,
                           std::vector<SweepPart> parts);

/// The path tracer's series of `r`: its rows for an spp sweep, else r.pathTracer.
const std::vector<SweepRow>& pathTracerRows(const SweepResult& r);
/// The points of that series for breakEven() (spp, render seconds, comparableError()).
std::vector<PathTracerPoint> pathTracerPoints(const SweepResult& r);

/// A model row's break-even sentence (breakEvenText with its error, frame times and break-even).
std::string sweepBreakEvenText(const SweepRow& row);

/// Least-squares slope of log(y) against log(x) over the pairs with x, y > 0 (NaN if fewer than 2).
double logLogSlope(const std::vector<double>& x, const std::vector<double>& y);

/// One line per row: what, setting (quoted when it holds commas), each stage's seconds, overall RMSE /
/// relative RMSE (each with noise floor and corrected) / MAE / max, RMSE and relative RMSE of every
/// object, then the cost columns: spp, one_off_seconds, frame_seconds, glsl_frame_seconds,
/// breakeven_spp, breakeven_seconds, breakeven_extrapolated (empty where unknown). A model sweep's
/// path-tracer series follows as rows whose `what` is "path_tracer".
std::string sweepCsv(const Scene& scene, const SweepResult& r);
/// Training curves of a trainer sweep (trainer, object, target, epoch, seconds, losses); empty otherwise.
std::string sweepCurveCsv(const SweepResult& r);
// The JSON report (sweepJson) is the sweep file's writer: core/pipeline/sweep_file.h.
/// Readable table of the rows (and the fitted slope for spp); for model sweeps the path tracer's
/// series and one break-even sentence per row (breakEvenText).
std::string sweepTable(const SweepResult& r);

}  // namespace rrf
