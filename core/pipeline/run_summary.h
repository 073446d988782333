#pragma once
/// One row of the workbench's runs table: what a run was (kind, trainer, network), what it cost
/// (records, training or render time, one frame of prediction) and how good it is (held-out error
/// with the reference's noise floor), read from the run's settings snapshot and metrics so that a
/// run recorded by the CLI and one recorded by the workbench read the same. Unknown fields stay
/// empty (the table shows "-"), never 0.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/project/runs.h"

namespace rrf {

struct RunSummary {
    std::string kind;                 ///< "render", "train", ...
    std::string status;               ///< trainRunStatusText (train runs), "" otherwise
    bool stopped = false;             ///< a stopped (partial) training run
    std::string trainer;              ///< "LM" or "Adam" (train runs)
    std::vector<int> hidden;          ///< hidden layer sizes (train runs)
    std::optional<int> leaves;        ///< kd-tree leaves over all models
    std::optional<double> records;    ///< training records
    std::optional<double> spp;        ///< render runs: samples per pixel
    std::optional<double> seconds;    ///< training time (train runs) or render time (render runs)
    std::optional<double> error;      ///< held-out relative RMSE of the global term (evaluated runs)
    /// Train runs: the reference's relative RMSE noise floor of `error`; render runs: the render's own
    /// relative error estimate (its noise, the floor of any comparison against it).
    std::optional<double> noiseFloor;
    std::optional<double> corrected;  ///< train runs: `error` less the reference's noise (evaluated runs)
    std::optional<double> frameSeconds;  ///< one frame of prediction: GLSL when measured, else CPU
    bool frameGlsl = false;           ///< frameSeconds is the GLSL figure
    int frameWidth = 0, frameHeight = 0;          ///< the frame's size (0: not recorded)
    int evaluatedWidth = 0, evaluatedHeight = 0;  ///< the size `error` was measured at (0: not recorded)
};

/// The table row of `run`.
RunSummary summarizeRun(const Run& run);

/// The names the runs table shows, one per run: a name the user chose is shown whole; a name that
/// is still the run's id ("train-20261201-194512[-n]") is cut to its shortest ending that no other
/// run's name ends with, cut at a '-' or inside a date at its month or day: "194512", or
/// "01-194512" when another day has a run at that second; an ending keeps at least one part of 3 or
/// more characters, so a "-2" counter keeps its time. A narrow column then shows what tells the
/// runs apart instead of their common prefix. Names still alike (two runs named the same) get
/// " #<row>" (1-based).
std::vector<std::string> shortRunNames(const std::vector<Run>& runs);

/// shortRunNames of a runs list, recomputed only when the list's ids or names change: the runs
/// table is drawn every frame, and shortRunNames compares every name with every other (quadratic in
/// the runs). Checking that nothing changed is one pass over the names.
class ShortRunNames {
public:
    /// The names of `runs` (shortRunNames(runs)), from the last call's when they are the same runs.
    const std::vector<std::string>& of(const std::vector<Run>& runs);
    /// How many times the names were computed (tests).
    int computations() const { return computations_; }

private:
    std::vector<std::pair<std::string, std::string>> key_;  ///< each run's id and name when computed
    std::vector<std::string> names_;
    int computations_ = 0;
};

/// "20,10": hidden sizes for tables; "-" when empty.
std::string hiddenText(const std::vector<int>& hidden);

}  // namespace rrf
