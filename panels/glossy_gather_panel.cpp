// The Network panel's glossy gather (core/predict/glossy_gather.h): which objects take their indirect
// light from one more bounce instead of their own network, and how many directions each pixel
// gathers. The settings are the project's "prediction": {"gather"} section, so the CLI and a saved
// project predict the same way.

#include <algorithm>
#include <string>

#include <imgui.h>

#include "core/predict/glossy_gather.h"
#include "panels/figure_text.h"
#include "panels/panels.h"

namespace rrf::panels {

bool setGlossyGather(const NetworkPanelView& panel, const PredictionSettings::Gather& gather) {
    PredictionSettings::Gather g = gather;
    g.minExponent = std::clamp(g.minExponent, 0.0, 1e6);
    g.lobeSamples = std::clamp(g.lobeSamples, 0, kMaxGatherSamples);
    g.diffuseSamples = std::clamp(g.diffuseSamples, 0, kMaxGatherSamples);
    g.directSamples = std::clamp(g.directSamples, 1, kMaxDirectSamples);
    g.causticSamples = std::clamp(g.causticSamples, 0, kMaxGatherSamples);
    const PredictionSettings::Gather& old = panel.project.prediction.gather;
    if (g.minExponent == old.minExponent && g.lobeSamples == old.lobeSamples && g.diffuseSamples == old.diffuseSamples &&
        g.directSamples == old.directSamples && g.causticSamples == old.causticSamples)
        return false;
    panel.project.prediction.gather.minExponent = g.minExponent;
    panel.project.prediction.gather.lobeSamples = g.lobeSamples;
    panel.project.prediction.gather.diffuseSamples = g.diffuseSamples;
    panel.project.prediction.gather.directSamples = g.directSamples;
    panel.project.prediction.gather.causticSamples = g.causticSamples;
    panel.actions.markDirty();
    panel.actions.request(Command::PredictionChanged);
    return true;
}

std::string gatheredObjectNames(const Scene& scene, const PredictionSettings& prediction) {
    std::string names;
    for (const Object& o : scene.objects)
        if (GlossyGather::gathers(scene, o, prediction)) names += (names.empty() ? "" : ", ") + o.name;
    return names;
}

void drawGlossyGather(const NetworkPanelView& panel) {
    PredictionSettings::Gather g = panel.project.prediction.gather;
    if (!ImGui::TreeNodeEx("Glossy gather (prediction)", ImGuiTreeNodeFlags_DefaultOpen)) return;
    bool on = g.minExponent > 0.0;
    bool changed = false;
    if (ImGui::Checkbox("gather sharply glossy objects", &on)) {
        g.minExponent = on ? PredictionSettings().gather.minExponent : 0.0;
        changed = true;
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("a near-mirror's indirect light is the scene seen in the mirror: trace one more bounce\n"
                          "and take exact direct light + the networks where it lands, instead of the object's own network");
    if (on) {
        float minExponent = float(g.minExponent);
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8);
        if (ImGui::InputFloat("from Phong exponent", &minExponent, 0.f, 0.f, "%.0f")) {
            g.minExponent = std::max(1.0, double(minExponent));
            changed = true;
        }
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8);
        changed |= ImGui::InputInt("lobe directions", &g.lobeSamples);
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8);
        changed |= ImGui::InputInt("diffuse directions", &g.diffuseSamples);
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8);
        changed |= ImGui::InputInt("light samples there", &g.directSamples);
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8);
        changed |= ImGui::InputInt("caustic samples", &g.causticSamples);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("light a gathered pixel receives diffusely by way of a polished face, sampled from the\n"
                              "light per face plane (0: left to the diffuse directions, which find it as fireflies)");
    }
    if (changed) setGlossyGather(panel, g);
    const std::string names = gatheredObjectNames(panel.project.scene, panel.project.prediction);
    figureText("%s", names.empty() ? "no object is gathered: every object's indirect light is its network's"
                                           : ("gathered (CPU prediction; the GLSL view shows their networks until the "
                                              "CPU frame arrives): " + names).c_str());
    ImGui::TreePop();
}

}  // namespace rrf::panels
