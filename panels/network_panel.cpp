// Network panel: hidden layers, activation, the ensemble size, the input encoding (by name), the
// reflected-direction input and per-object networks (network_objects_panel.cpp), what the networks predict, the kd-tree partition
// (Ren et al.'s leaves: goal, depth, leaf budget, records per weight, split axes), the trainer and its
// parameters (error goal included), and the parameter count of each network. Project::network and Project::trainer are the
// only copies of these settings: every edit goes through storeNetwork() or storeTrainer(), so editing
// the layers does not add a "trainer" section to the project (nor the trainer a "network" one).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <imgui.h>

#include "core/data/record_layout.h"
#include "core/nn/encoding_presets.h"
#include "core/nn/ensemble.h"
#include "core/util/error.h"
#include "panels/clip_check.h"
#include "panels/figure_text.h"
#include "panels/panels.h"
#include "panels/pipeline_controls.h"
#include "panels/status_text.h"

namespace rrf::panels {

namespace network_panel_detail {
namespace {
constexpr int kMaxLayers = 8;

/// The settings in effect. A project without network/trainer sections keeps none until an edit.
NetworkSettings current(const NetworkPanelView& panel) { return panel.project.networkOrDefault(); }
TrainerConfig currentTrainer(const NetworkPanelView& panel) { return panel.project.trainerOrDefault(); }

/// Stores the "network" part of `s` (layers, activation, targets).
void storeNetwork(const NetworkPanelView& panel, const NetworkSettings& s) { storeNetworkSettings(panel, s); }

/// Stores the trainer (the project's "trainer" section).
void storeTrainer(const NetworkPanelView& panel, const TrainerConfig& t) {
    panel.project.trainer = t;
    panel.actions.markDirty();
}

/// Network inputs: the generated dataset's count when there is one, else the scene's record layout
/// (the same number unless the scene changed since).
int inputCount(const NetworkPanelView& panel) {
    if (panel.dataset.inputCount > 0) return panel.dataset.inputCount;
    return RecordLayout::forScene(panel.project.scene).inputCount();
}

bool inputDouble(const char* label, double& v, double lo, double hi, const char* fmt = "%.4g") {
    double x = v;
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8);
    if (!ImGui::InputDouble(label, &x, 0.0, 0.0, fmt, ImGuiInputTextFlags_EnterReturnsTrue)) return false;
    x = std::clamp(x, lo, hi);
    if (x == v) return false;
    v = x;
    return true;
}

bool inputInt(const char* label, int& v, int lo, int hi) {
    int x = v;
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8);
    if (!ImGui::InputInt(label, &x, 0, 0, ImGuiInputTextFlags_EnterReturnsTrue)) return false;
    x = std::clamp(x, lo, hi);
    if (x == v) return false;
    v = x;
    return true;
}

bool inputInt64(const char* label, int64_t& v, int64_t lo, int64_t hi) {
    int x = int(std::min<int64_t>(v, 1 << 30));
    if (!inputInt(label, x, int(lo), int(std::min<int64_t>(hi, 1 << 30)))) return false;
    v = x;
    return true;
}

bool drawLevenbergMarquardt(LevenbergMarquardtConfig& c) {
    bool changed = inputInt("max epochs", c.maxEpochs, 1, 1000000);
    changed |= inputDouble("mu (initial damping)", c.mu, 1e-20, 1e20);
    changed |= inputDouble("mu_dec", c.muDec, 1e-6, 1.0);
    changed |= inputDouble("mu_inc", c.muInc, 1.0, 1e6);
    changed |= inputDouble("mu_max", c.muMax, 1e-6, 1e30);
    changed |= inputDouble("min gradient", c.minGrad, 0.0, 1e6);
    changed |= inputInt("max validation fails", c.maxFail, 0, 1000000);
    changed |= inputInt64("max samples (0 = all)", c.maxSamples, 0, int64_t(1) << 40);
    changed |= inputDouble("max GFLOP per epoch", c.maxEpochGflop, 0.0, 1e9);
    changed |= inputDouble("error goal", c.errorGoal, 0.0, 10.0);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("stop when the validation relative RMSE (noise-corrected) is below this; 0 = none");
    ImGui::TextDisabled("LM costs ~3 N P^2 flops per epoch: it trains on at most max samples (and the GFLOP bound).");
    return changed;
}

bool drawAdam(AdamConfig& c) {
    bool changed = inputInt("max epochs", c.maxEpochs, 1, 1000000);
    changed |= inputInt("batch size", c.batchSize, 1, 1 << 20);
    changed |= inputDouble("learning rate", c.learningRate, 1e-12, 10.0);
    int schedule = int(c.schedule);
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8);
    if (ImGui::Combo("schedule", &schedule, "constant\0step\0cosine\0")) {
        c.schedule = LrSchedule(schedule);
        changed = true;
    }
    if (c.schedule == LrSchedule::Cosine) changed |= inputDouble("min learning rate", c.minLearningRate, 0.0, 10.0);
    if (c.schedule == LrSchedule::Step) {
        changed |= inputInt("step epochs", c.stepEpochs, 1, 1000000);
        changed |= inputDouble("step gamma", c.stepGamma, 1e-6, 1.0);
    }
    int loss = int(c.loss);
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8);
    if (ImGui::Combo("loss", &loss, "mse\0relative L2\0relative L2 (prediction)\0")) {
        c.loss = AdamLoss(loss);
        changed = true;
    }
    if (c.loss == AdamLoss::RelativeL2) {
        changed |= ImGui::Checkbox("debias targets", &c.debiasTargets);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("raise each noisy target by 2 v / (|y| + 0.01), v its variance, which cancels the low bias of a\n"
                              "loss weighted by the noisy target itself (about -2 sigma^2: -2 %% at 10 %% record noise)");
    }
    changed |= inputDouble("weight decay", c.weightDecay, 0.0, 10.0);
    changed |= inputInt("patience (0 = none)", c.patience, 0, 1000000);
    changed |= inputDouble("patience below rate fraction", c.patienceLrFraction, 0.0, 1.0);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("epochs count toward patience only once the rate is at most this fraction of the learning rate");
    changed |= inputDouble("error goal", c.errorGoal, 0.0, 10.0);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("stop when the validation relative RMSE (noise-corrected) is below this; 0 = none");
    return changed;
}

