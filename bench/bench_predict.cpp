// bench_predict: CPU prediction per 256×256 frame of the Cornell box (G-buffer and network
// inference separately, 1 and 2 threads) and, in the same run, the path-traced ground truth of the
// same frame at 64 spp, so that the speed-up of prediction over path tracing is a measured ratio.
//
//   bench_predict [--quick] [--project path/to/project.json] [--hidden 20,10]
//
// The networks are the default architecture (20-10 tanh, "separate": a direct and an indirect net
// per object) with Nguyen–Widrow initial weights: inference costs the same for any weights, so no
// training is needed. Prediction figures are the fastest of several frames (the machine is shared);
// the path tracer is timed once per thread count (seconds, not milliseconds, of work). At 2 threads
// a second table gives the path tracer's time to the errors the presets reach (--errors; from the
// render's own noise, which falls as 1/sqrt(spp)) against one frame with the project's prediction
// settings: prediction against the path tracer at equal error (issue 28 item 5). Also shown:
// exact direct light (prediction "direct": "exact", core/predict/exact_direct.h) at 16 samples per
// pixel, and a second table at 128x128 with 16 and 64 samples: time per frame and the error of the
// direct image against a converged path-traced direct image (max depth 1, 1024 spp; --quick 256),
// relative RMSE over the footprint-kept pixels, raw and with the reference's own noise removed.
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "bench/bench_args.h"
#include "core/eval/evaluation.h"
#include "core/eval/reference_noise.h"
#include "core/predict/footprint_mask.h"
#include "core/pipeline/experiment.h"
#include "core/nn/network_settings.h"
#include "core/predict/predictor.h"
#include "core/project/project.h"
#include "core/project/project_file.h"
#include "core/util/stopwatch.h"

using namespace rrf;

