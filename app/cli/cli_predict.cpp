// `rrf evaluate`, `rrf predict`, `rrf sweep` and `rrf pipeline`: networks re-light the scene, are
// compared with the path tracer, and the cost of each setting is measured.
#include <cstdio>
#include <filesystem>
#include <string>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "core/util/atomic_file.h"
#include "core/data/dataset_file.h"
#include "core/util/error.h"
#include "core/eval/experiment.h"
#include "core/eval/held_out.h"
#include "core/util/image_io.h"
#include "core/nn/network_settings.h"
#include "core/render/render_outputs.h"
#include "core/eval/sweep.h"
#include "core/project/project.h"

namespace rrf::cli {

namespace fs = std::filesystem;

namespace {
struct Args {
    std::string input, models, out, lightPos, reference, direct, what, values, hidden, trainer;
    int heldOut = 0, spp = -1, width = -1, height = -1, threads = 0, frames = 5, grid = -1, dirs = -1, dataSpp = -1,
        epochs = -1, referenceSpp = -1;
    long long seed = 1;
    float exposure = 0.f;
    bool quick = false;
};

std::string path(const std::string& dir, const std::string& name) { return (fs::path(dir) / name).string(); }

void write(const std::string& file, const std::string& text) {
    writeFileAtomically(file, text);
    std::printf("wrote %s\n", file.c_str());
}

PredictionSettings predictionSettings(const Project& p, const Args& a) {
    PredictionSettings s = p.prediction;
    if (!a.direct.empty()) s.direct = a.direct == "exact" ? PredictionSettings::Direct::Exact : PredictionSettings::Direct::Network;
    return s;
}

RenderOptions referenceOptions(const Project& p, int spp, int width, int height) {
    RenderSettings s = p.render;
    if (spp > 0) s.spp = spp;
    if (width > 0) s.width = width;
    if (height > 0) s.height = height;
    return renderOptionsFor(p.scene, s, 16);
}

Reference renderWithProgress(const Scene& scene, const Vec3& lp, const RenderOptions& o, const std::string& label) {
    std::atomic<bool> cancel{false};
    std::atomic<double> progress{0.0};
    Reference r;
    runWithProgress(label, [&] { r = renderReference(scene, lp, o, &cancel, &progress); },
                    [&] { return std::make_pair(progress.load(), std::string()); }, [&] { cancel = true; });
    if (r.cancelled) throw std::runtime_error("interrupted while rendering the reference");
    return r;
}

/// Evaluates at each light position (rendering references), writes maps and reports; returns the
/// evaluations. With one position the files go to `out`, otherwise to out/light_<k>.
std::vector<Evaluation> evaluateAll(const Project& p, const Predictor& predictor, const std::vector<Vec3>& lights,
                                    const RenderOptions& ro, const Reference* given, const std::string& out, float exposure) {
    std::vector<Evaluation> evals;
    nlohmann::json reports = nlohmann::json::array();
    for (size_t k = 0; k < (given ? 1 : lights.size()); ++k) {
        const Reference ref = given ? *given
                                    : renderWithProgress(p.scene, lights[k], ro,
                                                         "reference " + std::to_string(k + 1) + "/" + std::to_string(lights.size()));
        const std::string dir = lights.size() > 1 ? path(out, "light_" + std::to_string(k)) : out;
        evals.push_back(evaluate(predictor, ref));
        const Evaluation& e = evals.back();
        nlohmann::json report = evaluationJson(p.scene, e);
        report["images"] = writeEvaluationImages(dir, e, ref, exposure);
        writeFileAtomically(path(dir, "evaluation.json"), report.dump(2) + "\n");
        const std::string table = evaluationTable(p.scene, e);
        writeFileAtomically(path(dir, "evaluation.txt"), table);
        std::printf("\n%s", table.c_str());
        std::printf("prediction: G-buffer %.1f ms, networks %.1f ms, exact direct %.1f ms; reference %.2f s; files in %s\n",
                    1e3 * e.gbufferSeconds, 1e3 * e.prediction.inferenceSeconds, 1e3 * e.prediction.directSeconds,
                    e.referenceSeconds, dir.c_str());
        for (const std::string& why : e.prediction.unavailableWhy) std::printf("unavailable: %s\n", why.c_str());
        reports.push_back(report);
    }
    if (evals.size() > 1) {
        const HeldOutSummary s = summarizeHeldOut(evals, p.scene.objects.size());
        const std::string table = heldOutTable(p.scene, s);
        std::printf("\nheld-out lights: spread over %zu positions\n%s", evals.size(), table.c_str());
        write(path(out, "held_out.txt"), table);
        write(path(out, "held_out.json"), nlohmann::json{{"summary", heldOutJson(p.scene, s)}, {"evaluations", reports}}.dump(2) + "\n");
    }
    return evals;
}

int runEvaluate(const Args& a) {
    const Project p = loadProjectOrScene(a.input);
    auto threads = limitThreads(a.threads);
    const ModelSet models = loadModelSet(a.models, p.scene.contentHash());
    const Predictor predictor(p.scene, models, predictionSettings(p, a));
    makeDirectories(a.out);
    std::printf("rrf evaluate: %s with %s (direct light: %s)\n", a.input.c_str(), a.models.c_str(), predictor.settings().directName());
    for (const std::string& l : predictor.describe()) std::printf("  %s\n", l.c_str());
    const RenderOptions ro = referenceOptions(p, a.spp, a.width, a.height);
    if (!a.reference.empty()) {
        const Reference ref = loadReference(a.reference);
        std::printf("reference: %s (%d spp, light at %.3f,%.3f,%.3f)\n", a.reference.c_str(), ref.spp, ref.lightPosition.x,
                    ref.lightPosition.y, ref.lightPosition.z);
        evaluateAll(p, predictor, {ref.lightPosition}, ro, &ref, a.out, a.exposure);
        return 0;
    }
    std::vector<Vec3> lights;
    if (a.heldOut > 0) {
        lights = heldOutLightPositions(p.scene.lightRange(), a.heldOut, uint64_t(a.seed));
        std::printf("%d held-out light positions (seed %lld), references %dx%d at %d spp\n", a.heldOut, a.seed, ro.width,
                    ro.height, ro.spp);
    } else {
        lights = {a.lightPos.empty() ? p.scene.lightPosition() : parseVec3(a.lightPos, "--light-pos")};
    }
    evaluateAll(p, predictor, lights, ro, nullptr, a.out, a.exposure);
    return 0;
}

int runPredict(const Args& a) {
    const Project p = loadProjectOrScene(a.input);
    auto threads = limitThreads(a.threads);
    const ModelSet models = loadModelSet(a.models, p.scene.contentHash());
    const Predictor predictor(p.scene, models, predictionSettings(p, a));
    const RenderOptions ro = referenceOptions(p, 1, a.width, a.height);
    const Vec3 lp = a.lightPos.empty() ? p.scene.lightPosition() : parseVec3(a.lightPos, "--light-pos");
    // Best of N frames: the first pays for page faults and thread start-up.
    double bestG = 1e30, bestN = 1e30, bestD = 1e30;
    Prediction pr;
    for (int f = 0; f < std::max(1, a.frames); ++f) {
        Stopwatch g;
        const GBuffer gb = predictor.gbuffer(lp, ro.width, ro.height);
        bestG = std::min(bestG, g.seconds());
        pr = predictor.predict(gb);
        bestN = std::min(bestN, pr.inferenceSeconds);
        bestD = std::min(bestD, pr.directSeconds);
    }
    for (const std::string& f : writePredictionImages(a.out, pr, a.exposure)) std::printf("wrote %s\n", f.c_str());
    for (const std::string& why : pr.unavailableWhy) std::printf("unavailable: %s\n", why.c_str());
    if (pr.pixelsWithoutNetwork)
        std::printf("%zu visible objects have no network: %llu pixels black\n", pr.objectsWithoutNetwork.size(),
                    (unsigned long long)pr.pixelsWithoutNetwork);
    if (pr.nonFinite) std::printf("warning: %llu non-finite values kept out of the images\n", (unsigned long long)pr.nonFinite);
    std::printf("%dx%d, light at (%.3f, %.3f, %.3f), direct light %s: %.2f ms per frame (G-buffer %.2f ms, networks %.2f ms%s), "
                "best of %d\n", ro.width, ro.height, lp.x, lp.y, lp.z, predictor.settings().directName(),
                1e3 * (bestG + bestN + bestD), 1e3 * bestG, 1e3 * bestN,
                bestD > 0 ? (", exact direct " + std::to_string(1e3 * bestD) + " ms").c_str() : "", std::max(1, a.frames));
    return 0;
}

/// Settings of the pipeline and sweeps: the project's sections where present, small defaults where not.
void stageSettings(const Project& p, const Args& a, bool quick, SamplingSettings& s, ObjectTrainingOptions& t) {
    s = p.samplingOrDefault();
    if (quick || !p.sampling) {
        // 15³ × 1200 directions (the paper's) is hours on 2 cores; these finish in minutes.
        s.nx = s.ny = s.nz = quick ? 5 : 6;
        s.directions = quick ? 150 : 200;
        s.spp = quick ? 16 : 32;
    }
    t = p.networkOrDefault().options;
    if (quick || !p.network) t.trainer.lm.maxEpochs = t.trainer.adam.maxEpochs = quick ? 50 : 100;
    if (a.grid > 0) s.nx = s.ny = s.nz = a.grid;
    if (a.dirs > 0) s.directions = a.dirs;
    if (a.dataSpp > 0) s.spp = a.dataSpp;
    if (!a.hidden.empty()) t.hidden = parseHiddenSizes(a.hidden, "--hidden");
    if (!a.trainer.empty()) t.trainer = t.trainer.withType(a.trainer);
    if (a.epochs > 0) t.trainer.lm.maxEpochs = t.trainer.adam.maxEpochs = a.epochs;
}

std::string describe(const SamplingSettings& s, const ObjectTrainingOptions& t) {
    char buf[256];
    std::snprintf(buf, sizeof buf, "grid %dx%dx%d, %d directions, %d spp per record; network %s, targets %s, %s, %d epochs",
                  s.nx, s.ny, s.nz, s.directions, s.spp, nlohmann::json(t.hidden).dump().c_str(), targetModeName(t.targets),
                  t.trainer.typeName(), t.trainer.maxEpochs());
    return buf;
}

int runSweepCommand(const Args& a) {
    const Project p = loadProjectOrScene(a.input);
    auto threads = limitThreads(a.threads);
    SweepOptions o;
    o.what = a.what;
    if (!a.values.empty()) {
        std::istringstream in(a.values);
        for (std::string v; std::getline(in, v, ',');) o.values.push_back(v);
    }
    o.width = a.width > 0 ? a.width : 128;
    o.height = a.height > 0 ? a.height : 128;
    o.referenceSpp = a.referenceSpp > 0 ? a.referenceSpp : 0;
    stageSettings(p, a, true, o.sampling, o.training);
    o.prediction = predictionSettings(p, a);
    o.seed = uint64_t(a.seed);
    std::atomic<bool>& interrupted = installInterruptHandler();
    o.cancel = &interrupted;
    o.log = [](const std::string& m) {
        std::printf("  %s\n", m.c_str());
        std::fflush(stdout);
    };
    std::printf("rrf sweep %s: %s, %dx%d; %s\n", a.what.c_str(), a.input.c_str(), o.width, o.height,
                describe(o.sampling, o.training).c_str());
    std::fflush(stdout);
    Stopwatch clock;
    const SweepResult r = runSweep(p.scene, o);
    makeDirectories(a.out);
    write(path(a.out, "sweep_" + a.what + ".csv"), sweepCsv(p.scene, r));
    write(path(a.out, "sweep_" + a.what + ".json"), sweepJson(p.scene, r).dump(2) + "\n");
    const std::string curves = sweepCurveCsv(r);
    if (!curves.empty()) write(path(a.out, "sweep_" + a.what + "_curves.csv"), curves);
    const std::string table = sweepTable(r);
    write(path(a.out, "sweep_" + a.what + ".txt"), table);
    std::printf("\nlight at (%.3f, %.3f, %.3f), reference %d spp (%.1f s); error of the global image%s\n%s",
                r.lightPosition.x, r.lightPosition.y, r.lightPosition.z, r.referenceSpp, r.referenceSeconds,
                a.what == "spp" ? " (all pixels)" : " (object pixels)", table.c_str());
    std::printf("sweep took %.1f s%s\n", clock.seconds(), r.cancelled ? " (interrupted)" : "");
    return r.cancelled ? 130 : 0;
}

int runPipeline(const Args& a) {
    Stopwatch total;
    const Project p = loadProjectOrScene(a.input);
    const Scene& scene = p.scene;
    auto threads = limitThreads(a.threads);
    SamplingSettings s;
    ObjectTrainingOptions t;
    stageSettings(p, a, a.quick, s, t);
    const RenderOptions ro = referenceOptions(p, a.spp > 0 ? a.spp : (a.quick ? 32 : 64), a.width > 0 ? a.width : (a.quick ? 128 : -1),
                                              a.height > 0 ? a.height : (a.quick ? 128 : -1));
    const int heldOut = a.heldOut > 0 ? a.heldOut : (a.quick ? 1 : 2);
    makeDirectories(a.out);
    std::printf("rrf pipeline%s: %s -> %s\n  ground truth %dx%d, %d spp; %s; %d held-out lights\n", a.quick ? " --quick" : "",
                a.input.c_str(), a.out.c_str(), ro.width, ro.height, ro.spp, describe(s, t).c_str(), heldOut);
    std::vector<std::pair<std::string, double>> stages;

    // 1. Ground truth at the scene's light position.
    const Reference gt = renderWithProgress(scene, scene.lightPosition(), ro, "ground truth");
    {
        const std::string dir = path(a.out, "ground_truth");
        makeDirectories(dir);
        for (int k = 0; k < kTermCount; ++k) writeImage(path(dir, std::string(termName(Term(k))) + ".exr"), gt.images[k], ImageFormat::EXR);
        writeImage(path(dir, "global.png"), gt.image(Term::Global), ImageFormat::PNG, p.render.exposure);
        const Vec3 lp = gt.lightPosition;
        writeFileAtomically(path(dir, "render.json"),
                            nlohmann::json{{"light_position", {lp.x, lp.y, lp.z}}, {"spp_completed", gt.spp}, {"seconds", gt.seconds},
                                           {"non_finite_samples_dropped", gt.nonFinite}, {"width", ro.width}, {"height", ro.height}}
                                    .dump(2) + "\n");
        stages.push_back({"ground truth", gt.seconds});
        std::printf("[1/4] ground truth: %.1f s -> %s\n", gt.seconds, dir.c_str());
    }
    // 2. Training data.
    const DataGenerator generator(scene, s);
    GeneratorProgress gp;
    std::atomic<bool> cancel{false};
    GeneratedData data;
    runWithProgress("generate", [&] { data = generator.run(0, 1, &cancel, &gp); },
                    [&] { return std::make_pair(gp.fraction(), humanCount(double(gp.records)) + "records"); }, [&] { cancel = true; });
    if (data.cancelled) throw std::runtime_error("interrupted while generating data");
    const std::string dataset = path(a.out, "dataset.rrfd");
    writeDataset(dataset, data.header, data.sceneHash, data.perObject);
    stages.push_back({"generate", data.seconds});
    std::printf("[2/4] generate: %llu records in %.1f s -> %s\n", (unsigned long long)data.header["stats"]["records"].get<uint64_t>(),
                data.seconds, dataset.c_str());
    // 3. Networks.
    const RecordLayout layout = generator.layout();
    const std::vector<ObjectSamples> samples = samplesFromGenerated(data, scene, layout);
    std::vector<ObjectModel> trained;
    std::atomic<int> epochs{0};
    ObjectTrainingObserver obs;
    obs.cancel = &cancel;
    obs.onEpoch = [&](int, const std::string&, const EpochRecord&) { ++epochs; };
    const double totalEpochs = double(samples.size()) * (t.targets == TargetMode::Separate ? 2 : 1) * t.trainer.maxEpochs();
    Stopwatch trainClock;
    runWithProgress("train", [&] { trained = trainObjects(samples, t, obs); },
                    [&] { return std::make_pair(std::min(1.0, epochs / std::max(1.0, totalEpochs)), std::string()); },
                    [&] { cancel = true; });
    stages.push_back({"train", trainClock.seconds()});
    const std::string modelDir = path(a.out, "models");
    saveModelSet(modelDir, trained, scene.contentHash(), layout.inputs,
                 {{"dataset", dataset}, {"project", a.input}, {"seconds", stages.back().second}, {"cancelled", bool(cancel)}});
    std::printf("[3/4] train: %.1f s -> %s\n", stages.back().second, modelDir.c_str());
    // 4. Evaluation: at the ground truth's light, then at held-out lights.
    const ModelSet models = loadModelSet(modelDir, scene.contentHash());
    const Predictor predictor(scene, models, predictionSettings(p, a));
    Stopwatch evalClock;
    std::printf("[4/4] evaluate at the ground truth's light:");
    evaluateAll(p, predictor, {gt.lightPosition}, ro, &gt, path(a.out, "evaluation"), p.render.exposure);
    std::printf("\nevaluate at %d held-out light positions:", heldOut);
    evaluateAll(p, predictor, heldOutLightPositions(scene.lightRange(), heldOut, uint64_t(a.seed)), ro, nullptr,
                path(a.out, "held_out"), p.render.exposure);
    stages.push_back({"evaluate", evalClock.seconds()});
    std::printf("\n%-14s %10s\n", "stage", "seconds");
    for (const auto& st : stages) std::printf("%-14s %10.2f\n", st.first.c_str(), st.second);
    std::printf("%-14s %10.2f\nresults in %s (ground_truth/, dataset.rrfd, models/, evaluation/, held_out/)\n", "total",
                total.seconds(), a.out.c_str());
    return cancel ? 130 : 0;
}

void commonOptions(CLI::App* cmd, Args& a) {
    cmd->add_option("input", a.input, "project or scene JSON file")->required();
    cmd->add_option("--out", a.out, "output directory")->required();
    cmd->add_option("--threads", a.threads, "worker threads (0 = all cores)")->check(CLI::NonNegativeNumber);
    cmd->add_option("--width", a.width, "image width (default: the project's)")->check(CLI::Range(1, 16384));
    cmd->add_option("--height", a.height, "image height (default: the project's)")->check(CLI::Range(1, 16384));
    cmd->add_option("--direct", a.direct, "direct light from the networks or exact shadow rays (default: the project's)")
        ->check(CLI::IsMember({"network", "exact"}));
}
}  // namespace

void addPredictCommands(CLI::App& app, int& exitCode) {
    auto a = std::make_shared<Args>();
    CLI::App* ev = app.add_subcommand("evaluate", "Compare network predictions with path-traced references");
    commonOptions(ev, *a);
    ev->add_option("--models", a->models, "model directory (rrf train --out)")->required();
    auto* lp = ev->add_option("--light-pos", a->lightPos, "light centre x,y,z (default: the scene's)");
    ev->add_option("--held-out", a->heldOut, "evaluate at K held-out light positions")->check(CLI::PositiveNumber)->excludes(lp);
    ev->add_option("--reference", a->reference, "use this rrf render output instead of rendering")->excludes(lp);
    ev->add_option("--spp", a->spp, "reference samples per pixel (default: the project's)")->check(CLI::PositiveNumber);
    ev->add_option("--seed", a->seed, "seed of the held-out light positions")->check(CLI::NonNegativeNumber);
    ev->add_option("--exposure", a->exposure, "exposure in stops for PNG output");
    ev->callback([a, &exitCode] { exitCode = runEvaluate(*a); });

    auto b = std::make_shared<Args>();
    CLI::App* pr = app.add_subcommand("predict", "Predict direct, indirect and global images with the networks");
    commonOptions(pr, *b);
    pr->add_option("--models", b->models, "model directory (rrf train --out)")->required();
    pr->add_option("--light-pos", b->lightPos, "light centre x,y,z (default: the scene's)");
    pr->add_option("--frames", b->frames, "frames to time (best is reported)")->check(CLI::PositiveNumber);
    pr->add_option("--exposure", b->exposure, "exposure in stops for PNG output");
    pr->callback([b, &exitCode] { exitCode = runPredict(*b); });

    auto c = std::make_shared<Args>();
    CLI::App* sw = app.add_subcommand("sweep", "Error against wall time while one setting varies");
    commonOptions(sw, *c);
    sw->add_option("--what", c->what, "what varies")->required()->check(CLI::IsMember({"spp", "grid", "hidden", "trainer"}));
    sw->add_option("--values", c->values, "comma-separated settings (spp: 1,4,16; grid: 3x100,4x200; hidden: 10,20-10; trainer: lm,adam)");
    sw->add_option("--reference-spp", c->referenceSpp, "reference spp (default 1024 for spp, 256 otherwise)")->check(CLI::PositiveNumber);
    c->dataSpp = -1;
    sw->add_option("--grid", c->grid, "data: N for an NxNxN viewpoint grid")->check(CLI::PositiveNumber);
    sw->add_option("--dirs", c->dirs, "data: directions per viewpoint")->check(CLI::PositiveNumber);
    sw->add_option("--data-spp", c->dataSpp, "data: paths per record")->check(CLI::PositiveNumber);
    sw->add_option("--hidden", c->hidden, "hidden layer sizes, e.g. 20,10");
    sw->add_option("--trainer", c->trainer, "trainer")->check(CLI::IsMember({"lm", "adam"}));
    sw->add_option("--epochs", c->epochs, "maximum epochs")->check(CLI::PositiveNumber);
    sw->add_option("--seed", c->seed, "seed of the evaluation light and renders")->check(CLI::NonNegativeNumber);
    sw->callback([c, &exitCode] { exitCode = runSweepCommand(*c); });

    auto d = std::make_shared<Args>();
    CLI::App* pl = app.add_subcommand("pipeline", "Ground truth, data, training and evaluation in one run");
    commonOptions(pl, *d);
    pl->add_flag("--quick", d->quick, "small grid, directions, spp and epochs (about a minute on 2 cores)");
    pl->add_option("--spp", d->spp, "ground-truth samples per pixel")->check(CLI::PositiveNumber);
    pl->add_option("--held-out", d->heldOut, "held-out light positions to evaluate")->check(CLI::PositiveNumber);
    pl->add_option("--grid", d->grid, "data: N for an NxNxN viewpoint grid")->check(CLI::PositiveNumber);
    pl->add_option("--dirs", d->dirs, "data: directions per viewpoint")->check(CLI::PositiveNumber);
    pl->add_option("--data-spp", d->dataSpp, "data: paths per record")->check(CLI::PositiveNumber);
    pl->add_option("--hidden", d->hidden, "hidden layer sizes, e.g. 20,10");
    pl->add_option("--trainer", d->trainer, "trainer")->check(CLI::IsMember({"lm", "adam"}));
    pl->add_option("--epochs", d->epochs, "maximum epochs")->check(CLI::PositiveNumber);
    pl->add_option("--seed", d->seed, "seed of the held-out light positions")->check(CLI::NonNegativeNumber);
    pl->callback([d, &exitCode] { exitCode = runPipeline(*d); });
}

}  // namespace rrf::cli
