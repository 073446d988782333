// Project panel: the project's name and files, the ground-truth render settings, recent projects and
// the runs table (re-open, compare, delete).
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "core/pipeline/run_summary.h"
#include "core/util/text_format.h"
#include "panels/clip_check.h"
#include "panels/figure_text.h"
#include "panels/layout.h"
#include "panels/panels.h"
#include "panels/status_text.h"

namespace rrf::panels {

namespace project_panel_detail {
namespace {
std::string numberText(std::optional<double> v, const char* fmt) {
    if (!v) return "-";
    char buf[32];
    std::snprintf(buf, sizeof buf, fmt, *v);
    return buf;
}

/// "0.0123 (0.0040)": the held-out error with its noise floor; "-" parts when unknown.
std::string errorWithFloorText(const RunSummary& r) {
    if (!r.error && !r.noiseFloor) return "-";
    return numberText(r.error, "%.3g") + " (" + numberText(r.noiseFloor, "%.2g") + ")";
}

/// The ground-truth render settings `r` of the project whose scene is `scene` (which estimator
/// `auto` picks); `dirty` is set on an edit.
void drawRenderSettings(RenderSettings& r, const Scene& scene, bool& dirty) {
    bool changed = false;
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8);
    changed |= ImGui::InputInt("samples per pixel", &r.spp, 16, 256);
    if (r.spp < 1) r.spp = 1;
    // In the order of the combo's entries.
    constexpr Estimator kChoices[] = {Estimator::Auto, Estimator::NEE, Estimator::BDPT, Estimator::Naive};
    int est = 0;
    for (int i = 0; i < 4; ++i)
        if (r.estimator == kChoices[i]) est = i;
    // As wide as its longest entry, so the choice reads in full; in a pane too narrow for the label
    // beside it the label goes above (the runs table's wide scrolling columns used to hide that both
    // overran the left pane at 1280x720 from the clip check).
    const char* items = "auto (BDPT where there are caustics)\0next-event estimation\0bidirectional (BDPT, MIS)\0"
                        "naive (BRDF sampling only)\0";
    const float comboW = fittedComboWidth(items);
    const bool labelAbove = labelledWidth(comboW, "estimator") > ImGui::GetContentRegionAvail().x;
    if (labelAbove) ImGui::TextUnformatted("estimator");
    ImGui::SetNextItemWidth(comboW);
    if (ImGui::Combo(labelAbove ? "##estimator" : "estimator", &est, items)) {
        r.estimator = kChoices[est];
        changed = true;
    }
    const EstimatorChoice used = chooseEstimator(r.estimator, Effects::derive(scene));
    figureTextDisabled("runs: %s (%s)", estimatorName(used.estimator), used.reason.c_str());
    int seed = int(r.seed & 0x7fffffff);
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8);
    if (ImGui::InputInt("seed", &seed)) {
        r.seed = uint64_t(seed < 0 ? 0 : seed);
        changed = true;
    }
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8);
    changed |= ImGui::InputInt("max path depth", &r.maxDepth);
    if (r.maxDepth < 1) r.maxDepth = 1;
    int size[2] = {r.width, r.height};
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8);
    if (ImGui::InputInt2("size (0 = camera)", size)) {
        r.width = std::max(0, std::min(size[0], kMaxImageSide));
        r.height = std::max(0, std::min(size[1], kMaxImageSide));
        changed = true;
    }
    if (changed) dirty = true;
}

/// "1325 GLSL": one frame of prediction in ms and the path that drew it; "-" when not measured.
std::string frameText(const RunSummary& r) {
    if (!r.frameSeconds) return "-";
    const double ms = *r.frameSeconds * 1e3;
    // Three significant figures at most: the median of a few frames is not known better, and a
    // shorter figure keeps the column in a narrow pane.
    return numberText(ms, ms >= 100 ? "%.0f" : "%.3g") + (r.frameGlsl ? " GLSL" : " CPU");
}

}  // namespace
}  // namespace project_panel_detail

