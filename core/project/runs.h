#pragma once
/// Experiment runs stored in the project's "runs" section. A run is a record of one piece of work
/// (a ground-truth render or a training run; an evaluation adds its metrics to the training run whose
/// models it judged): the settings it ran with, its loss history, its metrics, its timings and the files it produced.
/// Sections this build does not know are kept verbatim, so a newer workbench's runs survive a
/// round trip through an older one. core/project/runs_json.h reads and writes the section.

#include <optional>
#include <string>
#include <vector>

#include "core/project/run_fields.h"
#include "core/util/json_text.h"

namespace rrf {

/// One point of a loss curve (training runs).
struct LossPoint {
    int epoch = 0;
    double train = 0.0;
    double validation = 0.0;  ///< NaN when there is no validation set
    double seconds = 0.0;
};

/// The loss history of one network of a training run.
struct LossCurve {
    int objectId = -1;
    std::string object;  ///< object name
    std::string target;  ///< "direct", "indirect", "global" or "joint"
    std::vector<LossPoint> points;
    /// "<object> <target>", for legends and read-outs.
    std::string label() const { return object + " " + target; }
};

struct Run {
    std::string id;        ///< unique within the project, also the artifact directory name
    std::string name;      ///< user-visible, editable
    std::string kind;      ///< "render" or "train"
    std::string created;   ///< local time, ISO 8601
    RunSettings settings;                                 ///< snapshot of every setting that made the run
    std::vector<LossPoint> loss;                          ///< aggregate curve; empty for non-training runs
    std::vector<LossCurve> curves;                        ///< one per network (training runs)
    RunMetrics metrics;                                   ///< what it measured
    RunTimings timings;                                   ///< seconds per stage
    std::vector<std::string> artifacts;                   ///< files, relative to the project directory
    JsonText extra;                                       ///< unknown keys, kept for round trips

};

/// Mean of several networks' curves per epoch. A network that stopped earlier contributes its last
/// value (its kept weights do not change after it stops), so the mean does not jump when one
/// finishes. NaN validation values are left out of the validation mean. Seconds: the maximum.
std::vector<LossPoint> aggregateLoss(const std::vector<LossCurve>& curves);

/// A new id "<kind>-<yyyymmdd-hhmmss>[-n]" not yet used in `runs`.
std::string newRunId(const std::vector<Run>& runs, const std::string& kind);
/// Current local time as "yyyy-mm-ddThh:mm:ss".
std::string localTimestamp();

}  // namespace rrf
