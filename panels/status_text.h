#pragma once
/// The words the workbench uses for the state of its jobs and results, one definition each, so the
/// progress bars, tables and notifications never disagree and never call a stopped job "done":
/// a cancelled render says "cancelled at 42/64 spp", a stopped training "stopped at epoch N, 2 of 14
/// networks", and a coverage table whose dataset no longer matches the settings says why it is stale.

#include <optional>
#include <string>

#include "panels/workbench_state.h"

namespace rrf::panels {

/// The render progress bar's words: "12/64 spp" while running, "64/64 spp done" when it reached
/// its target, "cancelled at 42/64 spp" when it stopped short.
std::string renderProgressText(const RenderProgress& r);

/// The training progress bar's words: "37%" while running, "done, 14 networks" when it finished,
/// core's stoppedTrainingText ("stopped at epoch 12, 2 of 14 networks") when the user stopped it.
std::string trainingProgressText(const TrainingInfo& t);

/// Why the Sampling panel's coverage table does not describe what the current settings would
/// generate, or empty when it does: the last generation was cancelled (the table is the dataset
/// before it), the sampling settings or the scene changed since the dataset was generated.
std::string datasetStaleReason(const DatasetInfo& d, const Project& project);

/// The Views legend for a partial model set: "hatched magenta: no network for 5 objects (floor,
/// ...)" naming the objects of `set.withoutNetwork`; empty when every object has one.
std::string withoutNetworkText(const ImageSet& set, const Scene& scene);

/// Draws `notice` (the newest problem the user has not dismissed; WorkbenchState::notice) as a
/// coloured line with a Dismiss button, which clears it; nothing when there is none. The status bar
/// and the panel the notice concerns both draw it, so an error shows where the user is looking and not only in the Log. `wrap`: wrap
/// the text at the window's edge (panels); else one line with the whole text on hover (status bar).
void drawNotice(std::optional<Notice>& notice, bool wrap = true);

/// `value` clamped to [lo, hi]; a value outside (typed into a field) also makes a warning notice on
/// `panel` that names the setting, its bounds and what was kept ("hidden layer size is 1 ... 1024;
/// 0 was set to 1"), so no bound is applied silently.
int clampWithNotice(const PanelActions& actions, const char* panel, const std::string& what, int value, int lo, int hi);

}  // namespace rrf::panels
