#pragma once
/// Entry points of the workbench panels, one per file in panels/. Each draws into the current
/// ImGui window (a pane's tab) and takes the view of exactly what it draws and edits
/// (panels/panel_views.h: references into the WorkbenchState, built by projectPanelView(state) and
/// its siblings), not the whole state; actions that need the application (files, jobs, GL) are
/// queued as Requests through the view's PanelActions.

#include <optional>
#include <string>
#include <vector>

#include "core/eval/evaluation.h"
#include "core/nn/model_set.h"
#include "core/nn/network_settings.h"
#include "panels/panel_views.h"
#include "panels/workbench_state.h"

namespace rrf::panels {

/// A keyboard shortcut as the Help window lists it; the application's key table
/// (app/gui/shortcuts.h) is its one source.
struct ShortcutInfo {
    std::string keys;  ///< e.g. "Ctrl+O"
    std::string what;  ///< what it does
};
/// The Help window (F1): `shortcuts`, the mouse gestures of the views, plots and panes, and a short
/// tour of where each stage is driven from. Drawn while *open; its close button or Escape clears
/// it. `linesShown` (tests) receives one line per entry shown.
void drawHelpWindow(const std::vector<ShortcutInfo>& shortcuts, bool* open, std::vector<std::string>* linesShown = nullptr);

/// Project: name, file, render settings, recent projects and the runs table.
void drawProjectPanel(const ProjectPanelView& panel);
/// The tooltip of a run's row in the runs table: its name, full id, creation time and every field of
/// its row (the hidden columns' too), one a line.
std::string runTooltipText(const Run& run);
/// Scene: objects, materials (editable), lights, the movable light's position, derived effects.
void drawScenePanel(const ScenePanelView& panel);
/// Sampling: jitter grid, N_dir, spp per record, seed, light; estimates before and coverage after.
void drawSamplingPanel(const SamplingPanelView& panel);
/// Views: ground truth | compared image | error map, synchronised zoom/pan and read-out.
void drawViewsPanel(const ViewsPanelView& panel);
/// Log: messages and errors, copy to clipboard.
void drawLogPanel(const LogPanelView& panel);
/// Network: hidden layers, activation, targets, trainer and its parameters, parameter counts.
void drawNetworkPanel(const NetworkPanelView& panel);
/// Training: start/stop, live loss plot (log y, per network or aggregate), epoch, time, μ or rate.
void drawTrainingPanel(const TrainingPanelView& panel);
/// Objects: per-object error table of the last evaluation, sortable, click to highlight, CSV.
void drawObjectsPanel(const ObjectsPanelView& panel);
/// Cost: accuracy versus time from sweeps and from the project's runs.
void drawCostPanel(const CostPanelView& panel);
/// Light region: the loaded models' error over a grid of light positions spanning the light region,
/// one map per height, training lights marked; click a cell to move the light there.
void drawLightRegionPanel(const LightRegionPanelView& panel);
/// Leaves: the loaded models' kd-tree leaves per object, each leaf's records and validation error.
void drawLeavesPanel(const LeavesPanelView& panel);
/// The Leaves panel's rows for a model set (pixelLeaf left empty).
LeavesInfo leavesOf(const ModelSet& models);

// Network panel edits (the panel's buttons call these; each stores the edited settings in
// Project::network and marks the project dirty, and returns false when nothing changed).
bool addHiddenLayer(const NetworkPanelView& panel);
bool removeHiddenLayer(const NetworkPanelView& panel, int index);
bool resizeHiddenLayer(const NetworkPanelView& panel, int index, int size);
bool setTrainerType(const NetworkPanelView& panel, TrainerType type);
/// Networks averaged per leaf (Project::network's "ensemble", nn/ensemble.h), clamped to
/// 1 … kMaxEnsembleMembers.
bool setEnsemble(const NetworkPanelView& panel, int members);
/// Replaces the kd-tree settings (Project::network's "partition" section).
bool setPartition(const NetworkPanelView& panel, const PartitionSettings& partition);
/// Sets the networks' input encoding to the named one (nn/encoding_presets.h; Project::network's
/// "encoding"); false for an unknown name or no change.
bool setEncoding(const NetworkPanelView& panel, const std::string& name);
/// Stores `s` as Project::network and marks the project dirty (what every edit above ends with).
void storeNetworkSettings(const NetworkPanelView& panel, const NetworkSettings& s);
/// Every network's reflected-direction input (Project::network's "inputs": {"reflected"},
/// nn/derived_inputs.h).
bool setReflectedInput(const NetworkPanelView& panel, bool on);
// The entry of object `name` in Project::network's "objects" map (nn/object_network_overrides.h); an
// entry left with nothing set is removed.
/// Its reflected input: on, off, or nullopt for the section's.
bool setObjectReflected(const NetworkPanelView& panel, const std::string& name, std::optional<bool> on);
/// Its hidden sizes (each clamped to 1 … kMaxHiddenSize), or nullopt for the section's; an empty
/// list changes nothing.
bool setObjectHidden(const NetworkPanelView& panel, const std::string& name, std::optional<std::vector<int>> hidden);
/// Its input encoding by name (nn/encoding_presets.h), or "" for the section's; false for an
/// unknown name or no change.
bool setObjectEncoding(const NetworkPanelView& panel, const std::string& name, const std::string& encoding);
/// The reflected-input checkbox and the per-object table (drawn inside the Network panel; `inputs`:
/// the records' input count).
void drawObjectNetworks(const NetworkPanelView& panel, int inputs);
/// The project's glossy gather ("prediction": {"gather"}, core/predict/glossy_gather.h): values
/// clamped to their ranges; false when nothing changed.
bool setGlossyGather(const NetworkPanelView& panel, const PredictionSettings::Gather& gather);
/// The names of the objects `prediction` gathers, comma-separated ("" for none).
std::string gatheredObjectNames(const Scene& scene, const PredictionSettings& prediction);
/// The gather's switch, threshold and sample counts, and which objects it takes (in the Network panel).
void drawGlossyGather(const NetworkPanelView& panel);

/// The Objects table of an evaluation: per term, one row per object in view or trained (errors with
/// the reference's noise floor and corrected figure, as evaluate() computed them), with the samples
/// and training time from the models' own training records; the reference's spp, whether its noise
/// is known, and the footprint mask's counts.
EvaluationInfo evaluationInfo(const Evaluation& e, const Scene& scene, const ModelSet& models);
/// The rows of one term sorted by `column` (stable; ties keep object order).
std::vector<ObjectErrorRow> sortedObjectRows(const std::vector<ObjectErrorRow>& rows, ObjectColumn column, bool ascending);
/// The per-object rows of two evaluations of term `t` merged by object id (ascending): run A's and run
/// B's relative RMSE side by side, with the ground truth's noise floor.
std::vector<PairedObjectRow> pairedObjectRows(const EvaluationInfo& a, const EvaluationInfo& b, Term t);
/// Why the Objects table does not describe the models the Views show, or empty when it does: it
/// judged other models than the loaded ones (a later training, a re-opened run), or the Views show
/// a run pair or a render run instead of the prediction.
std::string objectsTableMismatch(const ObjectsPanelView& panel);
/// The table as CSV: a header line, then one line per row (object names quoted).
std::string objectRowsCsv(const std::vector<ObjectErrorRow>& rows, const char* term);
/// Accuracy-versus-time points of the project's training runs that were evaluated (raw errors, each
/// against its own ground truth).
CostSeries runsCostSeries(const std::vector<Run>& runs);
/// Where the path tracer's series `pathTracer` reaches the model point's error (core's breakEven on
/// its points: spp, render seconds, error).
BreakEven costBreakEven(const CostSeries& pathTracer, const CostPoint& model);
/// One sentence per model point of `series` (breakEvenText, prefixed with the series and setting),
/// against the path-tracer series it names; what the Cost panel prints under its plot.
std::vector<std::string> costBreakEvenLines(const std::vector<const CostSeries*>& series);

}  // namespace rrf::panels
