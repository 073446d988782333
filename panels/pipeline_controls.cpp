// Preset choices (Sampling, Network) and the one-click pipeline bar, with the estimates of
// core/pipeline/time_estimate.h and what they were computed from.
#include "panels/pipeline_controls.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <thread>

#include <imgui.h>

#include "core/data/data_generator.h"
#include "core/data/record_layout.h"
#include "core/util/memory_budget.h"
#include "panels/figure_text.h"

namespace rrf::panels {

namespace pipeline_controls_detail {
namespace {
int threads() { return std::max(1, int(std::thread::hardware_concurrency())); }

/// A combo of the presets whose items carry `estimate(preset)`; returns the chosen one (null: none).
template <class Estimate>
const PipelinePreset* presetCombo(const char* label, const PipelinePreset* current, Estimate estimate) {
    const PipelinePreset* chosen = nullptr;
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8);
    if (ImGui::BeginCombo(label, current ? current->name : "custom")) {
        for (const PipelinePreset& p : pipelinePresets()) {
            const StageEstimate e = estimate(p);
            const std::string item = std::string(p.name) + "  (" + rangeText(e) + ")";
            if (ImGui::Selectable(item.c_str(), &p == current)) chosen = &p;
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s\nestimate: %s", p.summary, e.basis.c_str());
        }
        ImGui::EndCombo();
    }
    return chosen;
}

void drawEstimateLine(const char* what, const StageEstimate& e) {
    figureText("estimated %s: %s", what, rangeText(e).c_str());
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", e.basis.c_str());
    ImGui::SameLine();
    ImGui::TextDisabled("(?)");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", e.basis.c_str());
}

StageEstimate total(const std::vector<StageEstimate>& stages) {
    StageEstimate t;
    for (const StageEstimate& e : stages) {
        t.low += e.low;
        t.high += e.high;
        t.basis += (t.basis.empty() ? "" : "\n") + e.basis;
    }
    return t;
}

const char* const kStageNames[] = {"render", "generate", "train", "evaluate"};
const char* const kProjectSettingsLabel = "project settings";
}  // namespace
}  // namespace pipeline_controls_detail

PathRate pathRateOf(const RenderProgress& render) {
    return PathRate::of(render.samplesPerSecond, pipeline_controls_detail::threads());
}

double recordsPerRayOf(const DatasetInfo& d) {
    // Not checked against the scene's hash (a per-frame hash of a large scene would cost the UI
    // thread): the fraction of rays that make a record changes little with material edits.
    if (!d.madeWith || d.generator.records == 0) return 1.0;
    return std::min(1.0, double(d.generator.records) / expectedRecords(*d.madeWith));
}

StageEstimate dataEstimate(const EstimateInputs& in, const SamplingSettings& s) {
    return estimateGenerate(s, pathRateOf(in.render), recordsPerRayOf(in.dataset));
}

std::string generateRefusal(const EstimateInputs& in, const SamplingSettings& s) {
    const int floats = RecordLayout::forScene(in.project.scene).floatsPerRecord();
    const uint64_t cells = saturatingProduct(uint64_t(std::max(s.nx, 0)), uint64_t(std::max(s.ny, 0)), uint64_t(std::max(s.nz, 0)));
    const std::string why =
        memoryShortfall(DataGenerator::memoryEstimate(s, floats, cells), in.availableMemory,
                        std::to_string(cells) + " cells x " + std::to_string(s.directions) + " directions x " +
                            std::to_string(floats) + " floats per record, if every ray makes a record");
    return why.empty() ? why : "the dataset " + why + "; choose a smaller grid or fewer directions";
}

StageEstimate trainingEstimate(const EstimateInputs& in, const SamplingSettings& s, const ObjectTrainingOptions& o) {
    const Scene& scene = in.project.scene;
    return estimateTraining(o, expectedRecords(s, recordsPerRayOf(in.dataset)), int(scene.objects.size()),
                            RecordLayout::forScene(scene).inputCount(), pipeline_controls_detail::threads());
}

std::vector<StageEstimate> pipelineEstimates(const EstimateInputs& in, const PipelinePreset* preset) {
    const SamplingSettings s = preset ? presetSampling(in.project, *preset) : in.project.samplingOrDefault();
    const ObjectTrainingOptions o = preset ? presetNetwork(in.project, *preset) : in.project.trainingOptions();
    const PathRate rate = pathRateOf(in.render);
    return {estimateRender(in.project.render, in.project.scene, rate), dataEstimate(in, s), trainingEstimate(in, s, o),
            estimateEvaluate(in.project.render, in.project.scene, rate)};
}

void drawSamplingPresets(const SamplingPanelView& panel) {
    const PipelinePreset* chosen = pipeline_controls_detail::presetCombo(
        "preset##sampling", matchingSamplingPreset(panel.project),
        [&](const PipelinePreset& p) { return dataEstimate(panel.estimates, presetSampling(panel.project, p)); });
    if (chosen) {
        applySamplingPreset(panel.project, *chosen);
        panel.actions.markDirty();
    }
    pipeline_controls_detail::drawEstimateLine("data time", dataEstimate(panel.estimates, panel.project.samplingOrDefault()));
}

