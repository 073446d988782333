// `rrf pipeline`: ground truth, training data, networks and evaluation (at the ground truth's light
// and at held-out lights) in one run, with each stage's wall time. Under an MPI launcher every stage
// splits across the ranks as its own command does (cli_ranks.h) and rank 0 writes every file
// (docs/cluster.md).
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli/cli_common.h"
#include "app/cli/cli_evaluation.h"
#include "core/project/run_recording.h"
#include "app/cli/cli_flags.h"
#include "app/cli/commands.h"
#include "app/cli/cli_ranks.h"
#include "app/mpi/ranks.h"
#include "core/data/data_generator.h"
#include "core/data/dataset_file.h"
#include "core/eval/experiment.h"
#include "core/nn/training_part.h"
#include "core/eval/held_out.h"
#include "core/nn/model_set.h"
#include "core/nn/training_run.h"
#include "core/project/presets.h"
#include "core/project/project.h"
#include "core/project/time_estimate.h"
#include "core/data/record_layout.h"
#include "core/render/render_outputs.h"
#include "core/util/atomic_file.h"
#include "core/util/image_io.h"
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
        // What the stages will cost, from the settings (core/project/time_estimate.h).
        const PathRate rate = PathRate::of(0, int(std::thread::hardware_concurrency()));
        const StageEstimate g = estimateGenerate(s, rate);
        const StageEstimate tr = estimateTraining(t, expectedRecords(s), int(scene.objects.size()),
                                                  RecordLayout::forScene(scene).inputCount(), int(std::thread::hardware_concurrency()));
        std::printf("estimated: generate %s (%s); train %s (%s)\n", rangeText(g).c_str(), g.basis.c_str(),
                    rangeText(tr).c_str(), tr.basis.c_str());
        makeDirectories(a.out);
        std::printf("rrf pipeline%s: %s -> %s\n  ground truth %dx%d, %d spp; %s; %d held-out lights (references from %s: "
                    "relative noise <= max(%g, %g x the error), at most %d spp)\n",
                    preset ? (std::string(" --preset ") + preset->name).c_str() : "", a.input.c_str(), a.out.c_str(), ro.width,
                    ro.height, ro.spp, describeExperiment(s, t).c_str(), heldOut, store.dir().c_str(), target.relativeRmse,
                    target.errorFraction, target.sppCap);
        std::fflush(stdout);
    }
    std::vector<std::pair<std::string, double>> stages;

    // 1. Ground truth at the scene's light position (each rank its interleaved rows in an MPI job).
    const Reference gt = renderOnRanks(scene, scene.lightPosition(), ro, "ground truth", ranks);
    if (root) {
        const std::string dir = outputPath(a.out, "ground_truth");
        makeDirectories(dir);
        for (int k = 0; k < kTermCount; ++k)
            writeImage(outputPath(dir, std::string(termName(Term(k))) + ".exr"), gt.images[k], ImageFormat::EXR);
        writeImage(outputPath(dir, "global.png"), gt.image(Term::Global), ImageFormat::PNG, p.render.exposure);
        const Vec3 lp = gt.lightPosition;
        nlohmann::json meta{{"light_position", {lp.x, lp.y, lp.z}}, {"spp_completed", gt.spp}, {"seconds", gt.seconds},
                            {"non_finite_samples_dropped", gt.nonFinite}, {"width", ro.width}, {"height", ro.height}};
        // The variances make the directory a reference with a known noise floor (rrf evaluate --reference).
        if (!gt.variance(Term::Global).empty()) {
            std::vector<std::string> written;
            meta["variance_images"] = writeVarianceImages(
                dir, {&gt.variance(Term::Direct), &gt.variance(Term::Indirect), &gt.variance(Term::Global)}, ImageFormat::EXR,
                written);
        }
        writeFileAtomically(outputPath(dir, "render.json"), meta.dump(2) + "\n");
        stages.push_back({"ground truth", gt.seconds});
        std::printf("[1/4] ground truth: %.1f s -> %s\n", gt.seconds, dir.c_str());
    }
    // 2. Training data (each rank its cells in an MPI job; every rank gets the whole data to train on).
    const DataGenerator generator(scene, s);
    std::atomic<bool> cancel{false};
    const GeneratedData data = generateOnAllRanks(generator, ranks);
    if (data.cancelled) throw std::runtime_error("interrupted while generating data");
    const std::string dataset = outputPath(a.out, "dataset.rrfd");
    if (root) {
        writeDataset(dataset, data.header, data.sceneHash, data.perObject);
        stages.push_back({"generate", data.seconds});
        std::printf("[2/4] generate: %llu records in %.1f s -> %s\n", (unsigned long long)data.stats.records, data.seconds,
                    dataset.c_str());
    }
    // 3. Networks (each rank its objects in an MPI job).
    const RecordLayout layout = generator.layout();
    const std::vector<ObjectSamples> samples = samplesFromGenerated(data, scene, layout);
    ObjectTrainingObserver obs;
    obs.cancel = &cancel;
    TrainingRun run = trainOnRanks(samples, t, ranks, scene, obs, cancel);
    const std::string modelDir = outputPath(a.out, "models");
    if (root) {
        stages.push_back({"train", run.seconds});
        NetworkSettings network;
        network.options = t;
        saveTrainingRun(modelDir, run, network, scene.contentHash(), layout.inputs, {dataset, a.input});
        std::printf("[3/4] train: %.1f s -> %s\n", stages.back().second, modelDir.c_str());
    }
    // The held-out references converge relative to the model's error (storeSource), so every rank
    // needs the very networks one process evaluates: rank 0 sends the joined run (weights bit for
    // bit, core/nn/training_part.h) and each rank builds the set in memory, so only the project's
    // reference store has to be shared by the ranks, not --out.
    if (ranks.size() > 1) {
        std::string bytes = root ? encodeTrainingPart(run) : std::string();
        ranks.broadcast(bytes);
        if (!root) run = decodeTrainingPart(bytes, "the networks from rank 0");
    }
    // 4. Evaluation: at the ground truth's light, then at held-out lights.
    const ModelSet models = root ? loadModelSet(modelDir, scene.contentHash()) : modelSetFromTrained(run.models, scene, layout);
    // A preset's prediction settings (e.g. best's direct samples) under the command's own flags.
    const Predictor predictor(scene, models, a.prediction.applied(preset ? presetPrediction(p, *preset) : p.prediction));
    Stopwatch evalClock;
    if (root) {
        std::printf("[4/4] evaluate at the ground truth's light:");
        const ReferenceSource groundTruth = [&](size_t, const Vec3&) {
            return ObtainedReference{gt, {{"fixed_spp", gt.spp}, {"directory", outputPath(a.out, "ground_truth")}}};
        };
        evaluateAll(p, predictor, {gt.lightPosition}, groundTruth, outputPath(a.out, "evaluation"), p.render.exposure);
        std::printf("\nevaluate at %d held-out light positions:\n", heldOut);
    }
    const std::vector<Vec3> lights = heldOutLightPositions(scene.lightRange(), heldOut, uint64_t(a.seed));
    const ReferenceSource held = storeSource(store, p, predictor, ro.width, ro.height, target, size_t(heldOut));
    // In an MPI job the ranks render the held-out references into the store, as rrf evaluate's do.
    if (ranks.size() > 1) obtainRankReferences(ranks, lights, held);
    // Interrupted training: every rank holds the joined run, whose flag says whether any rank was.
    if (!root) return run.cancelled ? 130 : 0;
    evaluateAll(p, predictor, lights, held, outputPath(a.out, "held_out"), p.render.exposure);
    stages.push_back({"evaluate", evalClock.seconds()});
    std::printf("\n%-14s %10s\n", "stage", "seconds");
    for (const auto& st : stages) std::printf("%-14s %10.2f\n", st.first.c_str(), st.second);
    std::printf("%-14s %10.2f\nresults in %s (ground_truth/, dataset.rrfd, models/, evaluation/, held_out/)\n", "total",
                total.seconds(), a.out.c_str());
    return cancel || run.cancelled ? 130 : 0;
}
}  // namespace

void addPipelineCommand(CLI::App& app, int& exitCode) {
    auto a = std::make_shared<PipelineArgs>();
    CLI::App* cmd = app.add_subcommand("pipeline", "Ground truth, data, training and evaluation in one run");
    addPredictionOptions(cmd, *a);
    CLI::Option* quick = cmd->add_flag("--quick", a->quick, "the same as --preset quick");
    cmd->add_option("--preset", a->preset, std::string("settings of the whole pipeline (core/project/presets.h): ") + presetNames(", ") +
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
