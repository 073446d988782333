// EvaluationController: the Light region panel's job. The loaded models are judged at a grid of light positions
// spanning the light region (core/pipeline/evaluate_stage.h's evaluateLightGrid, the stage behind
// `rrf evaluate --light-grid`) against references of the project's store at an interactive size, and
// the map becomes the panel's. Its files replace the previous light grid of the same models whole:
// runs/<train run>/light_grid (or <project dir>/light_grid for models no recorded run made).
#include "app/gui/evaluation_controller.h"
#include "app/gui/prediction_controller.h"

#include <algorithm>
#include <filesystem>

#include "core/pipeline/evaluate_stage.h"
#include "core/pipeline/run_recording.h"
#include "core/util/directory_replace.h"
#include "core/util/stopwatch.h"

namespace rrf {

namespace fs = std::filesystem;

/// A finished light-grid evaluation: the map, for the panel, and what it judged.
struct LightGridResult {
    LightGridMap map;
    std::string modelsDir, outDir;
    int width = 0, height = 0;
    double seconds = 0;
};

namespace {
/// The references' size: small enough that a grid of them renders in minutes, as the sweeps' are.
constexpr int kLightGridSize = 64;
}  // namespace

bool EvaluationController::startLightGrid() {
    if (lightGridRunning()) {
        state_.notify(panels::LogLevel::Error, "Light region", "evaluate over the light region: one is running; stop it first");
        return false;
    }
    if (!prediction_.live().loaded()) {
        state_.notify(panels::LogLevel::Error, "Light region", "evaluate over the light region: no models are loaded; train first");
        return false;
    }
    LightGridSpec grid;
    for (int a = 0; a < 3; ++a)
        grid.counts[a] = std::clamp(state_.lightRegion.counts[a], 1, panels::LightRegionInfo::kMaxCount);
    try {
        checkLightGrid(grid, state_.project.scene, "Light region", "grid");
    } catch (const std::exception& e) {
        state_.notify(panels::LogLevel::Error, "Light region", std::string("evaluate over the light region: ") + e.what());
        return false;
    }
    auto project = std::make_shared<const Project>(state_.project);
    const std::shared_ptr<const ModelSet> models = prediction_.live().models();
    const std::string modelsDir = prediction_.live().dir();
    const Run* run = findTrainRun(project->runs, projectDir(), modelsDir);
    const std::string outDir = run ? (fs::path(runDirectory(projectDir(), *run)) / "light_grid").string()
                                   : (fs::path(projectDir()) / "light_grid").string();
    const std::string storeDir = projectReferenceStore(state_.project).dir();
    const bool started = lightGridJob_.start("light grid " + grid.text(), [project, models, modelsDir, outDir, storeDir,
                                                                           grid](JobContext& ctx) -> std::optional<LightGridResult> {
        const Stopwatch clock;
        const Predictor predictor(project->scene, *models, project->prediction);
        ReferenceStore store(storeDir);
        const StageObserver base = ctx.stageObserver();
        const size_t n = grid.size();
        // One progress from 0 to 1 over the whole grid: each light's reference fills its share.
        const ReferenceSource source = [&](size_t k, const Vec3& light) {
            StageObserver o = base;
            o.progress = [&ctx, k, n](double f) { ctx.setProgress(std::min(0.99, (double(k) + f) / double(n))); };
            o.message = nullptr;  // the store's lines per light would bury the Log
            ctx.setStatus("reference " + std::to_string(k + 1) + "/" + std::to_string(n));
            return obtainReference(store, *project, light, kLightGridSize, kLightGridSize, project->reference.target,
                                   MeasuredErrorOfOnePrediction(predictor), o);
        };
        StageObserver evaluation = base;
        evaluation.progress = [&ctx](double f) { ctx.setProgress(std::min(0.99, f)); };
        evaluation.message = nullptr;  // one table per light: the panel shows the map instead
        LightGridResult r;
        try {
            replaceDirectory(outDir, [](const std::string&) { return true; }, [&](const std::string& staging) {
                r.map = evaluateLightGrid(*project, predictor, grid, source, staging, 0.f,
                                          trainingLightMarks(*project, modelsDir), evaluation)
                            .map;
            });
        } catch (const std::exception&) {
            if (ctx.cancelled()) return std::nullopt;  // stopped: the previous light grid's files stay
            throw;
        }
        r.modelsDir = modelsDir;
        r.outDir = outDir;
        r.width = r.height = kLightGridSize;
        r.seconds = clock.seconds();
        ctx.setProgress(1.0);
        return r;
    });
    if (!started) return false;
    state_.lightRegion.running = true;
    state_.log.info("light grid " + grid.text() + " started: the loaded models at " + std::to_string(grid.size()) +
                    " light positions against 64x64 references from " + storeDir);
    return true;
}

void EvaluationController::pollLightGrid() {
    panels::LightRegionInfo& lr = state_.lightRegion;
    lr.running = lightGridRunning();
    if (lr.running) lr.progress = lightGridJob_.progress();
    lightGridJob_.poll([&](LightGridResult& r) {
        const double worst = LightGridMap::scaleOf(r.map.global);
        lr.map = std::move(r.map);
        lr.modelsDir = r.modelsDir;
        lr.outDir = r.outDir;
        lr.width = r.width;
        lr.height = r.height;
        lr.object = -1;
        state_.focusTab = "Light region";
        char line[200];
        std::snprintf(line, sizeof line, "light grid %s done in %.0f s: worst global relative RMSE %.4g; files in ",
                      lr.map->grid.text().c_str(), r.seconds, worst);
        state_.notify(panels::LogLevel::Info, "Light region", line + projectRelative(projectDir(), r.outDir));
    });
}

}  // namespace rrf