std::string runTooltipText(const Run& run) {
    const RunSummary r = summarizeRun(run);
    std::string s = run.name + "\nid " + run.id + "\ncreated " + run.created + "\nkind " + r.kind;
    if (!r.status.empty()) s += "\nstate " + r.status;
    if (!r.trainer.empty()) s += "\ntrainer " + r.trainer + ", hidden " + hiddenText(r.hidden);
    if (r.leaves) s += "\nleaves " + std::to_string(*r.leaves);
    if (r.records) s += "\nrecords " + project_panel_detail::numberText(r.records, "%.0f");
    if (r.spp) s += "\nspp " + project_panel_detail::numberText(r.spp, "%.0f");
    if (r.seconds) s += "\ntime " + project_panel_detail::numberText(r.seconds, "%.2f") + " s";
    if (r.error || r.noiseFloor)
        s += "\nheld-out rel. RMSE " + project_panel_detail::numberText(r.error, "%.4g") + " (noise floor " +
             project_panel_detail::numberText(r.noiseFloor, "%.2g") + ", corrected " +
             project_panel_detail::numberText(r.corrected, "%.4g") + ")";
    if (r.frameSeconds) {
        const std::string size = r.frameWidth > 0 ? sizeText(r.frameWidth, r.frameHeight) : std::string("the view's size");
        s += "\nframe " + project_panel_detail::numberText(*r.frameSeconds * 1e3, "%.2f") + " ms, " +
             (r.frameGlsl ? "GLSL" : "CPU") + " at " + size;
    }
    return s + "\nright-click: rename, re-open, compare, delete";
}

