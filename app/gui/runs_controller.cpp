// The runs controller: saving, comparing and re-opening runs, and exporting the images on screen.
#include "app/gui/runs_controller.h"

#include <filesystem>
#include <utility>

#include "app/gui/ground_truth_controller.h"
#include "app/gui/prediction_controller.h"
#include "core/project/project.h"
#include "core/eval/error_metrics.h"
#include "core/pipeline/run_recording.h"
#include "core/project/scene_edits.h"
#include "core/util/error.h"
#include "core/util/image_io.h"

namespace rrf {

namespace fs = std::filesystem;

RunsController::RunsController(ControllerContext& ctx, GroundTruthController& groundTruth, PredictionController& prediction,
                               std::function<void()> sceneChanged)
    : ctx_(ctx),
      state_(ctx.state),
      groundTruth_(groundTruth),
      prediction_(prediction),
      sceneChanged_(std::move(sceneChanged)),
      runImages_(ctx.jobs, ctx.state.log) {}

RunsController::~RunsController() = default;

std::shared_ptr<RenderSession> RunsController::finishedRender(const std::string& action, const char* panel) {
    const std::shared_ptr<RenderSession>& render = groundTruth_.session();
    const char* why = !render || !render->latest()      ? "no ground truth rendered yet"
                      : groundTruth_.running()          ? "the render is still running; wait for it or stop it first"
                      : groundTruth_.restartPending()   ? "the render of the edited scene has not started yet; wait for it"
                                                        : nullptr;
    if (!why) return render;
    state_.notify(panels::LogLevel::Error, panel, action + ": " + why);
    return nullptr;
}

bool RunsController::saveRun() {
    const std::shared_ptr<RenderSession> render = finishedRender("save run", "Views");
    if (!render) return false;
    if (!ctx_.savedProject()) {
        state_.notify(panels::LogLevel::Error, "Views", "save run: save the project first (runs are stored next to it)");
        return false;
    }
    Run run = beginRun(state_.project.runs, "render");
    const std::string relDir = "runs/" + run.id;
    const auto snap = render->latest();
    try {
        const RenderOutputs out = render->write(runDirectory(ctx_.projectDir(), run), ImageFormat::EXR, 0.f);
        setRenderRun(run, ctx_.projectDir(), state_.project.render, render->options().spp, render->scene(),
                     state_.project.overrides, *snap, render->stats(), out);
    } catch (const std::exception& e) {
        state_.log.error(std::string("save run: ") + e.what());
        return false;
    }
    state_.project.runs.push_back(run);
    state_.markDirty();
    state_.log.info("saved run '" + run.name + "' (" + std::to_string(snap->sppCompleted) + " spp) to " + relDir);
    return true;
}

namespace {
/// Reads a render run's global/direct/indirect EXR images (any thread).
bool loadRunImages(const Run& run, const std::string& dir, panels::ImageSet& out, std::string& error) {
    Image* slots[3] = {&out.global, &out.direct, &out.indirect};
    const char* names[3] = {"global.exr", "direct.exr", "indirect.exr"};
    for (int i = 0; i < 3; ++i) {
        std::string file;
        for (const std::string& a : run.artifacts)
            if (fs::path(a).filename() == names[i]) file = (fs::path(dir) / a).string();
        if (file.empty()) {
            error = "run '" + run.name + "' has no " + names[i];
            return false;
        }
        try {
            *slots[i] = readImage(file);
        } catch (const std::exception& e) {
            error = e.what();
            return false;
        }
    }
    return true;
}

int runSpp(const Run& run) { return run.metrics.spp.value_or(0); }
}  // namespace

/// A render run's images read on a worker (readRunImages).
struct RunsController::RunImages {
    Run run;  ///< as it was when the read started (the project's list may change meanwhile)
    int index = -1;
    panels::ImageSet images;
    std::string error;  ///< why they could not be read (names the file or the missing image)
};

bool RunsController::readRunImages(int index, const char* action, std::function<void(RunImages&)> then) {
    // Three EXR images of the render's size: tens of milliseconds to seconds, never the UI
    // thread's (issue 29). The views keep what they show until the images have arrived.
    auto read = std::make_shared<RunImages>();
    read->run = state_.project.runs[size_t(index)];
    read->index = index;
    const std::string dir = ctx_.projectDir();
    return runImages_.start(
        "run images",
        [read, dir](JobContext&) -> std::optional<RunImages> {
            RunImages r = std::move(*read);
            loadRunImages(r.run, dir, r.images, r.error);
            return r;
        },
        [this, action = std::string(action), then = std::move(then)](RunImages& r) {
            if (!r.error.empty()) {
                state_.notify(panels::LogLevel::Error, "Project", action + ": " + r.error);
                return;
            }
            then(r);
        });
}

void RunsController::poll() { runImages_.poll(); }

bool RunsController::compareRun(int index) {
    if (index < 0 || index >= int(state_.project.runs.size())) return false;
    const Run& run = state_.project.runs[size_t(index)];
    if (run.kind == "train") return loadTrainRun(run);
    return readRunImages(index, "compare run", [this](RunImages& r) {
        panels::ImageSet& set = r.images;
        set.label = "Run '" + r.run.name + "' (" + std::to_string(runSpp(r.run)) + " spp)";
        set.touch();
        state_.compare = std::move(set);
        state_.compareRun = r.index;
        state_.view.compareSource = panels::CompareSource::Run;
        state_.log.info("comparing the ground truth with run '" + r.run.name + "'");
    });
}

bool RunsController::reopenRun(int index) {
    if (index < 0 || index >= int(state_.project.runs.size())) return false;
    const Run& run = state_.project.runs[size_t(index)];
    if (run.kind == "train") return loadTrainRun(run);
    // Nothing changes until the images are there: a run whose images cannot be read leaves the
    // settings and the ground truth as they were.
    return readRunImages(index, "re-open run", [this](RunImages& r) { showReopenedRun(r); });
}

void RunsController::showReopenedRun(RunImages& r) {
    const Run& run = r.run;
    const int index = r.index;
    panels::ImageSet& set = r.images;
    groundTruth_.cancel();
    // The run's settings snapshot was read (and checked) with the project; what does not fit the
    // scene is reported and the current setting kept.
    const RunSettings& settings = run.settings;
    if (settings.render) state_.project.render = *settings.render;
    if (settings.sceneOverrides) {
        std::vector<std::string> problems;
        state_.project.overrides = *settings.sceneOverrides;
        applySceneOverrides(state_.project.overrides, state_.project.scene, problems,
                            "/runs/" + std::to_string(index) + "/settings/scene_overrides");
        for (const std::string& p : problems) state_.log.warning("re-open run: " + p);
    }
    if (settings.lightPosition && !state_.project.scene.lights.empty()) {
        try {
            moveLight(state_.project, *settings.lightPosition);
        } catch (const InputError& e) {
            state_.log.warning(std::string("re-open run: light position kept as it is: ") + e.what());
        }
    }
    sceneChanged_();
    set.label = "Run '" + run.name + "'";
    set.stamp = panels::ImageStamp{state_.project.scene.lightPosition(), state_.project.scene.contentHash(), set.global.width,
                                   set.global.height};
    set.touch();
    state_.groundTruth = std::move(set);
    state_.render = panels::RenderProgress{};
    state_.render.spp = state_.render.targetSpp = runSpp(run);
    state_.markDirty();
    state_.log.info("re-opened run '" + run.name + "': settings restored, its images shown as the ground truth");
}

bool RunsController::loadTrainRun(const Run& run) {
    // A training run "opens" as its settings and its models: the Network panel shows what trained
    // them, and the prediction view shows what they predict. Its settings snapshot was read (and
    // checked) with the project.
    if (run.settings.network && run.settings.trainer) {
        state_.project.network = *run.settings.network;
        state_.project.trainer = *run.settings.trainer;
        state_.markDirty();
    }
    if (run.artifacts.empty()) {
        state_.notify(panels::LogLevel::Error, "Project", "run '" + run.name + "' lists no models");
        return false;
    }
    return prediction_.loadModels((fs::path(ctx_.projectDir()) / fs::path(run.artifacts.front()).parent_path()).string());
}

bool RunsController::exportImages(const std::string& dir, const Image& error) {
    const std::shared_ptr<RenderSession> render = finishedRender("export images", "");
    if (!render) return false;
    try {
        // One set: a second write would replace the first (core/render/render_outputs.h).
        render->write(dir, ImageFormat::EXR, 0.f, {{ImageFormat::PNG, state_.view.exposure}});
        if (!error.empty()) {
            writeImage((fs::path(dir) / "error.exr").string(), error, ImageFormat::EXR);
            writeImage((fs::path(dir) / "error.png").string(), errorMapColour(error, state_.view.metric, state_.view.errorMax), ImageFormat::PNG);
        }
        if (!prediction_.exportImages(dir)) return false;
    } catch (const std::exception& e) {
        state_.notify(panels::LogLevel::Error, "", std::string("export images: ") + e.what());
        return false;
    }
    state_.notify(panels::LogLevel::Info, "", "exported images (EXR and PNG) to " + dir);
    return true;
}

}  // namespace rrf