/// The kd-tree settings; returns true when one changed. `paramsPerNetwork` < 0: unknown (no bound shown).
bool drawPartition(PartitionSettings& p, long long paramsPerNetwork) {
    bool changed = inputInt("max leaves (1 = none)", p.maxLeaves, 1, kMaxPartitionLeaves);
    changed |= inputInt("max depth", p.maxDepth, 0, 20);
    changed |= inputDouble("split above error", p.goal, 1e-6, 10.0);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("a node splits while its validation relative RMSE (noise-corrected) is above this");
    changed |= inputDouble("min records per weight", p.minRecordsPerWeight, 1.0, 1000.0, "%.3g");
    changed |= inputDouble("min split gain", p.minSplitGain, 0.0, 0.99, "%.3g");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("a split is kept only if its halves lower the node's validation error by this fraction (0 = keep all)");
    changed |= ImGui::Checkbox("split on position", &p.axes.position);
    ImGui::SameLine();
    changed |= ImGui::Checkbox("split on light", &p.axes.light);
    if (!p.axes.any()) ImGui::TextColored(ImVec4(1.f, .6f, .3f, 1.f), "no split axis: the trees will not grow");
    if (p.enabled() && paramsPerNetwork >= 0)
        figureTextDisabled("a node splits only if each half keeps >= %.0f records (%.3g x %lld weights)",
                            std::ceil(p.minRecordsPerWeight * double(paramsPerNetwork)), p.minRecordsPerWeight,
                            paramsPerNetwork);
    return changed;
}

/// The MLP of one network under `s`: its first layer reads the encoding's features.
MlpArch networkArch(const NetworkPanelView& /*panel*/, const NetworkSettings& s, const InputEncoding& encoding) {
    MlpArch arch;
    arch.inputs = encoding.outputs();  // the identity: the record inputs and the derived ones
    arch.hidden = s.options.hidden;
    arch.activation = s.options.activation;
    arch.outputs = s.options.targets == TargetMode::Joint ? 6 : 3;
    return arch;
}

/// The encoding combo (the named encodings, plus "custom" when the project's own array is none of
/// them) and the warning for a trainable encoding under Levenberg–Marquardt.
void drawEncoding(const NetworkPanelView& panel, const NetworkSettings& s) {
    const EncodingSettingView view = viewEncodingSetting(s.options.encoding, inputCount(panel), s.options.inputs);
    const std::string& name = view.presetName;
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 12);
    if (ImGui::BeginCombo("input encoding", name.empty() ? "custom (the project file's)" : name.c_str())) {
        for (const EncodingPreset& p : encodingPresets()) {
            if (ImGui::Selectable(p.name, name == p.name)) setEncoding(panel, p.name);
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", p.summary);
        }
        ImGui::EndCombo();
    }
    if (currentTrainer(panel).type == TrainerType::LevenbergMarquardt && view.hasParameters)
        ImGui::TextColored(ImVec4(1.f, .6f, .3f, 1.f),
                           "a hash grid's tables train with Adam only: choose the Adam trainer (LM would refuse)");
    if (s.options.ensemble > 1 && view.hasParameters)
        ImGui::TextColored(ImVec4(1.f, .6f, .3f, 1.f),
                           "an ensemble's members cannot share a hash grid's tables: ensemble 1 or a fixed encoding");
}