namespace project_panel_detail {
namespace {

/// What the runs table draws and edits, and nothing else of the workbench's state: the project's
/// runs (names are edited in place), the A/B pair, the run shown in the compare view, and where its
/// actions and edits go.
struct RunsTableView {
    std::vector<Run>& runs;
    ShortRunNames& names;             ///< WorkbenchState::runNames: the names shown, kept between frames
    RunPair& pair;
    int compareRun;                   ///< index into runs shown in the compare view, -1 = none
    PanelActions actions;             ///< the panel's: requests, and the dirty flag a rename sets
    void request(Command c, int index = -1) const { actions.request(c, {}, index); }
    void markDirty() const { actions.markDirty(); }
};

/// Right-click menu of a run's row: rename it and the row's actions (also in the last column, which a
/// narrow pane scrolls out of sight).
void runMenu(RunsTableView& t, Run& run, int i) {
    if (!ImGui::BeginPopupContextItem("##run menu")) return;
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 16);
    if (ImGui::InputText("name", &run.name)) t.markDirty();
    if (ImGui::MenuItem("Re-open")) t.request(Command::ReopenRun, i);
    if (ImGui::MenuItem("Compare")) t.request(Command::CompareRun, i);
    if (ImGui::MenuItem("Delete")) t.request(Command::DeleteRun, i);
    ImGui::EndPopup();
}

/// The runs table's columns, in their order: what tells runs apart and what they achieved first, so
/// a narrow pane shows them without scrolling; the rest can be hidden from the header's context menu.
enum RunColumn { kName, kKind, kError, kTime, kFrame, kA, kB, kActions, kState, kTrainer, kHidden, kLeaves, kRecords, kSpp, kCorrected, kRunColumns };

void drawRuns(RunsTableView& t) {
    if (t.runs.empty()) {
        ImGui::PushTextWrapPos(0.f);
        ImGui::TextDisabled("No runs yet. \"Save run\" in the Views panel records the current ground truth.");
        ImGui::PopTextWrapPos();
        return;
    }
    // Horizontal scrolling reaches the columns a narrow pane cannot show. Not resizable: ImGui stops
    // fitting a resizable column to its content after the first frames, so figures that arrive later
    // (a new run's error) would be cut. Hideable: the header's context menu hides or shows columns.
    const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollX |
                                  ImGuiTableFlags_ScrollY | ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_Hideable;
    struct Column {
        const char* header;
        ImGuiTableColumnFlags flags;
    };
    constexpr ImGuiTableColumnFlags hide = ImGuiTableColumnFlags_DefaultHide;
    const Column columns[kRunColumns] = {
        {"name", ImGuiTableColumnFlags_NoHide}, {"kind", 0}, {"error (floor)", 0}, {"time (s)", 0}, {"frame (ms)", 0},
        {"A", 0}, {"B", 0}, {"actions", 0}, {"state", hide}, {"trainer", hide}, {"hidden", hide}, {"leaves", hide},
        {"records", hide}, {"spp", hide}, {"corrected", hide}};
    if (!ImGui::BeginTable("##runs", kRunColumns, flags, ImVec2(0, ImGui::GetFontSize() * 14))) return;
    ImGui::TableSetupScrollFreeze(1, 1);
    for (const Column& c : columns) ImGui::TableSetupColumn(c.header, c.flags);
    ImGui::TableHeadersRow();
    // Computed when the runs' ids or names changed (a rename below shows from the next frame on).
    const std::vector<std::string>& names = t.names.of(t.runs);
    for (size_t i = 0; i < t.runs.size(); ++i) {
        Run& run = t.runs[i];
        const RunSummary r = summarizeRun(run);
        ImGui::PushID(run.id.c_str());
        ImGui::TableNextRow();
        // The name spans the row, so hovering anywhere on it shows every field and a right click
        // opens its menu; the checkboxes and buttons of later cells stay clickable over it.
        ImGui::TableSetColumnIndex(kName);
        ImGui::Selectable(names[i].c_str(), t.compareRun == int(i),
                          ImGuiSelectableFlags_SpanAllColumns | ImGuiSelectableFlags_AllowItemOverlap);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", runTooltipText(run).c_str());
        runMenu(t, run, int(i));
        if (ImGui::TableSetColumnIndex(kKind)) ImGui::TextUnformatted(r.kind.c_str());
        if (ImGui::TableSetColumnIndex(kError)) ImGui::TextUnformatted(errorWithFloorText(r).c_str());
        if (ImGui::TableSetColumnIndex(kTime)) ImGui::TextUnformatted(numberText(r.seconds, "%.2f").c_str());
        if (ImGui::TableSetColumnIndex(kFrame)) {
            ImGui::TextUnformatted(frameText(r).c_str());
            if (r.frameSeconds && ImGui::IsItemHovered()) {
                const std::string size = r.frameWidth > 0 ? sizeText(r.frameWidth, r.frameHeight) : std::string("the view's size");
                ImGui::SetTooltip(r.frameGlsl ? "one full-quality GLSL frame at %s: the GPU time of the G-buffer and network passes\n"
                                                "(GL timer queries, median of the last frames; read-back excluded).\n"
                                                "On a software driver (Mesa llvmpipe) the GPU is this machine's CPU."
                                              : "one CPU frame at %s: wall time of the G-buffer, the networks and the direct light\n"
                                                "(median of the last frames)",
                                  size.c_str());
            }
        }
        // A and B: the two training runs the Views show side by side (prediction A | B | difference).
        for (int* pick : {&t.pair.a, &t.pair.b}) {
            if (!ImGui::TableSetColumnIndex(pick == &t.pair.a ? kA : kB) || run.kind != "train") continue;
            bool on = *pick == int(i);
            if (ImGui::Checkbox(pick == &t.pair.a ? "##a" : "##b", &on)) {
                *pick = on ? int(i) : -1;
                if (t.pair.a >= 0 && t.pair.b >= 0 && t.pair.a != t.pair.b)
                    t.request(Command::CompareRunPair);
            }
        }
        if (ImGui::TableSetColumnIndex(kActions)) {
            if (ImGui::SmallButton("Re-open")) t.request(Command::ReopenRun, int(i));
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("Restore this run's settings and show its images");
            ImGui::SameLine();
            const bool comparing = t.compareRun == int(i);
            if (ImGui::SmallButton(comparing ? "Comparing" : "Compare")) t.request(Command::CompareRun, int(i));
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip(run.kind == "train" ? "Show this run's models' prediction next to the ground truth"
                                                      : "Show this run next to the ground truth, with the error map");
            ImGui::SameLine();
            if (ImGui::SmallButton("Delete")) t.request(Command::DeleteRun, int(i));
        }
        if (ImGui::TableSetColumnIndex(kState)) {
            if (r.stopped) figureTextColored(ImVec4(1.f, 0.8f, 0.3f, 1.f), "%s", r.status.c_str());
            else ImGui::TextUnformatted(r.status.c_str());
        }
        if (ImGui::TableSetColumnIndex(kTrainer)) ImGui::TextUnformatted(r.trainer.empty() ? "-" : r.trainer.c_str());
        if (ImGui::TableSetColumnIndex(kHidden)) ImGui::TextUnformatted(hiddenText(r.hidden).c_str());
        if (ImGui::TableSetColumnIndex(kLeaves))
            ImGui::TextUnformatted(numberText(r.leaves ? std::optional<double>(*r.leaves) : std::nullopt, "%.0f").c_str());
        if (ImGui::TableSetColumnIndex(kRecords)) ImGui::TextUnformatted(numberText(r.records, "%.0f").c_str());
        if (ImGui::TableSetColumnIndex(kSpp)) ImGui::TextUnformatted(numberText(r.spp, "%.0f").c_str());
        if (ImGui::TableSetColumnIndex(kCorrected)) ImGui::TextUnformatted(numberText(r.corrected, "%.4g").c_str());
        ImGui::PopID();
    }
    ImGui::EndTable();
    ImGui::PushTextWrapPos(0.f);
    ImGui::TextDisabled("Tick A and B on two training runs to see their predictions side by side; hover a run for all its "
                        "fields, right-click it to rename it; right-click the header to show or hide columns.");
    ImGui::PopTextWrapPos();
}
}  // namespace
}  // namespace project_panel_detail

