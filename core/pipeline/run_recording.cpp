#include "core/pipeline/run_recording.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <system_error>

#include "core/nn/mlp_kernel.h"
#include "core/util/error.h"
#include "core/util/text_format.h"

namespace rrf {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {
json vec3Json(const Vec3& v) { return json::array({v.x, v.y, v.z}); }

/// Both paths absolute and normalised, so "runs/x/models" and "/p/runs/x/models/" compare equal.
fs::path normal(const fs::path& p) {
    std::error_code ec;
    fs::path n = fs::weakly_canonical(fs::absolute(p), ec);
    if (ec) n = fs::absolute(p).lexically_normal();
    if (!n.has_filename() && n.has_parent_path()) n = n.parent_path();  // drop a trailing '/'
    return n;
}
}  // namespace

std::string projectDirectory(const Project& project) {
    if (project.path.empty()) return fs::current_path().string();
    return fs::absolute(fs::path(project.path)).parent_path().string();
}

ReferenceStore projectReferenceStore(const Project& project) {
    return ReferenceStore((std::filesystem::path(projectDirectory(project)) / "references").string());
}

bool isBareScene(const Project& project) {
    // A bare scene is wrapped in a project that references the scene file itself.
    return !project.sceneRef.empty() && !project.path.empty() &&
           normal(fs::path(project.path).parent_path() / project.sceneRef) == normal(project.path);
}

std::string projectRelative(const std::string& projectDir, const std::string& file) {
    return normal(file).lexically_relative(normal(projectDir)).generic_string();
}

Run beginRun(const std::vector<Run>& runs, const std::string& kind) {
    Run run;
    run.kind = kind;
    run.id = newRunId(runs, kind);
    run.name = run.id;
    run.created = localTimestamp();
    return run;
}

std::string runDirectory(const std::string& projectDir, const Run& run) {
    return (fs::path(projectDir) / "runs" / run.id).string();
}

void setRenderRun(Run& run, const std::string& projectDir, RenderSettings settings, int targetSpp, const Scene& scene,
                  const SceneOverrides& overrides, const RenderSnapshot& snapshot, const RenderStats& stats,
                  const RenderOutputs& outputs) {
    settings.spp = targetSpp;
    run.settings = json{{"render", renderSettingsToJson(settings)},
                        {"light_position", vec3Json(scene.lightPosition())},
                        {"scene_hash", hexString(scene.contentHash())}};
    if (!overrides.empty()) run.settings["scene_overrides"] = overrides.toJson();
    run.metrics = json{{"spp", snapshot.sppCompleted},
                       {"relative_error", snapshot.relativeError},
                       {"non_finite_samples", snapshot.nonFinite},
                       {"samples_per_second", stats.samplesPerSecond()}};
    run.timings = json{{"render", snapshot.seconds}};
    run.artifacts.clear();
    for (const std::string& p : outputs.images) run.artifacts.push_back(projectRelative(projectDir, p));
    run.artifacts.push_back(projectRelative(projectDir, outputs.metadata));
}

std::vector<LossCurve> lossCurves(const std::vector<NetworkCurve>& curves) {
    std::vector<LossCurve> out;
    for (const NetworkCurve& n : curves) {
        LossCurve c;
        c.objectId = n.objectId;
        c.object = n.object.empty() ? "?" : n.object;
        c.target = n.target;
        for (const EpochRecord& r : n.epochs) c.points.push_back({r.epoch, r.trainLoss, r.validationLoss, r.seconds});
        out.push_back(std::move(c));
    }
    return out;
}

void setTrainRun(Run& run, const std::string& projectDir, TrainRecord r) {
    run.settings = json{{"network", r.settings.networkJson()}, {"trainer", r.settings.trainerJson()},
                        {"dataset", projectRelative(projectDir, r.dataset)}, {"scene_hash", hexString(r.sceneHash)}};
    if (r.sampling) run.settings["sampling"] = r.sampling->toJson();
    // The process trains with one kernel (nn/mlp_kernel.h); a model reproduces bit for bit on it only.
    run.settings["kernel"] = mlpKernelName(mlpKernel());
    int epochs = 0;
    for (const LossCurve& c : r.curves)
        for (const LossPoint& p : c.points) epochs = std::max(epochs, p.epoch);
    run.curves = std::move(r.curves);
    run.loss = aggregateLoss(run.curves);
    run.metrics = json{{"networks", r.networks}, {"skipped", r.skipped}, {"epochs", epochs}};
    if (r.plannedNetworks > 0) run.metrics["planned_networks"] = r.plannedNetworks;
    if (r.stopped) run.metrics["stopped"] = true;
    if (r.leaves > 0) run.metrics["leaves"] = r.leaves;
    if (r.records > 0) run.metrics["records"] = r.records;
    run.timings = json{{"train", r.seconds}};
    if (r.generateSeconds) run.timings["generate"] = *r.generateSeconds;
    run.artifacts = {projectRelative(projectDir, (fs::path(r.modelsDir) / "models.json").string())};
}

bool isStoppedTrainRun(const Run& run) {
    const auto it = run.metrics.find("stopped");
    return run.kind == "train" && it != run.metrics.end() && it->is_boolean() && it->get<bool>();
}

std::string stoppedTrainingText(int epoch, int networks, int planned) {
    std::string t = "stopped at epoch " + std::to_string(epoch) + ", " + std::to_string(networks);
    if (planned > 0) t += " of " + std::to_string(planned);
    return t + (planned == 1 || (planned <= 0 && networks == 1) ? " network" : " networks");
}

std::string trainRunStatusText(const Run& run) {
    if (run.kind != "train") return {};
    const int networks = int(run.metric("networks").value_or(0));
    if (isStoppedTrainRun(run))
        return stoppedTrainingText(int(run.metric("epochs").value_or(0)), networks,
                                   int(run.metric("planned_networks").value_or(0)));
    return std::to_string(networks) + (networks == 1 ? " network" : " networks");
}

std::string trainRunModelsDir(const Run& run, const std::string& projectDir) {
    if (run.artifacts.empty()) return {};
    return (fs::path(projectDir) / fs::path(run.artifacts.front()).parent_path()).string();
}

namespace {
bool trainedInto(const Run& r, const std::string& projectDir, const fs::path& modelsDir) {
    return r.kind == "train" && !r.artifacts.empty() && normal(trainRunModelsDir(r, projectDir)) == modelsDir;
}
}  // namespace

const Run* findTrainRun(const std::vector<Run>& runs, const std::string& projectDir, const std::string& modelsDir) {
    const fs::path wanted = normal(modelsDir);
    for (const Run& r : runs)
        if (trainedInto(r, projectDir, wanted)) return &r;
    return nullptr;
}

int recordEvaluation(std::vector<Run>& runs, const std::string& projectDir, const std::string& modelsDir,
                     const EvaluationRecord& e) {
    int changed = 0;
    const fs::path wanted = normal(modelsDir);
    for (Run& r : runs) {
        if (!trainedInto(r, projectDir, wanted)) continue;
        r.metrics["relative_rmse"] = e.global.relativeRmse;
        r.metrics["rmse"] = e.global.rmse;
        r.metrics["mae"] = e.global.mae;
        r.metrics["evaluated_spp"] = e.referenceSpp;
        r.metrics.erase("evaluated_width");
        r.metrics.erase("evaluated_height");
        if (e.width > 0 && e.height > 0) {
            r.metrics["evaluated_width"] = e.width;
            r.metrics["evaluated_height"] = e.height;
        }
        // The noise floor makes the error readable (an error at the floor is as good as the
        // reference allows); without the reference's variance it is unknown and left out.
        r.metrics.erase("relative_rmse_noise_floor");
        r.metrics.erase("relative_rmse_corrected");
        if (std::isfinite(e.global.relativeRmseNoiseFloor)) {
            r.metrics["relative_rmse_noise_floor"] = e.global.relativeRmseNoiseFloor;
            if (std::isfinite(e.global.relativeRmseCorrected))
                r.metrics["relative_rmse_corrected"] = e.global.relativeRmseCorrected;
        }
        r.metrics.erase("evaluated_light");
        r.metrics.erase("evaluated_lights");
        if (e.lights.size() == 1)
            r.metrics["evaluated_light"] = vec3Json(e.lights.front());
        else
            r.metrics["evaluated_lights"] = e.lights.size();
        r.timings["evaluate"] = e.seconds;
        // models.json stays first: the workbench loads the models from the first artifact's directory.
        for (const std::string& a : e.artifacts) {
            const std::string rel = projectRelative(projectDir, a);
            if (std::find(r.artifacts.begin(), r.artifacts.end(), rel) == r.artifacts.end()) r.artifacts.push_back(rel);
        }
        ++changed;
    }
    return changed;
}

std::string frameSizeKey(const std::string& secondsKey, const char* side) {
    const std::string suffix = "_seconds";
    const bool ends = secondsKey.size() > suffix.size() &&
                      secondsKey.compare(secondsKey.size() - suffix.size(), suffix.size(), suffix) == 0;
    return (ends ? secondsKey.substr(0, secondsKey.size() - suffix.size()) : secondsKey) + "_" + side;
}

int recordFrameSeconds(std::vector<Run>& runs, const std::string& projectDir, const std::string& modelsDir,
                       const std::string& key, double seconds, int width, int height) {
    int changed = 0;
    const fs::path wanted = normal(modelsDir);
    for (Run& r : runs)
        if (trainedInto(r, projectDir, wanted)) {
            r.metrics[key] = seconds;
            r.metrics[frameSizeKey(key, "width")] = width;
            r.metrics[frameSizeKey(key, "height")] = height;
            ++changed;
        }
    return changed;
}

void editRuns(const std::string& projectFile, const std::function<void(std::vector<Run>&)>& edit) {
    Project project = loadProjectOrScene(projectFile);
    if (isBareScene(project))
        throw InputError(projectFile, "", "is a scene file, not a project: there is no project to record the run in");
    edit(project.runs);
    saveProject(project, projectFile);
}

void recordRun(const std::string& projectFile, const Run& run) {
    editRuns(projectFile, [&](std::vector<Run>& runs) {
        for (const Run& r : runs)
            if (r.id == run.id) throw InputError(projectFile, "/runs", "a run with id '" + run.id + "' already exists");
        runs.push_back(run);
    });
}

}  // namespace rrf