void drawParameterCount(const NetworkPanelView& panel, const NetworkSettings& s) {
    const EncodingSettingView view = viewEncodingSetting(s.options.encoding, inputCount(panel), s.options.inputs);
    if (!view.fits) {
        // A project's own array may not fit this scene's records (e.g. a hash grid over more than 4
        // inputs); training would refuse it with this message, so show it in place of the count.
        figureTextColored(ImVec4(1.f, .4f, .4f, 1.f), "input encoding: %s", view.error.c_str());
        return;
    }
    const InputEncoding& encoding = view.encoding;
    const MlpArch arch = ensembleArch(networkArch(panel, s, encoding), s.options.ensemble);
    const int perObject = s.options.targets == TargetMode::Separate ? 2 : 1;
    const long long table = (long long)encoding.numParams();
    const long long params = (long long)arch.numParams() + table;
    const std::string hidden = hiddenSizesText(arch.hidden);
    if (encoding.isIdentity())
        figureText("%d inputs%s -> [%s] -> %d outputs: %lld parameters per network", arch.inputs,
                    encoding.derived.any() ? " (with the reflected direction)" : "", hidden.c_str(), arch.outputs, params);
    else
        figureText("%d inputs -> %s -> %d features -> [%s] -> %d outputs: %lld parameters per network (%lld in the encoding)",
                    inputCount(panel), encoding.describe().c_str(), arch.inputs, hidden.c_str(), arch.outputs, params, table);
    if (s.options.ensemble > 1)
        figureTextDisabled("(the merged network of an ensemble of %d: block-diagonal layers, %d trainings per network)",
                            s.options.ensemble, s.options.ensemble);
    figureText("%d network%s per object, %zu objects: %lld parameters in all", perObject, perObject > 1 ? "s" : "",
                panel.project.scene.objects.size(), params * perObject * (long long)panel.project.scene.objects.size());
    if (!s.options.perObject.empty())
        figureTextDisabled("(counted with the section's networks; %zu object%s with its own entry differ%s)",
                            s.options.perObject.size(), s.options.perObject.size() > 1 ? "s" : "",
                            s.options.perObject.size() > 1 ? "" : "s");
    if (currentTrainer(panel).type == TrainerType::LevenbergMarquardt) {
        const long long member = (long long)networkArch(panel, s, encoding).numParams();  // LM trains each member alone
        figureTextDisabled("LM solves a %lld x %lld system per step", member, member);
    }
}
}  // namespace
}  // namespace network_panel_detail

bool addHiddenLayer(const NetworkPanelView& panel) {
    NetworkSettings s = network_panel_detail::current(panel);
    if (int(s.options.hidden.size()) >= network_panel_detail::kMaxLayers) return false;
    // A new layer repeats the last one's size: a sensible start that the user then resizes.
    s.options.hidden.push_back(s.options.hidden.empty() ? 10 : s.options.hidden.back());
    network_panel_detail::storeNetwork(panel, s);
    return true;
}

bool removeHiddenLayer(const NetworkPanelView& panel, int index) {
    NetworkSettings s = network_panel_detail::current(panel);
    // The file format needs at least one hidden layer.
    if (s.options.hidden.size() <= 1 || index < 0 || index >= int(s.options.hidden.size())) return false;
    s.options.hidden.erase(s.options.hidden.begin() + index);
    network_panel_detail::storeNetwork(panel, s);
    return true;
}

bool resizeHiddenLayer(const NetworkPanelView& panel, int index, int size) {
    NetworkSettings s = network_panel_detail::current(panel);
    if (index < 0 || index >= int(s.options.hidden.size())) return false;
    size = clampWithNotice(panel.actions, "Network", "a hidden layer's size", size, 1, kMaxHiddenSize);
    if (s.options.hidden[size_t(index)] == size) return false;
    s.options.hidden[size_t(index)] = size;
    network_panel_detail::storeNetwork(panel, s);
    return true;
}

bool setEnsemble(const NetworkPanelView& panel, int members) {
    NetworkSettings s = network_panel_detail::current(panel);
    members = std::clamp(members, 1, kMaxEnsembleMembers);
    if (s.options.ensemble == members) return false;
    s.options.ensemble = members;
    network_panel_detail::storeNetwork(panel, s);
    return true;
}

bool setTrainerType(const NetworkPanelView& panel, TrainerType type) {
    const TrainerConfig t = network_panel_detail::currentTrainer(panel);
    if (t.type == type) return false;
    network_panel_detail::storeTrainer(panel, t.withType(type));
    return true;
}

