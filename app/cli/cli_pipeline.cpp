// `rrf pipeline`: ground truth, training data, networks and evaluation (at the ground truth's light
// and at held-out lights) in one run, with each stage's wall time. Under an MPI launcher every stage
// splits across the ranks as its own command does (cli_ranks.h) and rank 0 writes every file
// (docs/cluster.md).
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "app/cli/cli_common.h"
#include "app/cli/cli_evaluation.h"
#include "core/pipeline/run_recording.h"
#include "app/cli/cli_flags.h"
#include "app/cli/commands.h"
#include "app/cli/cli_ranks.h"
#include "app/mpi/ranks.h"
#include "core/data/data_generator.h"
#include "core/pipeline/experiment.h"
#include "core/pipeline/pipeline.h"
#include "app/cli/cli_stage.h"
#include "core/nn/training_part.h"
#include "core/pipeline/presets.h"
#include "core/project/project.h"
#include "core/pipeline/time_estimate.h"
#include "core/data/record_layout.h"
#include "core/project/project_file.h"
#include "core/util/stopwatch.h"

namespace rrf::cli {

namespace {
struct PipelineArgs : PredictionArgs {
    bool quick = false;
    std::string preset;  ///< empty: the project's settings
    std::string estimator;  ///< --estimator of the ground truth and references (empty: the project's)
    int spp = -1, heldOut = 0, sppCap = -1;
    double noise = -1;
    long long seed = 1;
    ExperimentFlags experiment;
};

int runPipeline(const PipelineArgs& a) {
    const mpi::Ranks& ranks = mpi::ranks();
    const bool root = ranks.isRoot();
    Stopwatch total;
    Project p = loadProjectOrScene(a.input);
    applyEstimatorFlag(a.estimator, p.render.estimator);
    refuseOverwritingInputs(a.out, projectInputs(p));
    const Scene& scene = p.scene;
    auto threads = limitThreads(a.threads);
    // --quick is --preset quick; without a preset the project's settings and the command's sizes apply.
    const PipelinePreset* preset = a.quick ? &quickPreset() : a.preset.empty() ? nullptr : findPreset(a.preset);
    SamplingSettings s;
    ObjectTrainingOptions t;
    experimentSettings(p, a.experiment, preset, s, t);
    const PipelineEvaluationSizes sizes = preset ? preset->evaluation : PipelineEvaluationSizes{};
    const RenderOptions ro = referenceOptions(p, a.spp > 0 ? a.spp : sizes.groundTruthSpp, a.width > 0 ? a.width : (sizes.width > 0 ? sizes.width : -1),
                                              a.height > 0 ? a.height : (sizes.height > 0 ? sizes.height : -1));
    const int heldOut = a.heldOut > 0 ? a.heldOut : sizes.heldOutLights;
    // Held-out references come from the project's store, converged to the noise target (the quick
    // preset caps them at 1024 spp unless --spp-cap says otherwise), at the ground truth's size.
    ReferenceStore store = projectReferenceStore(p);
    NoiseTarget target = noiseTargetFor(p, a.noise, a.sppCap);
    if (sizes.referenceSppCap > 0 && a.sppCap <= 0) target.sppCap = std::min(target.sppCap, sizes.referenceSppCap);
    if (root) {
        // What the stages will cost, from the settings (core/pipeline/time_estimate.h).
        const PathRate rate = PathRate::of(0, int(std::thread::hardware_concurrency()));
        const StageEstimate g = estimateGenerate(s, rate);
        const StageEstimate tr = estimateTraining(t, expectedRecords(s), int(scene.objects.size()),
                                                  RecordLayout::forScene(scene).inputCount(), int(std::thread::hardware_concurrency()));
        std::printf("estimated: generate %s (%s); train %s (%s)\n", rangeText(g).c_str(), g.basis.c_str(),
                    rangeText(tr).c_str(), tr.basis.c_str());
        std::printf("rrf pipeline%s: %s -> %s\n  ground truth %dx%d, %d spp; %s; %d held-out lights (references from %s: "
                    "relative noise <= max(%g, %g x the error), at most %d spp)\n",
                    preset ? (std::string(" --preset ") + preset->name).c_str() : "", a.input.c_str(), a.out.c_str(), ro.width,
                    ro.height, ro.spp, describeExperiment(s, t).c_str(), heldOut, store.dir().c_str(), target.relativeRmse,
                    target.errorFraction, target.sppCap);
        std::fflush(stdout);
    }
    PipelineRequest request;
    request.sampling = s;
    request.training = t;
    // A preset's prediction settings (e.g. best's direct samples) under the command's own flags.
    request.prediction = a.prediction.applied(preset ? presetPrediction(p, *preset) : p.prediction);
    request.groundTruth = ro;
    request.heldOutLights = heldOut;
    request.heldOutSeed = uint64_t(a.seed);
    request.referenceTarget = target;
    request.out = a.out;
    request.projectFile = a.input;
    // Under an MPI launcher every stage splits across the ranks as its own command does.
    PipelineProcesses processes;
    processes.writes = root;
    processes.groundTruth = [&](const Scene& sc, const Vec3& lp, const RenderOptions& o) {
        return renderOnRanks(sc, lp, o, "ground truth", ranks);
    };
    processes.generate = [&](const DataGenerator& g) { return generateOnAllRanks(g, ranks); };
    std::optional<RankTraining> rankTraining;
    processes.training = rankTrainingOrNull(rankTraining, ranks, scene);
    if (ranks.size() > 1) {
        // The held-out references converge relative to the model's error, so every rank needs the
        // very networks one process evaluates: rank 0 sends the joined run (weights bit for bit,
        // core/nn/training_part.h) and each rank builds the set in memory, so only the project's
        // reference store has to be shared by the ranks, not --out.
        processes.shareNetworks = [&](TrainingRun& run) {
            std::string bytes = root ? encodeTrainingPart(run) : std::string();
            ranks.broadcast(bytes);
            if (!root) run = decodeTrainingPart(bytes, "the networks from rank 0");
        };
        // The ranks render the held-out references into the store, as rrf evaluate's do.
        processes.prefetchReferences = [&](const std::vector<Vec3>& lights, const ReferenceSource& source) {
            obtainRankReferences(ranks, lights, source);
        };
    }
    const PipelineOutcome outcome = rrf::runPipeline(p, request, store, stageRunner(), printingObserver(), processes);
    if (!root) return outcome.cancelled ? 130 : 0;
    std::printf("\n%-14s %10s\n", "stage", "seconds");
    for (const auto& st : outcome.stageSeconds) std::printf("%-14s %10.2f\n", st.first.c_str(), st.second);
    std::printf("%-14s %10.2f\nresults in %s (ground_truth/, dataset.rrfd, models/, evaluation/, held_out/)\n", "total",
                total.seconds(), a.out.c_str());
    return outcome.cancelled ? 130 : 0;
}
}  // namespace

void addPipelineCommand(CLI::App& app, int& exitCode) {
    auto a = std::make_shared<PipelineArgs>();
    CLI::App* cmd = app.add_subcommand("pipeline", "Ground truth, data, training and evaluation in one run");
    addPredictionOptions(cmd, *a);
    CLI::Option* quick = cmd->add_flag("--quick", a->quick, "the same as --preset quick");
    cmd->add_option("--preset", a->preset, std::string("settings of the whole pipeline (core/pipeline/presets.h): ") + presetNames(", ") +
                                               "; default: the project's")
        ->check(CLI::IsMember([] {
            std::vector<std::string> names;
            for (const PipelinePreset& p : pipelinePresets()) names.push_back(p.name);
            return names;
        }()))
        ->excludes(quick);
    cmd->add_option("--spp", a->spp,
                    "ground-truth samples per pixel (fixed; the held-out references come from the project's reference "
                    "store, converged to the noise target)")
        ->check(positive());
    addNoiseTargetFlags(cmd, a->noise, a->sppCap, "the held-out references", "the project's, 4096; 1024 with the quick preset", true);
    cmd->add_option("--held-out", a->heldOut, "held-out light positions to evaluate")->check(positive());
    addExperimentFlags(cmd, a->experiment);
    cmd->add_option("--seed", a->seed, "seed of the held-out light positions")->check(nonNegative());
    addEstimatorOption(cmd, a->estimator, "the ground truth and the references");
    cmd->callback([a, &exitCode] { exitCode = runPipeline(*a); });
}

}  // namespace rrf::cli