void drawNetworkPresets(const NetworkPanelView& panel) {
    const SamplingSettings s = panel.project.samplingOrDefault();
    const PipelinePreset* chosen = pipeline_controls_detail::presetCombo(
        "preset##network", matchingNetworkPreset(panel.project),
        [&](const PipelinePreset& p) { return trainingEstimate(panel.estimates, s, presetNetwork(panel.project, p)); });
    if (chosen) {
        applyNetworkPreset(panel.project, *chosen);
        panel.actions.markDirty();
    }
    pipeline_controls_detail::drawEstimateLine("training time",
                                               trainingEstimate(panel.estimates, s, panel.project.trainingOptions()));
}

std::string pipelineChoiceLabel(const std::string& preset) {
    return preset.empty() ? pipeline_controls_detail::kProjectSettingsLabel : preset;
}

std::string pipelineExpectation(const Project& project, const std::string& presetName, bool brief) {
    const PipelinePreset* preset = presetName.empty() ? matchingPreset(project) : findPreset(presetName);
    if (preset) return brief ? preset->expectationShort : preset->expectation;
    return brief ? "custom settings"
                 : "custom settings: no preset's figures apply; the run's own evaluation (Objects, Runs) says how good it is";
}

namespace pipeline_controls_detail {
namespace {
/// The bar's choice: the project's settings as the Sampling and Network panels show them (the
/// default: what a new user runs is what the panels say), or a preset applied first.
void drawPipelineChoice(const PipelineBarView& bar) {
    PipelineInfo& p = bar.pipeline;
    const std::string current = pipelineChoiceLabel(p.preset);
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 9);
    if (!ImGui::BeginCombo("##pipeline-preset", current.c_str())) return;
    auto item = [&](const std::string& name, const std::vector<StageEstimate>& stages) {
        const StageEstimate e = total(stages);
        const std::string text = pipelineChoiceLabel(name) + "  (" + rangeText(e) + "; " +
                                 pipelineExpectation(bar.estimates.project, name, true) + ")";
        if (ImGui::Selectable(text.c_str(), name == p.preset)) p.preset = name;
        if (ImGui::IsItemHovered()) {
            const PipelinePreset* preset = findPreset(name);
            ImGui::SetTooltip("%s\nexpect: %s\nestimate: %s",
                              preset ? preset->summary : "the settings the Sampling and Network panels show, unchanged",
                              pipelineExpectation(bar.estimates.project, name, false).c_str(), e.basis.c_str());
        }
    };
    item("", pipelineEstimates(bar.estimates, nullptr));
    for (const PipelinePreset& preset : pipelinePresets()) item(preset.name, pipelineEstimates(bar.estimates, &preset));
    ImGui::EndCombo();
}
}  // namespace
}  // namespace pipeline_controls_detail

void drawPipelineBar(const PipelineBarView& bar) {
    PipelineInfo& p = bar.pipeline;
    const Project& project = bar.estimates.project;
    const PipelinePreset* preset = findPreset(p.preset);
    if (p.running) {
        if (ImGui::Button("Stop pipeline")) bar.actions.request(Command::CancelPipeline);
    } else {
        const std::string refusal =
            bar.hasProject ? generateRefusal(bar.estimates, preset ? presetSampling(project, *preset) : project.samplingOrDefault())
                             : std::string();
        ImGui::BeginDisabled(!bar.hasProject || !refusal.empty());
        if (ImGui::Button("Run pipeline")) bar.actions.request(Command::RunPipeline, p.preset);
        ImGui::EndDisabled();
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
            const std::string estimate =
                bar.hasProject ? "\nestimated " + rangeText(pipeline_controls_detail::total(pipelineEstimates(bar.estimates, preset))) +
                                     "\nexpect: " + pipelineExpectation(project, p.preset, false)
                                 : std::string();
            if (!refusal.empty()) ImGui::SetTooltip("cannot run: %s", refusal.c_str());
            else
                ImGui::SetTooltip("render, generate, train and evaluate with %s%s",
                                  preset ? "the chosen preset's settings" : "the project's settings", estimate.c_str());
        }
    }
    ImGui::SameLine();
    ImGui::BeginDisabled(p.running || !bar.hasProject);
    if (bar.hasProject) pipeline_controls_detail::drawPipelineChoice(bar);
    else {
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 9);
        if (ImGui::BeginCombo("##pipeline-preset", pipelineChoiceLabel(p.preset).c_str())) ImGui::EndCombo();
    }
    ImGui::EndDisabled();
    ImGui::SameLine();
    if (p.running) {
        char overlay[96];
        const int stage = std::clamp(p.stageIndex, 0, 3);
        if (p.etaSeconds >= 0)
            std::snprintf(overlay, sizeof overlay, "%d/4 %s  %.0f%%  ETA %s", stage + 1,
                          pipeline_controls_detail::kStageNames[stage], 100 * p.fraction, durationText(p.etaSeconds).c_str());
        else
            std::snprintf(overlay, sizeof overlay, "%d/4 %s  %.0f%%", stage + 1, pipeline_controls_detail::kStageNames[stage],
                          100 * p.fraction);
        ImGui::ProgressBar(float(p.fraction), ImVec2(ImGui::GetFontSize() * 16, 0), overlay);
    } else if (!p.outcome.empty()) {
        figureTextDisabled("pipeline %s", p.outcome.c_str());
    } else if (bar.hasProject) {
        // What the next run gives, in sight before the click: a smoke test says so.
        const std::string brief = pipelineExpectation(project, p.preset, true);
        figureTextDisabled("expect %s, %s", brief.c_str(),
                           rangeText(pipeline_controls_detail::total(pipelineEstimates(bar.estimates, preset))).c_str());
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", pipelineExpectation(project, p.preset, false).c_str());
    }
}

}  // namespace rrf::panels
