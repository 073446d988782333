// Status words of jobs and results (see status_text.h).
#include "panels/status_text.h"

#include <algorithm>
#include <cstdio>

#include <imgui.h>

#include "core/pipeline/run_recording.h"
#include "panels/figure_text.h"

namespace rrf::panels {

std::string renderProgressText(const RenderProgress& r) {
    char buf[96];
    if (r.running) std::snprintf(buf, sizeof buf, "%d/%d spp", r.spp, r.targetSpp);
    else if (r.cancelled) std::snprintf(buf, sizeof buf, "cancelled at %d/%d spp", r.spp, r.targetSpp);
    else std::snprintf(buf, sizeof buf, "%d/%d spp done", r.spp, r.targetSpp);
    return buf;
}

std::string trainingProgressText(const TrainingInfo& t) {
    if (t.running) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.0f%%", 100 * t.progress);
        return buf;
    }
    if (t.stopped) return stoppedTrainingText(t.epoch, t.networks, t.plannedNetworks);
    return "done, " + std::to_string(t.networks) + (t.networks == 1 ? " network" : " networks");
}

std::string datasetStaleReason(const DatasetInfo& d, const Project& project) {
    if (d.path.empty()) return {};
    if (d.lastCancelled) return "stale: the last generation was cancelled or failed; this is the dataset before it";
    if (d.sceneHash != 0 && d.sceneHash != project.scene.contentHash())
        return "stale: the scene changed since this dataset was generated";
    if (d.madeWith && *d.madeWith != project.samplingOrDefault())
        return "stale: the sampling settings changed since this dataset was generated";
    return {};
}

std::string withoutNetworkText(const ImageSet& set, const Scene& scene) {
    const size_t n = set.withoutNetwork.size();
    if (n == 0) return {};
    std::string t = "hatched magenta: no network for " + std::to_string(n) + (n == 1 ? " object (" : " objects (");
    for (size_t i = 0; i < n; ++i) {
        const int id = set.withoutNetwork[i];
        if (i) t += ", ";
        t += id >= 0 && id < int(scene.objects.size()) ? scene.objects[size_t(id)].name : "#" + std::to_string(id);
    }
    return t + "): a partial model set";
}

int clampWithNotice(const PanelActions& actions, const char* panel, const std::string& what, int value, int lo, int hi) {
    const int kept = std::clamp(value, lo, hi);
    if (kept != value)
        actions.notify(LogLevel::Warning, panel,
                     what + " is " + std::to_string(lo) + " ... " + std::to_string(hi) + "; " + std::to_string(value) +
                         " was set to " + std::to_string(kept));
    return kept;
}

void drawNotice(std::optional<Notice>& notice, bool wrap) {
    if (!notice) return;
    const Notice& n = *notice;
    // Errors red, warnings amber, a finished action (saved, exported, written) green.
    const ImVec4 colour = n.level == LogLevel::Error     ? ImVec4(1.f, 0.45f, 0.4f, 1.f)
                          : n.level == LogLevel::Warning ? ImVec4(1.f, 0.8f, 0.3f, 1.f)
                                                         : ImVec4(0.55f, 0.9f, 0.55f, 1.f);
    ImGui::PushID("##notice");
    const bool dismiss = ImGui::SmallButton("Dismiss");
    ImGui::SameLine();
    // In a panel the text wraps at the pane's edge; on the one-line status bar it runs on, and
    // hovering shows it whole.
    if (wrap) ImGui::PushTextWrapPos(0.f);
    figureTextColored(colour, "%s", n.text.c_str());
    if (wrap) ImGui::PopTextWrapPos();
    else if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", n.text.c_str());
    ImGui::PopID();
    if (dismiss) notice.reset();
}

}  // namespace rrf::panels
