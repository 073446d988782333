// Workbench: frame loop pieces, host window, menus, status bar, modals, request dispatch and the
// wiring of the controllers.
#include "app/gui/workbench.h"

#include <cstdio>
#include <filesystem>
#include <optional>

// Key codes only: no GL header, so that glad (app/gl, window.cpp) may come after it in a unity build.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "core/project/project_file.h"
#include "core/util/memory_budget.h"
#include "panels/clip_check.h"
#include "panels/frame_overlay.h"
#include "panels/panels.h"
#include "panels/pipeline_controls.h"
#include "panels/status_text.h"

namespace rrf {

namespace fs = std::filesystem;
using panels::Command;

Workbench::Workbench(const std::string& configDir)
    : project_(ctx_, configDir), pipeline_(ctx_, pipelineStages()) {
    project_.onOpened = [this] { projectOpened(); };
    project_.onError = [this](const std::string& title, const std::string& message) { showError(title, message); };
    project_.chooseFile = [this](bool newProject) { openDialog(newProject ? DialogPurpose::New : DialogPurpose::Open); };
    // A CPU frame asked for while a training runs waits for it: both want every core.
    prediction_.holdCpuFrames = [this] { return training_.trainRunning(); };
    training_.onTrained = [this](const std::string& modelsDir, std::shared_ptr<const ModelSet> models) {
        loadModels(modelsDir, std::move(models));
        // The pipeline evaluates as its own stage; a manual training is evaluated here (issue 29 item 8).
        if (!pipelineRunning()) evaluation_.evaluateWhenReady();
    };
    // Objects without a network are hatched by the id map: a map that arrives after the prediction
    // (a project just opened) updates the hatching.
    picking_.onPublished = [this] { prediction_.objectIdsChanged(); };
    evaluation_.holdEvaluation = [this] {
        return pipelineRunning() || groundTruth_.running() || groundTruth_.restartPending() || prediction_.predictRunning() ||
               prediction_.modelsLoading();
    };
}

std::array<PipelineController::StageHooks, PipelineController::kStages> Workbench::pipelineStages() {
    PipelineController::StageHooks render, generate, train, evaluate;
    render.start = [this](StageDone done) { return groundTruth_.startStage(std::move(done)); };
    render.progress = [this] { return groundTruth_.progress(); };
    render.cancel = [this] { groundTruth_.cancel(); };
    render.finished = [this] { return groundTruth_.converged(); };
    generate.start = [this](StageDone done) { return training_.startGenerate(std::move(done)); };
    generate.progress = [this] { return training_.generateProgress(); };
    generate.cancel = [this] { training_.cancelGenerate(); };
    train.start = [this](StageDone done) { return training_.startTrain(0, std::move(done)); };
    train.progress = [this] { return training_.trainProgress(); };
    train.cancel = [this] { training_.cancelTrain(); };
    evaluate.start = [this](StageDone done) { return evaluation_.startEvaluate(std::move(done)); };
    evaluate.progress = [this] { return evaluation_.evaluateProgress(); };
    evaluate.cancel = [this] { evaluation_.cancelEvaluate(); };
    evaluate.ready = [this] { return !prediction_.modelsLoading(); };  // the trained models are uploaded first
    return {render, generate, train, evaluate};
}

Workbench::~Workbench() {
    jobs_.cancelAll();
    jobs_.waitAll();
}


std::string Workbench::takeScreenshotRequest() {
    std::string p;
    p.swap(screenshotRequest_);
    return p;
}

bool Workbench::requestQuit() {
    if (project_.quitConfirmed()) return true;
    return project_.whenSaved({ProjectController::PendingAction::Quit, {}});
}






void Workbench::showError(const std::string& title, const std::string& message) {
    state_.log.error(message);
    errorTitle_ = title;
    errorMessage_ = message;
    errorModal_ = true;
}

void Workbench::dropJobs() {
    groundTruth_.drop();
    picking_.drop();
    runs_.drop();
    training_.drop();
    evaluation_.drop();
    prediction_.drop();
    pipeline_.abandon("stopped: its project was closed");
}

void Workbench::logFinishedJobs() {
    for (const JobInfo& j : jobs_.takeFinished()) {
        if (j.failed) state_.log.error(std::string(jobKindName(j.kind)) + " '" + j.name + "' failed: " + j.error);
        else state_.log.info(std::string(jobKindName(j.kind)) + " '" + j.name + "' " +
                             (j.cancelled ? "stopped" : "finished") + " after " + std::to_string(int(j.seconds + 0.5)) + " s");
    }
}

void Workbench::refreshAvailableMemory() {
    // A few small /proc and cgroup reads, once a second: the controls' refusals follow the machine.
    const auto now = std::chrono::steady_clock::now();
    if (now - memoryCheckedAt_ < std::chrono::seconds(1) && state_.availableMemory != UINT64_MAX) return;
    memoryCheckedAt_ = now;
    state_.availableMemory = availableMemoryBytes();
}

void Workbench::frame() {
    // Ended jobs are logged first, so their results' lines follow "... finished after N s".
    logFinishedJobs();
    groundTruth_.poll();
    picking_.poll();
    runs_.poll();
    training_.poll();
    evaluation_.pollEvaluation();
    // After pollPredict: a CPU frame that has just ended is delivered before the evaluation that
    // waited for it looks for it.
    prediction_.poll();
    evaluation_.pollAfterPrediction();
    pipeline_.poll();
    prediction_.updateFlipMap();
    prediction_.updateSpreadMap();
    refreshAvailableMemory();
    prediction_.finishDraft();
    drawHost();
    drawModals();
    drawFrameOverlay();
    if (dialog_.draw()) dialogConfirmed(dialog_.result());
    handleRequests();
    // One undo step per settled edit: while a button is held (a slider, a light drag) the edit is
    // still being made.
    if (state_.hasProject && !ImGui::IsAnyMouseDown()) history_.observe(state_.project);
    project_.autosave();

    viewModel_.update(state_);
    for (int i = 0; i < 3; ++i) {
        textures_[i].upload(viewModel_.image(i));
        state_.viewTextures[i] = textures_[i].id();
    }
}

void Workbench::drawHost() {
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(vp->WorkPos);
    ImGui::SetNextWindowSize(vp->WorkSize);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                   ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_NoSavedSettings |
                                   ImGuiWindowFlags_MenuBar;
    ImGui::PushStyleVar(ImGuiStyleVar_WindowRounding, 0.f);
    ImGui::Begin("##host", nullptr, flags);
    ImGui::PopStyleVar();
    drawMenuBar();

    const float statusH = ImGui::GetFrameHeightWithSpacing();
    ImGui::BeginChild("##workspace", ImVec2(0, -statusH), false, ImGuiWindowFlags_NoScrollbar);
    // Panes, tabs and splitters follow the project's layout section (panels/layout.h); moving
    // tabs changes that section like the splitters do, saved with the project.
    panels::drawWorkspace(
        state_.project.layout, [&](const std::string& name) { panels::drawPanel(state_, name); }, state_.focusTab);
    ImGui::EndChild();
    drawStatusBar();
    ImGui::End();
}

void Workbench::drawMenuBar() {
    if (!ImGui::BeginMenuBar()) return;
    if (ImGui::BeginMenu("File")) {
        if (ImGui::MenuItem("New from scene...")) state_.request(Command::NewProject);
        if (ImGui::MenuItem("Open...", shortcutKeys(ShortcutAction::Open))) state_.request(Command::OpenProject);
        if (ImGui::MenuItem("Save", shortcutKeys(ShortcutAction::Save), false, state_.hasProject))
            state_.request(Command::SaveProject);
        if (ImGui::MenuItem("Save As...", nullptr, false, state_.hasProject)) state_.request(Command::SaveProjectAs);
        if (ImGui::BeginMenu("Recent", !state_.recent.empty())) {
            for (const std::string& p : state_.recent)
                if (ImGui::MenuItem(p.c_str())) state_.request(Command::OpenProject, p);
            ImGui::EndMenu();
        }
        ImGui::Separator();
        if (ImGui::MenuItem("Export images...", nullptr, false, groundTruth_.session() != nullptr)) openDialog(DialogPurpose::ExportImages);
        if (ImGui::MenuItem("Export screenshot...")) openDialog(DialogPurpose::ExportScreenshot);
        if (ImGui::MenuItem("Export error table (CSV)...", nullptr, false, state_.evaluation.valid))
            openDialog(DialogPurpose::ExportObjectsCsv);
        ImGui::Separator();
        if (ImGui::MenuItem("Quit", shortcutKeys(ShortcutAction::Quit))) state_.request(Command::Quit);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Edit")) {
        if (ImGui::MenuItem("Undo", shortcutKeys(ShortcutAction::Undo), false, history_.undoSteps() > 0))
            performShortcut(ShortcutAction::Undo);
        if (ImGui::MenuItem("Redo", shortcutKeys(ShortcutAction::Redo), false, history_.redoSteps() > 0))
            performShortcut(ShortcutAction::Redo);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("View")) {
        if (ImGui::MenuItem("Reset layout")) state_.request(Command::ResetLayout);
        if (ImGui::MenuItem("Reset zoom and pan")) {
            state_.view.zoom = 1.f;
            state_.view.panX = state_.view.panY = 0.f;
        }
        ImGui::MenuItem("Frame time overlay", shortcutKeys(ShortcutAction::FrameOverlay), &frameOverlay_);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Help")) {
        ImGui::MenuItem("Shortcuts and help", shortcutKeys(ShortcutAction::Help), &helpOpen_);
        if (ImGui::MenuItem("About")) aboutModal_ = true;
        ImGui::EndMenu();
    }
    // The one-click pipeline and its one progress display, always in sight.
    ImGui::Separator();
    panels::drawPipelineBar(panels::pipelineBarView(state_));
    // The keyboard shortcuts, from the one table the menus and the Help window show (shortcuts.h).
    const ImGuiIO& io = ImGui::GetIO();
    if (!io.WantTextInput)
        for (const Shortcut& s : shortcuts())
            if (s.ctrl == io.KeyCtrl && s.shift == io.KeyShift && ImGui::IsKeyPressed(s.key, false))
                performShortcut(s.action);
    ImGui::EndMenuBar();
}

void Workbench::performShortcut(ShortcutAction action) {
    switch (action) {
        case ShortcutAction::Open: state_.request(Command::OpenProject); break;
        case ShortcutAction::Save:
            if (state_.hasProject) state_.request(Command::SaveProject);
            break;
        case ShortcutAction::Quit: state_.request(Command::Quit); break;
        case ShortcutAction::Undo: applySettings(history_.undo(), "undo"); break;
        case ShortcutAction::Redo: applySettings(history_.redo(), "redo"); break;
        case ShortcutAction::FrameOverlay: frameOverlay_ = !frameOverlay_; break;
        case ShortcutAction::Help: helpOpen_ = !helpOpen_; break;
    }
}

void Workbench::applySettings(const std::optional<ProjectSettings>& settings, const char* what) {
    if (!settings || !state_.hasProject) {
        state_.notify(panels::LogLevel::Info, "", std::string(what) + ": nothing to " + what);
        return;
    }
    const bool lightMoved = settings->applyTo(state_.project);
    state_.markDirty();
    state_.log.info(std::string(what) + ": settings restored (" + std::to_string(history_.undoSteps()) + " undo, " +
                    std::to_string(history_.redoSteps()) + " redo steps left)");
    // The light restarts the ground truth and moves the prediction; other settings change what
    // the next render, generation or training does, and the prediction's direct light.
    if (lightMoved) sceneChanged(true);
    else prediction_.refresh();
}

void Workbench::drawStatusBar() {
    if (state_.notice) {
        panels::drawNotice(state_.notice, false);
        ImGui::SameLine();
    }
    // New models: the GL worker compiles their shaders (seconds when the driver's shader cache is
    // cold, a first start) while the view keeps the last prediction; say why it has not changed.
    if (prediction_.uploadPending() || prediction_.glslBuilding()) {
        ImGui::TextColored(ImVec4(1.f, 0.8f, 0.3f, 1.f), "compiling GLSL shaders (seconds on a first start)");
        ImGui::SameLine();
        prediction_.uploadAnnounced();
    }
    const std::vector<JobInfo> running = jobs_.jobs();
    // The one-click pipeline is one entry of its own, before its stage's job: between two stages
    // (a frame or two with no job) the bar keeps showing it instead of flickering to idle.
    const panels::PipelineInfo& pipeline = state_.pipeline;
    if (pipeline.running) {
        char overlay[64];
        if (pipeline.etaSeconds >= 0)
            std::snprintf(overlay, sizeof overlay, "%.0f%%, ETA %.0f s", 100 * pipeline.fraction, pipeline.etaSeconds);
        else std::snprintf(overlay, sizeof overlay, "%.0f%%", 100 * pipeline.fraction);
        ImGui::Text("pipeline: %s (stage %d of 4)", pipeline.stage.c_str(), pipeline.stageIndex + 1);
        ImGui::SameLine();
        panels::fittedProgressBar(float(pipeline.fraction), ImGui::GetFontSize() * 10, overlay);  // figures never cut
        ImGui::SameLine();
    }
    if (running.empty()) {
        // Work that follows at once (the next pipeline stage, the evaluation after a training, a
        // render restarted by an edit) is said, not shown as idle.
        const char* next = pipeline.running    ? "starting the next stage"
                           : evaluation_.evaluationPending() ? "the trained models are evaluated next"
                           : groundTruth_.restartPending() ? "the render restarts"
                                                 : nullptr;
        if (next) {
            ImGui::TextDisabled("%s", next);
            return;
        }
        if (pipelineRunning()) ++statusIdleWhilePipeline_;
        ImGui::TextDisabled("%s%s", state_.hasProject ? state_.project.path.c_str() : "no project",
                            state_.dirty ? "  (unsaved changes)" : "");
        return;
    }
    for (const JobInfo& j : running) {
        ImGui::PushID(j.id);
        char overlay[64];
        if (j.etaSeconds >= 0) std::snprintf(overlay, sizeof overlay, "%.0f%%, ETA %.0f s", 100 * j.progress, j.etaSeconds);
        else std::snprintf(overlay, sizeof overlay, "%.0f%%", 100 * j.progress);
        ImGui::TextUnformatted(j.name.c_str());
        ImGui::SameLine();
        panels::fittedProgressBar(float(j.progress), ImGui::GetFontSize() * 10, overlay);
        ImGui::SameLine();
        ImGui::TextUnformatted(j.status.c_str());
        ImGui::SameLine();
        if (ImGui::SmallButton("Cancel")) jobs_.cancel(j.id);
        ImGui::SameLine();
        ImGui::PopID();
    }
    ImGui::NewLine();
}

bool Workbench::busy() const {
    // A draft on screen is replaced by the full frame shortly: keep the frames coming until then.
    // So is a full frame rendered in bands (app/gui/prediction_bands.h): a band per frame.
    // drained(), not idle(): a job that ended after this frame's polls still has its result to hand
    // over, and the window must not wait for an event to take it.
    return !jobs_.drained() || pipelineRunning() || prediction_.modelsLoading() || prediction_.draftShown() || prediction_.bandsPending() ||
           evaluation_.sweepRunning() ||
           ImGui::IsAnyMouseDown();
}

void Workbench::drawFrameOverlay() {
    if (!frameOverlay_) return;
    const FrameTimeSummary s = summarizeFrameTimes(frameStats_.recent());
    char line[3][96];
    std::snprintf(line[0], sizeof line[0], "frame %.1f ms", 1e3 * frameStats_.last());
    std::snprintf(line[1], sizeof line[1], "median %.1f ms, p95 %.1f ms", 1e3 * s.median, 1e3 * s.p95);
    std::snprintf(line[2], sizeof line[2], "last %zu frames, UI thread work", s.frames);
    // Over the Views' images, clear of their toolbar; at the window's top-right when no view is shown.
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    panels::drawFrameOverlay({line[0], line[1], line[2]}, state_.view,
                             ImVec2(vp->WorkPos.x + vp->WorkSize.x - 10, vp->WorkPos.y + 30));
}

void Workbench::drawModals() {
    if (helpOpen_) panels::drawHelpWindow(shortcutInfos(), &helpOpen_);
    if (aboutModal_) {
        ImGui::OpenPopup("About RRF Workbench");
        aboutModal_ = false;
    }
    if (ImGui::BeginPopupModal("About RRF Workbench", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::TextUnformatted("RRF Workbench: learning global illumination with radiance regression functions");
        ImGui::TextUnformatted("after Ren et al., \"Global Illumination with Radiance Regression Functions\", SIGGRAPH 2013.");
        ImGui::Text("Dear ImGui %s", ImGui::GetVersion());
        if (ImGui::Button("Close")) ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
    }
    if (project_.takePromptRequest()) ImGui::OpenPopup("Unsaved changes");
    if (ImGui::BeginPopupModal("Unsaved changes", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        if (!unsavedPromptOpen()) {
            ImGui::CloseCurrentPopup();  // answered from elsewhere (a script)
        } else {
            using PendingAction = ProjectController::PendingAction;
            const PendingAction& pending = project_.pending();
            const char* what = pending.kind == PendingAction::Quit  ? "quitting"
                               : pending.kind == PendingAction::New ? "starting a new project"
                                                                     : "opening another project";
            ImGui::Text("'%s' has unsaved changes. Save them before %s?", state_.projectName().c_str(), what);
            if (!pending.path.empty()) ImGui::TextDisabled("%s", pending.path.c_str());
            std::optional<UnsavedChoice> choice;
            if (ImGui::Button("Save")) choice = UnsavedChoice::Save;
            ImGui::SameLine();
            if (ImGui::Button("Discard")) choice = UnsavedChoice::Discard;
            ImGui::SameLine();
            if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(GLFW_KEY_ESCAPE)) choice = UnsavedChoice::Cancel;
            if (choice) {
                ImGui::CloseCurrentPopup();
                answerUnsavedPrompt(*choice);
            }
        }
        ImGui::EndPopup();
    }
    if (errorModal_) {
        ImGui::OpenPopup("Error##modal");
        errorModal_ = false;
    }
    if (ImGui::BeginPopupModal("Error##modal", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::TextUnformatted(errorTitle_.c_str());
        ImGui::Separator();
        ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40);
        ImGui::TextUnformatted(errorMessage_.c_str());
        ImGui::PopTextWrapPos();
        if (ImGui::Button("Copy")) ImGui::SetClipboardText(errorMessage_.c_str());
        ImGui::SameLine();
        if (ImGui::Button("OK")) ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
    }
}

void Workbench::openDialog(DialogPurpose purpose) {
    dialogPurpose_ = purpose;
    const std::string here = state_.hasProject && !state_.project.path.empty() ? state_.project.path : projectDir();
    using M = panels::FileDialog::Mode;
    switch (purpose) {
        case DialogPurpose::Open: dialog_.open(M::Open, "Open project", here, ".json"); break;
        case DialogPurpose::New: dialog_.open(M::Open, "New project from a scene file", here, ".json"); break;
        case DialogPurpose::SaveAs: dialog_.open(M::Save, "Save project as", here, ".json"); break;
        case DialogPurpose::ExportImages:
            dialog_.open(M::Directory, "Export images to directory", (fs::path(projectDir()) / "export").string(), "");
            break;
        case DialogPurpose::ExportScreenshot:
            dialog_.open(M::Save, "Export screenshot", (fs::path(projectDir()) / "screenshot.png").string(), ".png");
            break;
        case DialogPurpose::ExportObjectsCsv:
            dialog_.open(M::Save, "Export the per-object error table", (fs::path(projectDir()) / "objects.csv").string(), ".csv");
            break;
        case DialogPurpose::None: break;
    }
}

void Workbench::dialogConfirmed(const std::string& path) {
    switch (dialogPurpose_) {
        case DialogPurpose::Open: openProject(path); break;
        case DialogPurpose::New: project_.newFromScene(path); break;
        case DialogPurpose::SaveAs: saveProject(path); break;
        case DialogPurpose::ExportImages: exportImages(path); break;
        case DialogPurpose::ExportScreenshot: screenshotRequest_ = path; break;
        case DialogPurpose::ExportObjectsCsv: exportObjectsCsv(path); break;
        case DialogPurpose::None: break;
    }
    dialogPurpose_ = DialogPurpose::None;
}

void Workbench::handleRequests() {
    std::vector<panels::Request> requests;
    requests.swap(state_.requests);
    bool sceneEdited = false;
    for (const panels::Request& r : requests) {
        // Backstop: whatever a handler throws (a malformed section in a hand-edited project, a file
        // system error) becomes a message, never std::terminate of the whole workbench.
        try {
            handleRequest(r, sceneEdited);
        } catch (const std::exception& e) {
            state_.log.error(e.what());
            showError("Error", e.what());
        }
    }
    if (sceneEdited) sceneChanged(true, false);  // the Scene panel edits materials and the light only
}

void Workbench::handleRequest(const panels::Request& r, bool& sceneEdited) {
    {
        switch (r.command) {
            case Command::NewProject: project_.whenSaved({ProjectController::PendingAction::New, {}}); break;
            case Command::OpenProject: requestOpen(r.path); break;
            case Command::SaveProject: saveProject(); break;
            case Command::SaveProjectAs:
                if (r.path.empty()) openDialog(DialogPurpose::SaveAs);
                else saveProject(r.path);
                break;
            case Command::StartRender: startRender(); break;
            case Command::CancelRender: cancelRender(); break;
            case Command::Generate: startGenerate(); break;
            case Command::CancelGenerate: training_.cancelGenerate(); break;
            case Command::Train: startTrain(); break;
            case Command::CancelTrain: training_.cancelTrain(); break;
            case Command::Evaluate: evaluation_.startEvaluate(); break;
            case Command::ExportObjectsCsv:
                if (r.path.empty()) openDialog(DialogPurpose::ExportObjectsCsv);
                else exportObjectsCsv(r.path);
                break;
            case Command::RunSweep: startSweep(r.path); break;
            case Command::CancelSweep: evaluation_.cancelSweep(); break;
            case Command::EvaluateLightRegion: startLightGrid(); break;
            case Command::CancelLightRegion: evaluation_.cancelLightGrid(); break;
            case Command::RunPipeline: startPipeline(r.path); break;
            case Command::CancelPipeline: cancelPipeline(); break;
            case Command::SceneChanged: sceneEdited = true; break;  // many edits in a frame: one restart
            case Command::PredictionChanged: prediction_.refresh(); break;
            case Command::SaveRun: saveRun(); break;
            case Command::ReopenRun: reopenRun(r.index); break;
            case Command::CompareRun: compareRun(r.index); break;
            case Command::CompareRunPair: compareRunPair(); break;
            case Command::DeleteRun:
                if (r.index >= 0 && r.index < int(state_.project.runs.size())) {
                    state_.log.info("removed run '" + state_.project.runs[size_t(r.index)].name +
                                    "' from the project (its files stay on disk)");
                    state_.project.runs.erase(state_.project.runs.begin() + r.index);
                    state_.runPair.a = state_.runPair.b = -1;  // indices moved: choose again
                    if (state_.training.partialRun == r.index) state_.training.partialRun = -1;
                    else if (state_.training.partialRun > r.index) --state_.training.partialRun;
                    if (state_.compareRun == r.index) {
                        state_.compareRun = -1;
                        state_.compare = panels::ImageSet{};
                        state_.compare.touch();
                    } else if (state_.compareRun > r.index) {
                        --state_.compareRun;
                    }
                    state_.markDirty();
                }
                break;
            case Command::ExportImages:
                if (r.path.empty()) openDialog(DialogPurpose::ExportImages);
                else exportImages(r.path);
                break;
            case Command::ExportScreenshot:
                if (r.path.empty()) openDialog(DialogPurpose::ExportScreenshot);
                else screenshotRequest_ = r.path;
                break;
            case Command::ResetLayout: state_.project.layout.reset(); break;
            case Command::Quit: requestQuit(); break;
        }
    }
}

}  // namespace rrf