namespace bench_predict {

ModelSet randomModels(const Scene& scene, const std::vector<int>& hidden) {
    const RecordLayout layout = RecordLayout::forScene(scene);
    ModelSet set;
    set.inputLayout = layout.inputs;
    for (const Object& o : scene.objects) {
        ObjectNetworks n;
        n.objectId = o.id;
        n.name = o.name;
        for (const char* target : {"direct", "indirect"}) {
            NetworkModel m;
            m.arch.inputs = layout.inputCount();
            m.arch.hidden = hidden;
            m.arch.outputs = 3;
            m.params = initialParams(m.arch, 1, uint64_t(o.id) * 2 + (target[0] == 'i'));
            m.inputScaler = MinMaxScaler::identity(m.arch.inputs);
            m.outputScaler = MinMaxScaler::identity(3);
            n.byTarget[target] = m;
        }
        set.objects.push_back(n);
    }
    return set;
}

struct FrameTimes {
    double gbuffer = 1e30, networks = 1e30, exact = 1e30;
};

FrameTimes timePrediction(const Scene& scene, const ModelSet& models, const Vec3& light, int frames) {
    FrameTimes t;
    PredictionSettings networkSettings;
    networkSettings.direct = PredictionSettings::Direct::Network;
    const Predictor pred(scene, models, networkSettings);
    PredictionSettings exactSettings;
    exactSettings.direct = PredictionSettings::Direct::Exact;
    exactSettings.directSamples = 16;
    const Predictor exact(scene, models, exactSettings);
    for (int f = 0; f < frames; ++f) {
        Stopwatch g;
        const GBuffer gb = pred.gbuffer(light, 256, 256);
        t.gbuffer = std::min(t.gbuffer, g.seconds());
        t.networks = std::min(t.networks, pred.predict(gb).inferenceSeconds);
        if (f < 3) t.exact = std::min(t.exact, exact.predict(gb).directSeconds);
    }
    return t;
}

/// Exact direct light at 128x128 against a converged direct image: ms per frame (best of `frames`) and
/// relative RMSE, for each sample count.
void exactDirectTable(const Scene& scene, const ModelSet& models, const Vec3& light, int refSpp, int frames) {
    RenderOptions ro;
    ro.width = ro.height = 128;
    ro.spp = refSpp;
    ro.samplesPerPass = refSpp;
    ro.maxDepth = 1;  // direct light only
    ro.seed = 77;
    const Reference ref = renderReference(scene, light, ro);
    std::printf("\nexact direct light, 128x128, against a %d-spp path-traced direct image (%.1f s to render):\n\n",
                refSpp, ref.seconds);
    // Light samples, not shadow rays: the shadow casters settle most pixels without any
    // (bench_direct counts the rays).
    std::printf("| light samples/pixel | ms/frame | direct relative RMSE | reference noise | corrected |\n");
    std::printf("|---|---|---|---|---|\n");
    for (int samples : {16, 64, 256}) {
        PredictionSettings s;
        s.directSamples = samples;
        const Predictor pred(scene, models, s);
        double best = 1e30;
        for (int f = 0; f < frames; ++f) {
            const GBuffer gb = pred.gbuffer(light, 128, 128);
            best = std::min(best, pred.predict(gb).directSeconds);
        }
        const Evaluation e = evaluate(pred, ref);
        const ErrorStats& d = e.term(Term::Direct).overall;
        std::printf("| %d | %.1f | %.4f | %.4f | %.4f |\n", samples, 1e3 * best, d.relativeRmse,
                    d.relativeRmseNoiseFloor, d.relativeRmseCorrected);
        std::fflush(stdout);
    }
}


/// The path tracer's time to the error a model reaches: the render's own noise (relative RMSE noise
/// floor of the global term over the footprint mask, core/eval/reference_noise.h, the figure held-out
/// errors are reported in) falls as 1/sqrt(spp), so a render of `ref.spp` samples with noise r reaches
/// noise e at spp · (r/e)² samples in ref.seconds · (r/e)². Against one prediction frame with the
/// project's own prediction settings (G-buffer, networks and its direct light), timed on the same
/// threads.
void equalErrorTable(const Project& p, const ModelSet& models, const Vec3& light, const Reference& ref,
                     const std::vector<double>& errors, int frames) {
    const Scene& scene = p.scene;
    const Predictor pred(scene, models, p.prediction);
    double frame = 1e30;
    GBuffer gb;
    for (int f = 0; f < frames; ++f) {
        Stopwatch s;
        gb = pred.gbuffer(light, ref.image(Term::Global).width, ref.image(Term::Global).height);
        pred.predict(gb);
        frame = std::min(frame, s.seconds());
    }
    const double noise = referenceNoise(ref, footprintMask(gb)).relativeRmse[int(Term::Global)];
    std::printf("\npath tracer to equal error (global relative RMSE noise over the footprint mask; %d spp gave %.4f in "
                "%.2f s), against one prediction frame with the project's prediction settings (direct: %s, %d samples):\n\n",
                ref.spp, noise, ref.seconds, p.prediction.direct == PredictionSettings::Direct::Exact ? "exact" : "network",
                p.prediction.directSamples);
    std::printf("| error | path tracer spp | path tracer s | prediction ms/frame | path tracer / prediction |\n");
    std::printf("|---|---|---|---|---|\n");
    for (double e : errors) {
        const double factor = (noise / e) * (noise / e);
        std::printf("| %.3f | %.0f | %.1f | %.1f | %.0fx |\n", e, ref.spp * factor, ref.seconds * factor, 1e3 * frame,
                    ref.seconds * factor / frame);
    }
}

int main(int argc, char** argv) {
    bool quick = false;
    std::string project;
    std::vector<int> hidden{20, 10};
    CLI::App app{"CPU prediction per 256x256 frame versus path tracing the same frame", "bench_predict"};
    app.add_flag("--quick", quick, "fewer frames, 16 spp ground truth");
    app.add_option("--project", project, bench::kProjectHelp)->type_name("FILE");
    app.add_option("--hidden", hidden, "hidden layer sizes of the networks")
        ->delimiter(',')
        ->type_name("N,N,...")
        ->check(bench::kPositive)
        ->default_str("20,10");
    std::vector<double> errors{0.04, 0.015};
    app.add_option("--errors", errors,
                   "held-out errors to reach (the default and best presets' on the Cornell box, docs/results.md)")
        ->delimiter(',')
        ->type_name("E,E,...")
        ->check(CLI::PositiveNumber)
        ->default_str("0.04,0.015");
    bench::parseArgs(app, argc, argv);
    project = bench::projectOrDefault(project, "bench_predict");
    const Project p = loadProjectOrScene(project);
    const Scene& scene = p.scene;
    const ModelSet models = randomModels(scene, hidden);
    const Vec3 light = scene.lightPosition();
    const int frames = quick ? 5 : 20, spp = quick ? 16 : 64;
    std::printf("bench_predict: %s, 256x256, networks %s (2 per object, %zu objects), ground truth %d spp\n\n",
                project.c_str(), models.objects.front().byTarget.begin()->second.arch().describe().c_str(),
                models.objects.size(), spp);
    std::printf("| threads | G-buffer ms | networks ms | prediction ms/frame | exact direct (16 spp) ms | path tracer %d spp ms | speed-up |\n",
                spp);
    std::printf("|---|---|---|---|---|---|---|\n");
    for (int threads : {1, 2}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
        const FrameTimes t = timePrediction(scene, models, light, frames);
        RenderOptions ro;
        ro.width = ro.height = 256;
        ro.spp = spp;
        ro.samplesPerPass = spp;
        const Reference ref = renderReference(scene, light, ro);
        const double predictMs = 1e3 * (t.gbuffer + t.networks);
        std::printf("| %d | %.2f | %.2f | %.2f | %.1f | %.0f | %.0fx |\n", threads, 1e3 * t.gbuffer, 1e3 * t.networks,
                    predictMs, 1e3 * t.exact, 1e3 * ref.seconds, 1e3 * ref.seconds / predictMs);
        std::fflush(stdout);
        if (threads == 2) {
            equalErrorTable(p, models, light, ref, errors, frames);
            std::printf("\n");
        }
    }
    std::printf("\nprediction = G-buffer + networks (best of %d frames); speed-up = path tracer time / prediction time.\n",
                frames);
    exactDirectTable(scene, models, light, quick ? 256 : 1024, quick ? 2 : 5);
    return 0;
}

}  // namespace bench_predict
