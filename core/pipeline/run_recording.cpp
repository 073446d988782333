#include "core/pipeline/run_recording.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <system_error>

#include "core/nn/mlp_kernel.h"
#include "core/project/project_file.h"
#include "core/util/error.h"
#include "core/util/text_format.h"

namespace rrf {

namespace fs = std::filesystem;

namespace {
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
    run.settings = RunSettings();
    run.settings.render = settings;
    run.settings.lightPosition = scene.lightPosition();
    run.settings.sceneHash = hexString(scene.contentHash());
    if (!overrides.empty()) run.settings.sceneOverrides = overrides;
    run.metrics = RunMetrics();
    run.metrics.spp = snapshot.sppCompleted;
    run.metrics.relativeError = snapshot.relativeError;
    run.metrics.nonFiniteSamples = snapshot.nonFinite;
    run.metrics.samplesPerSecond = stats.samplesPerSecond();
    run.timings = RunTimings();
    run.timings.render = snapshot.seconds;
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
    run.settings = RunSettings();
    run.settings.network = r.network;
    run.settings.trainer = r.trainer;
    run.settings.dataset = projectRelative(projectDir, r.dataset);
    run.settings.sceneHash = hexString(r.sceneHash);
    run.settings.sampling = r.sampling;
    // The process trains with one kernel (nn/mlp_kernel.h); a model reproduces bit for bit on it only.
    run.settings.kernel = mlpKernelName(mlpKernel());
    int epochs = 0;
    for (const LossCurve& c : r.curves)
        for (const LossPoint& p : c.points) epochs = std::max(epochs, p.epoch);
    run.curves = std::move(r.curves);
    run.loss = aggregateLoss(run.curves);
    run.metrics = RunMetrics();
    run.metrics.networks = r.networks;
    run.metrics.skipped = r.skipped;
    run.metrics.epochs = epochs;
    if (r.plannedNetworks > 0) run.metrics.plannedNetworks = r.plannedNetworks;
    if (r.stopped) run.metrics.stopped = true;
    if (r.leaves > 0) run.metrics.leaves = r.leaves;
    if (r.records > 0) run.metrics.records = r.records;
    run.timings = RunTimings();
    run.timings.train = r.seconds;
    run.timings.generate = r.generateSeconds;
    run.artifacts = {projectRelative(projectDir, (fs::path(r.modelsDir) / "models.json").string())};
}

bool isStoppedTrainRun(const Run& run) {
    return run.kind == "train" && run.metrics.stopped.value_or(false);
}

std::string stoppedTrainingText(int epoch, int networks, int planned) {
    std::string t = "stopped at epoch " + std::to_string(epoch) + ", " + std::to_string(networks);
    if (planned > 0) t += " of " + std::to_string(planned);
    return t + (planned == 1 || (planned <= 0 && networks == 1) ? " network" : " networks");
}

std::string trainRunStatusText(const Run& run) {
    if (run.kind != "train") return {};
    const int networks = run.metrics.networks.value_or(0);
    if (isStoppedTrainRun(run))
        return stoppedTrainingText(run.metrics.epochs.value_or(0), networks, run.metrics.plannedNetworks.value_or(0));
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
        RunMetrics& m = r.metrics;
        m.relativeRmse = e.global.relativeRmse;
        m.rmse = e.global.rmse;
        m.mae = e.global.mae;
        m.evaluatedSpp = e.referenceSpp;
        m.evaluatedWidth.reset();
        m.evaluatedHeight.reset();
        if (e.width > 0 && e.height > 0) {
            m.evaluatedWidth = e.width;
            m.evaluatedHeight = e.height;
        }
        // The noise floor makes the error readable (an error at the floor is as good as the
        // reference allows); without the reference's variance it is unknown and left out.
        m.relativeRmseNoiseFloor.reset();
        m.relativeRmseCorrected.reset();
        if (std::isfinite(e.global.relativeRmseNoiseFloor)) {
            m.relativeRmseNoiseFloor = e.global.relativeRmseNoiseFloor;
            if (std::isfinite(e.global.relativeRmseCorrected)) m.relativeRmseCorrected = e.global.relativeRmseCorrected;
        }
        m.evaluatedLight.reset();
        m.evaluatedLights.reset();
        if (e.lights.size() == 1)
            m.evaluatedLight = e.lights.front();
        else
            m.evaluatedLights = int64_t(e.lights.size());
        r.timings.evaluate = e.seconds;
        // models.json stays first: the workbench loads the models from the first artifact's directory.
        for (const std::string& a : e.artifacts) {
            const std::string rel = projectRelative(projectDir, a);
            if (std::find(r.artifacts.begin(), r.artifacts.end(), rel) == r.artifacts.end()) r.artifacts.push_back(rel);
        }
        ++changed;
    }
    return changed;
}

int recordFrameSeconds(std::vector<Run>& runs, const std::string& projectDir, const std::string& modelsDir,
                       FramePath path, double seconds, int width, int height) {
    int changed = 0;
    const fs::path wanted = normal(modelsDir);
    for (Run& r : runs)
        if (trainedInto(r, projectDir, wanted)) {
            RunMetrics& m = r.metrics;
            (path == FramePath::Glsl ? m.glslFrameSeconds : m.frameSeconds) = seconds;
            (path == FramePath::Glsl ? m.glslFrameWidth : m.frameWidth) = width;
            (path == FramePath::Glsl ? m.glslFrameHeight : m.frameHeight) = height;
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
