#include "core/pipeline/pipeline.h"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "core/eval/held_out.h"
#include "core/eval/reference_file.h"
#include "core/pipeline/experiment.h"
#include "core/render/render_outputs.h"
#include "core/util/atomic_file.h"
#include "core/util/image_io.h"
#include "core/util/stopwatch.h"

namespace rrf {

namespace {
std::string pipelineFile(const std::string& dir, const std::string& name) { return (std::filesystem::path(dir) / name).string(); }

/// "[k/4] <stage>: <what> -> <where>", the line each stage ends with.
std::string stageLine(int k, const std::string& what, const std::string& where) {
    return "[" + std::to_string(k) + "/4] " + what + " -> " + where;
}

std::string secondsText(double s) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f s", s);
    return buf;
}

/// The ground truth's files: the terms as EXR, global.png, and render.json with the variances that
/// make the directory a reference with a known noise floor (rrf evaluate --reference).
void writeGroundTruth(const std::string& dir, const Reference& gt, const RenderOptions& ro, float exposure) {
    makeDirectories(dir);
    for (int k = 0; k < kTermCount; ++k)
        writeImage(pipelineFile(dir, std::string(termName(Term(k))) + ".exr"), gt.images[k], ImageFormat::EXR);
    writeImage(pipelineFile(dir, "global.png"), gt.image(Term::Global), ImageFormat::PNG, exposure);
    writeReferenceDescription(dir, gt, ro.width, ro.height);
}
}  // namespace

PipelineOutcome runPipeline(const Project& project, const PipelineRequest& request, ReferenceStore& store,
                            const StageRunner& run, const StageObserver& notes, const PipelineProcesses& processes) {
    const Scene& scene = project.scene;
    const RenderOptions& ro = request.groundTruth;
    const bool writes = processes.writes;
    PipelineOutcome outcome;
    if (writes) makeDirectories(request.out);

    // 1. Ground truth at the scene's light position.
    Reference gt;
    if (processes.groundTruth) {
        gt = processes.groundTruth(scene, scene.lightPosition(), ro);
    } else {
        run("ground truth", [&](const StageObserver& obs) { gt = renderFixedReference(scene, scene.lightPosition(), ro, obs).reference; });
    }
    const std::string gtDir = pipelineFile(request.out, "ground_truth");
    if (writes) {
        writeGroundTruth(gtDir, gt, ro, project.render.exposure);
        outcome.stageSeconds.push_back({"ground truth", gt.seconds});
        notes.note(stageLine(1, "ground truth: " + secondsText(gt.seconds), gtDir));
    }

    // 2. Training data (every process gets the whole of it to train on).
    const DataGenerator generator(scene, request.sampling);
    const std::string dataset = pipelineFile(request.out, "dataset.rrfd");
    GenerateRequest g;
    g.datasetPath = dataset;
    g.generate = processes.generate;
    g.writes = writes;
    GenerateOutcome data;
    if (processes.generate) data = generateStage(generator, g, notes);
    else run("generate", [&](const StageObserver& obs) { data = generateStage(generator, g, obs); });
    if (data.data.cancelled) throw std::runtime_error("interrupted while generating data");
    if (writes) {
        outcome.stageSeconds.push_back({"generate", data.data.seconds});
        notes.note(stageLine(2, "generate: " + std::to_string(data.data.stats.records) + " records in " +
                                    secondsText(data.data.seconds), dataset));
    }

    // 3. Networks.
    const RecordLayout layout = generator.layout();
    const std::vector<ObjectSamples> samples = samplesFromGenerated(data.data, scene, layout);
    const std::string modelDir = pipelineFile(request.out, "models");
    TrainRequest t;
    t.options = request.training;
    t.sceneHash = scene.contentHash();
    t.inputLayout = layout.inputs;
    t.modelsDir = modelDir;
    t.provenance = {dataset, request.projectFile};
    t.share = processes.training;
    TrainOutcome trained;
    run("train", [&](const StageObserver& obs) { trained = trainStage(samples, t, obs); });
    TrainingRun& networks = trained.run;
    outcome.cancelled = networks.cancelled;
    if (writes) {
        outcome.stageSeconds.push_back({"train", networks.seconds});
        notes.note(stageLine(3, "train: " + secondsText(networks.seconds), modelDir));
    }
    if (processes.shareNetworks) processes.shareNetworks(networks);

    // 4. Evaluation: at the ground truth's light, then at held-out lights. The writing process
    // judges the saved models, as a later `rrf evaluate` would load them.
    const ModelSet models = writes && trained.saved ? loadModelSet(modelDir, scene.contentHash())
                                                     : modelSetFromTrained(networks.models, scene, layout);
    const Predictor predictor(scene, models, request.prediction);
    const Stopwatch evalClock;
    if (writes) {
        notes.note("[4/4] evaluate at the ground truth's light:");
        const ReferenceSource groundTruth = [&](size_t, const Vec3&) {
            ObtainedReference o{gt, {}};
            o.info.fixedSpp = gt.spp;
            o.info.directory = gtDir;
            return o;
        };
        outcome.atGroundTruth = evaluateAtLights(project, predictor, {gt.lightPosition}, groundTruth,
                                                 pipelineFile(request.out, "evaluation"), project.render.exposure, notes);
        notes.note("\nevaluate at " + std::to_string(request.heldOutLights) + " held-out light positions:");
    }
    const std::vector<Vec3> lights = heldOutLightPositions(scene.lightRange(), request.heldOutLights, request.heldOutSeed);
    const ReferenceSource held = storeReferenceSource(store, project, predictor, ro.width, ro.height, request.referenceTarget,
                                                      lights.size(), run);
    if (processes.prefetchReferences) processes.prefetchReferences(lights, held);
    if (!writes) return outcome;
    outcome.heldOut = evaluateAtLights(project, predictor, lights, held, pipelineFile(request.out, "held_out"),
                                       project.render.exposure, notes);
    outcome.stageSeconds.push_back({"evaluate", evalClock.seconds()});
    return outcome;
}

}  // namespace rrf
