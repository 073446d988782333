// `rrf evaluate`: the networks' predictions against path-traced references at the scene's light, at
// a given position, at K held-out positions, over a grid of the light region (--light-grid), or
// against a saved `rrf render` output. Under an MPI
// launcher the ranks render the references of the light positions into the project's reference
// store, each its share, and rank 0 evaluates (docs/cluster.md).
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "app/cli/cli_common.h"
#include "app/cli/cli_ranks.h"
#include "app/cli/cli_evaluation.h"
#include "app/cli/cli_flags.h"
#include "app/cli/commands.h"
#include "app/mpi/ranks.h"
#include "core/eval/held_out.h"
#include "core/eval/reference_file.h"
#include "core/nn/model_set.h"
#include "core/project/project.h"
#include "core/pipeline/run_recording.h"
#include "core/project/project_file.h"
#include "core/util/error.h"
#include "core/util/stopwatch.h"
#include "core/render/render_outputs.h"

namespace rrf::cli {

namespace {
struct EvaluateArgs : PredictionArgs {
    std::string models, reference;
    std::string estimator;  ///< --estimator of the references (empty: the project's)
    std::string lightGrid;  ///< --light-grid NxMxK (empty: none)
    std::optional<Vec3> lightPos;
    int heldOut = 0, spp = -1, sppCap = -1;
    double noise = -1;
    long long seed = 1;
    float exposure = 0.f;
    bool record = false;
};

/// For --record: the train run that made `a.models` must be in the project, since the evaluation's
/// metrics go into it (as the workbench does); the files go to runs/<that run>/evaluation unless --out.
void prepareRecording(const Project& p, EvaluateArgs& a) {
    if (!a.record) {
        if (a.out.empty()) throw InputError("command line", "--out", "an output directory is required (or --record)");
        return;
    }
    if (isBareScene(p))
        throw InputError("command line", "--record", a.input + " is a scene file, not a project: there is no project to record the run in");
    const Run* trained = findTrainRun(p.runs, projectDirectory(p), a.models);
    if (!trained)
        throw InputError("command line", "--record",
                         "the models in " + a.models + " are not from a train run recorded in " + a.input +
                             " (train them with rrf train --record)");
    if (a.out.empty()) a.out = outputPath(runDirectory(projectDirectory(p), *trained), "evaluation");
}

/// Adds what `evals` (references of width x height) measured to the train run that made the models
/// and saves the project.
void recordEvaluations(const EvaluateArgs& a, const Project& p, const std::vector<Evaluation>& evals, int width,
                       int height, double seconds, const char* report = nullptr) {
    EvaluationRecord r;
    for (const Evaluation& e : evals) {
        const ErrorStats& g = e.term(Term::Global).overall;
        r.global.pixels += g.pixels;
        r.global.relativeRmse += g.relativeRmse / double(evals.size());
        r.global.rmse += g.rmse / double(evals.size());
        r.global.mae += g.mae / double(evals.size());
        r.lights.push_back(e.lightPosition);
    }
    r.referenceSpp = evals.empty() ? 0 : evals.front().referenceSpp;
    r.width = width;
    r.height = height;
    r.seconds = seconds;
    r.artifacts = {outputPath(a.out, report ? report : evals.size() > 1 ? "held_out.json" : "evaluation.json")};
    const std::string dir = projectDirectory(p);
    editRuns(a.input, [&](std::vector<Run>& runs) { recordEvaluation(runs, dir, a.models, r); });
    std::printf("recorded the evaluation in the train run of %s in %s\n", a.models.c_str(), a.input.c_str());
}

int runEvaluate(EvaluateArgs a) {
    const mpi::Ranks& ranks = mpi::ranks();
    const std::optional<LightGridSpec> grid =
        a.lightGrid.empty() ? std::nullopt : std::optional<LightGridSpec>(LightGridSpec::parse(a.lightGrid, "command line", "--light-grid"));
    Project p = loadProjectOrScene(a.input);
    if (grid) checkLightGrid(*grid, p.scene, "command line", "--light-grid");
    applyEstimatorFlag(a.estimator, p.render.estimator);
    std::vector<std::string> inputs = projectInputs(p);
    inputs.push_back(a.models);
    inputs.push_back(a.reference);
    refuseOverwritingInputs(a.out, inputs);
    if (ranks.size() > 1 && a.spp > 0)
        throw InputError("command line", "--spp",
                         "references at a fixed spp are not stored, so MPI ranks cannot share them; drop --spp (the "
                         "project's reference store) or run one process");
    if (ranks.size() > 1 && !a.reference.empty())
        throw InputError("command line", "--reference", "one given reference leaves nothing to split across MPI ranks; run one process");
    if (ranks.isRoot()) prepareRecording(p, a);
    auto threads = limitThreads(a.threads);
    const ModelSet models = loadModelSet(a.models, p.scene.contentHash());
    const Predictor predictor(p.scene, models, a.prediction.applied(p.prediction));
    if (ranks.isRoot()) makeDirectories(a.out);
    if (ranks.isRoot()) {
        std::printf("rrf evaluate: %s with %s (direct light: %s)\n", a.input.c_str(), a.models.c_str(),
                    predictor.settings().directName());
        for (const std::string& l : predictor.describe()) std::printf("  %s\n", l.c_str());
    }
    if (!a.reference.empty()) {
        const Reference ref = loadReference(a.reference);
        std::printf("reference: %s (%d spp, light at %.3f,%.3f,%.3f; noise %s)\n", a.reference.c_str(), ref.spp,
                    ref.lightPosition.x, ref.lightPosition.y, ref.lightPosition.z,
                    ref.variance(Term::Global).empty() ? "unknown: no variance images, noise floors are not known"
                                                       : "known from its variance images");
        const Stopwatch clock;
        const ReferenceSource given = [&](size_t, const Vec3&) {
            ObtainedReference o{ref, {}};
            o.info.directory = a.reference;
            return o;
        };
        const std::vector<Evaluation> evals = evaluateAll(p, predictor, {ref.lightPosition}, given, a.out, a.exposure);
        const Image& refImage = ref.images[int(Term::Global)];
        if (a.record) recordEvaluations(a, p, evals, refImage.width, refImage.height, clock.seconds());
        return 0;
    }
    std::vector<Vec3> lights;
    if (grid) lights = grid->positions(p.scene.lightRange());
    else if (a.heldOut > 0) lights = heldOutLightPositions(p.scene.lightRange(), a.heldOut, uint64_t(a.seed));
    else lights = {a.lightPos.value_or(p.scene.lightPosition())};
    if (a.lightPos) checkLightPosition(p.scene, *a.lightPos);
    // --spp: a fixed number of samples, no noise target, not stored. Otherwise the project's store
    // renders (or reuses) references converged to the noise target.
    ReferenceStore store = projectReferenceStore(p);
    const NoiseTarget target = noiseTargetFor(p, a.noise, a.sppCap);
    const auto [width, height] = referenceSize(p, a.width, a.height);
    const RenderOptions ro = referenceOptions(p, a.spp, a.width, a.height);
    const ReferenceSource source = a.spp > 0 ? fixedSppSource(p, ro, lights.size())
                                             : storeSource(store, p, predictor, width, height, target, lights.size());
    // The size of the references the figures are measured at (recorded beside them).
    const int evalWidth = a.spp > 0 ? ro.width : width, evalHeight = a.spp > 0 ? ro.height : height;
    if (a.spp > 0)
        std::printf("%zu light position(s), references %dx%d at a fixed %d spp (no noise target, not stored)\n", lights.size(),
                    ro.width, ro.height, ro.spp);
    else if (ranks.isRoot())
        std::printf("%zu light position(s)%s, references %dx%d from %s: relative noise <= max(%g, %g x the error), at most "
                    "%d spp\n",
                    lights.size(),
                    grid         ? (" (a " + grid->text() + " grid over the light region)").c_str()
                    : a.heldOut > 0 ? (" (held out, seed " + std::to_string(a.seed) + ")").c_str()
                                    : "",
                    width,
                    height, store.dir().c_str(), target.relativeRmse, target.errorFraction, target.sppCap);
    const Stopwatch clock;
    if (ranks.size() > 1) {
        obtainRankReferences(ranks, lights, source);
        if (!ranks.isRoot()) return 0;
    }
    if (grid) {
        const LightGridOutcome o = lightGrid(p, predictor, *grid, source, a.out, a.exposure, trainingLightMarks(p, a.models));
        if (a.record) recordEvaluations(a, p, o.evaluations, evalWidth, evalHeight, clock.seconds(), "light_grid.json");
        return 0;
    }
    const std::vector<Evaluation> evals = evaluateAll(p, predictor, lights, source, a.out, a.exposure);
    if (a.record) recordEvaluations(a, p, evals, evalWidth, evalHeight, clock.seconds());
    return 0;
}
}  // namespace

void addEvaluateCommand(CLI::App& app, int& exitCode) {
    auto a = std::make_shared<EvaluateArgs>();
    CLI::App* cmd = app.add_subcommand("evaluate", "Compare network predictions with path-traced references");
    addPredictionOptions(cmd, *a);
    cmd->add_option("--models", a->models, "model directory (rrf train --out)")->required();
    CLI::Option* lp = addVec3Option(cmd, "--light-pos", a->lightPos, "light centre x,y,z (default: the scene's)");
    cmd->add_option("--held-out", a->heldOut, "evaluate at K held-out light positions")->check(positive())->excludes(lp);
    CLI::Option* ref = cmd->add_option("--reference", a->reference, "use this rrf render output instead of rendering")->excludes(lp);
    cmd->add_option("--light-grid", a->lightGrid,
                    "evaluate at an NxMxK grid of light positions spanning the light region (edges included): "
                    "light_grid.json, light_grid.txt and one error map per y slice, light_grid_y<j>.png, with the "
                    "training records' lights marked")
        ->excludes(lp)
        ->excludes(ref)
        ->excludes("--held-out");
    CLI::Option* spp = cmd->add_option("--spp", a->spp,
                                       "render references at this fixed spp: no noise target, not stored (default: the "
                                       "project's reference store, converged to the noise target)")
                           ->check(positive());
    addNoiseTargetFlags(cmd, a->noise, a->sppCap, "the references", "the project's, 4096", true, spp);
    cmd->add_option("--seed", a->seed, "seed of the held-out light positions")->check(nonNegative());
    addEstimatorOption(cmd, a->estimator, "the references");
    cmd->add_option("--exposure", a->exposure, "exposure in stops for PNG output")->check(finiteNumber());
    cmd->get_option("--out")->required(false)->description("output directory (required unless --record)");
    cmd->add_flag("--record", a->record,
                  "add the evaluation's metrics to the project's train run that made --models, as the workbench does "
                  "(files under runs/<that run>/evaluation unless --out); this saves the project file, which the CLI "
                  "otherwise never changes");
    cmd->callback([a, &exitCode] { exitCode = runEvaluate(*a); });
}

}  // namespace rrf::cli
