#pragma once
/// State of the learning side of the workbench: the training job's live loss curves, the last
/// evaluation's per-object errors and the accuracy-versus-time series of sweeps. The application
/// (app/gui) fills these from the snapshots its worker jobs publish; the Training, Objects and Cost
/// panels only read them (and their own view options), so they draw in a bare ImGui context.

#include <cstdint>
#include <string>
#include <vector>

#include "core/eval/error_metrics.h"
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
    uint64_t samples = 0;        ///< training records of the object (all its networks)
    double trainSeconds = 0.0;   ///< training time of the object's networks
};

/// Result of the last evaluation (prediction vs ground truth at one light position).
struct EvaluationInfo {
    bool running = false;
    bool valid = false;
    Vec3 lightPosition{0.f};
    int referenceSpp = 0;
    double seconds = 0.0;
    /// Rows per term, indexed with int(Term). The statistics are core's (errorStats through
    /// rrf::evaluate), the figures `rrf evaluate` reports.
    std::vector<ObjectErrorRow> rows[kTermCount];
    ErrorStats overall[kTermCount];
    bool available[kTermCount] = {false, false, false};
};

/// Columns of the Objects table, also the sort keys.
enum class ObjectColumn { Object, Rmse, RelativeRmse, Mae, Max, Pixels, Samples, TrainSeconds, Count };

struct ObjectsView {
    ObjectColumn sortColumn = ObjectColumn::Object;
    bool ascending = true;
};

/// One point of an accuracy-versus-time curve.
struct CostPoint {
    double seconds = 0.0;        ///< wall time the setting cost
    double error = 0.0;          ///< relative RMSE (global term, all object pixels)
    std::string label;           ///< the setting, e.g. "16 spp", "20,10"
};

struct CostSeries {
    std::string name;            ///< e.g. "sweep spp", "runs"
    std::vector<CostPoint> points;
};

/// Sweeps run in this session and the sweep job's state.
struct CostInfo {
    bool running = false;
    double progress = 0.0;
    std::vector<CostSeries> sweeps;
};

struct CostView {
    int what = 0;                ///< index into kSweepKinds (core/eval/sweep.h)
    bool showRuns = true;
    int hoverSeries = -1, hoverPoint = -1;
};

}  // namespace rrf::panels
