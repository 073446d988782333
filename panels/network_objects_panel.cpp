// The Network panel's derived inputs and per-object networks (issue 26): the reflected-direction
// input of every network, and for each scene object the entry of Project::network's "objects" map
// (nn/object_network_overrides.h) that changes its reflected input, hidden sizes or input encoding.
// Like the rest of the panel, every edit goes through storeNetworkSettings(), and each row says what
// the object's networks will read, or why training would refuse them.
#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>

#include <imgui.h>

#include "core/nn/encoding_presets.h"
#include "core/util/error.h"
#include "panels/figure_text.h"
#include "panels/panels.h"

namespace rrf::panels {

namespace network_objects_panel_detail {
namespace {

/// The object's entry (an empty one when it has none).
ObjectNetworkOverride entryOf(const NetworkSettings& s, const std::string& name) {
    const auto it = s.options.perObject.find(name);
    return it == s.options.perObject.end() ? ObjectNetworkOverride() : it->second;
}

/// Stores `entry` as the object's (an empty entry removes it); false when nothing changed.
bool storeEntry(const NetworkPanelView& panel, NetworkSettings s, const std::string& name, const ObjectNetworkOverride& entry) {
    if (entryOf(s, name) == entry) return false;
    if (entry.empty()) s.options.perObject.erase(name);
    else s.options.perObject[name] = entry;
    storeNetworkSettings(panel, s);
    return true;
}

/// One object's row: reflected (section's / on / off), hidden sizes (empty: the section's), encoding
/// (section's or a named one), then what its networks read.
void drawObjectRow(const NetworkPanelView& panel, const NetworkSettings& s, const std::string& name, int inputs) {
    const ObjectNetworkOverride entry = entryOf(s, name);
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(name.c_str());

    ImGui::TableNextColumn();
    int reflected = !entry.inputs ? 0 : entry.inputs->reflected ? 1 : 2;
    const char* items = s.options.inputs.reflected ? "section's (on)\0on\0off\0" : "section's (off)\0on\0off\0";
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 7);
    if (ImGui::Combo("##reflected", &reflected, items))
        setObjectReflected(panel, name, reflected == 0 ? std::nullopt : std::optional<bool>(reflected == 1));

    ImGui::TableNextColumn();
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s", entry.hidden ? hiddenSizesText(*entry.hidden).c_str() : "");
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 6);
    if (ImGui::InputTextWithHint("##hidden", hiddenSizesText(s.options.hidden).c_str(), buf, sizeof buf,
                                 ImGuiInputTextFlags_EnterReturnsTrue)) {
        const std::string text = buf;
        try {
            setObjectHidden(panel, name, text.empty() ? std::nullopt : std::optional(parseHiddenSizes(text, "hidden")));
        } catch (const SettingError&) {
            // Not a list of sizes: the field shows the stored value again next frame.
        }
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("layer sizes, e.g. 32,16; empty: the section's");

    ImGui::TableNextColumn();
    const std::string own = entry.encoding ? encodingPresetName(*entry.encoding) : "";
    const char* shown = !entry.encoding ? "section's" : own.empty() ? "custom (the project file's)" : own.c_str();
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 9);
    if (ImGui::BeginCombo("##encoding", shown)) {
        if (ImGui::Selectable("section's", !entry.encoding)) setObjectEncoding(panel, name, "");
        for (const EncodingPreset& p : encodingPresets()) {
            if (ImGui::Selectable(p.name, entry.encoding && own == p.name)) setObjectEncoding(panel, name, p.name);
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", p.summary);
        }
        ImGui::EndCombo();
    }

    ImGui::TableNextColumn();
    const ObjectNetworkChoice c = s.options.choiceFor(name);
    const EncodingSettingView view = viewEncodingSetting(c.encoding, inputs, c.inputs);
    if (view.fits) figureTextDisabled("%s, [%s]", view.encoding.describe().c_str(), hiddenSizesText(c.hidden).c_str());
    else figureTextColored(ImVec4(1.f, .4f, .4f, 1.f), "%s", view.error.c_str());
}

}  // namespace
}  // namespace network_objects_panel_detail

void storeNetworkSettings(const NetworkPanelView& panel, const NetworkSettings& s) {
    panel.project.network = s;
    panel.actions.markDirty();
}

bool setReflectedInput(const NetworkPanelView& panel, bool on) {
    NetworkSettings s = panel.project.networkOrDefault();
    if (s.options.inputs.reflected == on) return false;
    s.options.inputs.reflected = on;
    storeNetworkSettings(panel, s);
    return true;
}

bool setObjectReflected(const NetworkPanelView& panel, const std::string& name, std::optional<bool> on) {
    const NetworkSettings s = panel.project.networkOrDefault();
    ObjectNetworkOverride entry = network_objects_panel_detail::entryOf(s, name);
    if (on) entry.inputs = DerivedInputs{*on};
    else entry.inputs.reset();
    return network_objects_panel_detail::storeEntry(panel, s, name, entry);
}

bool setObjectHidden(const NetworkPanelView& panel, const std::string& name, std::optional<std::vector<int>> hidden) {
    const NetworkSettings s = panel.project.networkOrDefault();
    ObjectNetworkOverride entry = network_objects_panel_detail::entryOf(s, name);
    if (hidden) {
        if (hidden->empty()) return false;  // the file format needs at least one hidden layer
        for (int& h : *hidden) h = std::clamp(h, 1, kMaxHiddenSize);
    }
    entry.hidden = std::move(hidden);
    return network_objects_panel_detail::storeEntry(panel, s, name, entry);
}

bool setObjectEncoding(const NetworkPanelView& panel, const std::string& name, const std::string& encoding) {
    const NetworkSettings s = panel.project.networkOrDefault();
    ObjectNetworkOverride entry = network_objects_panel_detail::entryOf(s, name);
    if (encoding.empty()) {
        entry.encoding.reset();
    } else {
        const EncodingPreset* preset = findEncodingPreset(encoding);
        if (!preset) return false;
        entry.encoding = preset->settings;
    }
    return network_objects_panel_detail::storeEntry(panel, s, name, entry);
}

void drawObjectNetworks(const NetworkPanelView& panel, int inputs) {
    NetworkSettings s = panel.project.networkOrDefault();
    bool reflected = s.options.inputs.reflected;
    if (ImGui::Checkbox("reflected direction input", &reflected)) {
        setReflectedInput(panel, reflected);
        s = panel.project.networkOrDefault();
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("every network also reads the view direction reflected about the normal (Ref-NeRF):\n"
                          "a near-mirror's indirect light is a smooth function of it; encodings may name it \"reflected\"");
    // Open by default when the project has entries, so they are never hidden from view.
    const ImGuiTreeNodeFlags open = s.options.perObject.empty() ? 0 : ImGuiTreeNodeFlags_DefaultOpen;
    if (!ImGui::TreeNodeEx("Per-object networks", open)) return;
    if (ImGui::BeginTable("object networks", 5, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
        ImGui::TableSetupColumn("object");
        ImGui::TableSetupColumn("reflected");
        ImGui::TableSetupColumn("hidden");
        ImGui::TableSetupColumn("encoding");
        ImGui::TableSetupColumn("networks read");
        ImGui::TableHeadersRow();
        for (const Object& o : panel.project.scene.objects) {
            ImGui::PushID(o.id);
            network_objects_panel_detail::drawObjectRow(panel, s, o.name, inputs);
            ImGui::PopID();
            s = panel.project.networkOrDefault();  // a row's edit is stored already
        }
        ImGui::EndTable();
    }
    ImGui::TreePop();
}

}  // namespace rrf::panels