void drawProjectPanel(const ProjectPanelView& panel) {
    if (ImGui::Button("New")) panel.actions.request(Command::NewProject);
    ImGui::SameLine();
    if (ImGui::Button("Open...")) panel.actions.request(Command::OpenProject);
    ImGui::SameLine();
    if (ImGui::Button("Save")) panel.actions.request(Command::SaveProject);
    ImGui::SameLine();
    if (ImGui::Button("Save as...")) panel.actions.request(Command::SaveProjectAs);

    if (panel.actions.notice && panel.actions.notice->panel == "Project") drawNotice(panel.actions.notice);
    if (!panel.hasProject) {
        ImGui::TextDisabled("No project is open.");
        return;
    }
    ImGui::Separator();
    std::string name = projectDisplayName(panel.project, panel.hasProject);
    if (ImGui::InputText("name", &name)) {
        panel.project.name = name;
        panel.actions.markDirty();
    }
    figureTextDisabled("file   %s", panel.project.path.empty() ? "(not saved yet)" : panel.project.path.c_str());
    figureTextDisabled("scene  %s", panel.project.sceneRef.empty() ? "(embedded)" : panel.project.sceneRef.c_str());
    figureTextDisabled("%s", panel.actions.dirty ? "unsaved changes" : "saved");

    if (ImGui::CollapsingHeader("Ground-truth render", ImGuiTreeNodeFlags_DefaultOpen))
        project_panel_detail::drawRenderSettings(panel.project.render, panel.project.scene, panel.actions.dirty);
    if (ImGui::CollapsingHeader("Runs", ImGuiTreeNodeFlags_DefaultOpen)) {
        project_panel_detail::RunsTableView runs{panel.project.runs, panel.runNames, panel.runPair, panel.compareRun,
                                                 panel.actions};
        project_panel_detail::drawRuns(runs);
    }
    if (ImGui::CollapsingHeader("Recent projects")) {
        if (panel.recent.empty()) ImGui::TextDisabled("(none)");
        for (size_t i = 0; i < panel.recent.size(); ++i) {
            ImGui::PushID(int(i));
            if (ImGui::Selectable(panel.recent[i].c_str())) panel.actions.request(Command::OpenProject, panel.recent[i]);
            ImGui::PopID();
        }
    }
}

}  // namespace rrf::panels