bool setPartition(const NetworkPanelView& panel, const PartitionSettings& partition) {
    NetworkSettings s = network_panel_detail::current(panel);
    if (s.options.partition == partition) return false;
    s.options.partition = partition;
    network_panel_detail::storeNetwork(panel, s);
    return true;
}

bool setEncoding(const NetworkPanelView& panel, const std::string& name) {
    NetworkSettings s = network_panel_detail::current(panel);
    if (!setNamedEncoding(s.options.encoding, name)) return false;
    network_panel_detail::storeNetwork(panel, s);
    return true;
}

void drawNetworkPanel(const NetworkPanelView& panel) {
    if (!panel.hasProject) {
        ImGui::TextDisabled("No project is open.");
        return;
    }
    drawNetworkPresets(panel);
    if (panel.actions.notice && panel.actions.notice->panel == "Network") drawNotice(panel.actions.notice);
    NetworkSettings s = network_panel_detail::current(panel);

    ImGui::TextUnformatted("Hidden layers");
    int remove = -1;
    for (size_t i = 0; i < s.options.hidden.size(); ++i) {
        ImGui::PushID(int(i));
        int size = s.options.hidden[i];
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 6);
        char label[32];
        std::snprintf(label, sizeof label, "layer %zu", i + 1);
        if (ImGui::InputInt(label, &size, 1, 5)) resizeHiddenLayer(panel, int(i), size);
        ImGui::SameLine();
        ImGui::BeginDisabled(s.options.hidden.size() <= 1);
        if (ImGui::SmallButton("remove")) remove = int(i);
        ImGui::EndDisabled();
        ImGui::PopID();
    }
    if (remove >= 0) removeHiddenLayer(panel, remove);
    ImGui::BeginDisabled(int(s.options.hidden.size()) >= network_panel_detail::kMaxLayers);
    if (ImGui::Button("Add layer")) addHiddenLayer(panel);
    ImGui::EndDisabled();
    s = network_panel_detail::current(panel);  // the layer edits above are stored already

    int activation = int(s.options.activation);
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8);
    if (ImGui::Combo("activation", &activation, "tanh\0relu\0")) {
        s.options.activation = Activation(activation);
        network_panel_detail::storeNetwork(panel, s);
    }
    int members = s.options.ensemble;
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 6);
    if (ImGui::InputInt("ensemble", &members, 1, 1)) {
        setEnsemble(panel, members);
        s = network_panel_detail::current(panel);
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("networks trained per leaf from different initial weights, merged into one network that "
                          "predicts their mean (hidden layers that many times wider); each costs a full training");
    // Combo order is TargetMode's order: global, direct, indirect, separate, joint.
    int targets = int(s.options.targets);
    const char* targetItems = "global\0direct\0indirect\0separate (direct + indirect nets)\0joint (6 outputs)\0";
    ImGui::SetNextItemWidth(fittedComboWidth(targetItems));  // the longest entry is readable when chosen
    if (ImGui::Combo("targets", &targets, targetItems)) {
        s.options.targets = TargetMode(targets);
        network_panel_detail::storeNetwork(panel, s);
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("per object: one global net, one net per term (separate), or one 6-output net (joint)");
    network_panel_detail::drawEncoding(panel, s);
    drawObjectNetworks(panel, network_panel_detail::inputCount(panel));
    drawGlossyGather(panel);
    s = network_panel_detail::current(panel);

    ImGui::Separator();
    ImGui::TextUnformatted("Partition (kd-tree of networks per object)");
    {
        // The records-per-weight bound counts the MLP's weights only (not an encoding's table entries);
        // unknown (-1) while the encoding does not fit the records (drawParameterCount says why).
        const EncodingSettingView view =
            viewEncodingSetting(s.options.encoding, network_panel_detail::inputCount(panel), s.options.inputs);
        const long long weights =
            view.fits ? (long long)network_panel_detail::networkArch(panel, s, view.encoding).numParams() : -1;
        PartitionSettings p = s.options.partition;
        if (network_panel_detail::drawPartition(p, weights)) setPartition(panel, p);
        s = network_panel_detail::current(panel);
    }

    ImGui::Separator();
    TrainerConfig t = network_panel_detail::currentTrainer(panel);
    int trainer = int(t.type);
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 12);
    if (ImGui::Combo("trainer", &trainer, "Levenberg-Marquardt\0Adam\0")) {
        setTrainerType(panel, TrainerType(trainer));
        t = network_panel_detail::currentTrainer(panel);
    }
    const bool changed = t.type == TrainerType::Adam ? network_panel_detail::drawAdam(t.adam)
                                                     : network_panel_detail::drawLevenbergMarquardt(t.lm);
    if (changed) network_panel_detail::storeTrainer(panel, t);

    ImGui::Separator();
    network_panel_detail::drawParameterCount(panel, s);
}

}  // namespace rrf::panels
