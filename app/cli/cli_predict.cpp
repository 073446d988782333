// `rrf predict`: direct, indirect and global images from the networks at one light position, with
// the time per frame (best of N frames).
#include <algorithm>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "app/cli/cli_common.h"
#include "app/cli/cli_evaluation.h"
#include "app/cli/cli_flags.h"
#include "app/cli/commands.h"
#include "core/eval/evaluation.h"
#include "core/nn/model_set.h"
#include "core/project/project.h"
#include "core/project/project_file.h"
#include "core/render/render_settings.h"
#include "core/util/stopwatch.h"

namespace rrf::cli {

namespace {
struct PredictArgs : PredictionArgs {
    std::string models;
    std::optional<Vec3> lightPos;
    int frames = 5;
    float exposure = 0.f;
};

int runPredict(const PredictArgs& a) {
    const Project p = loadProjectOrScene(a.input);
    std::vector<std::string> inputs = projectInputs(p);
    inputs.push_back(a.models);
    refuseOverwritingInputs(a.out, inputs);
    auto threads = limitThreads(a.threads);
    const ModelSet models = loadModelSet(a.models, p.scene.contentHash());
    const Predictor predictor(p.scene, models, a.prediction.applied(p.prediction));
    const RenderOptions ro = referenceOptions(p, 1, a.width, a.height);
    const Vec3 lp = a.lightPos.value_or(p.scene.lightPosition());
    if (a.lightPos) checkLightPosition(p.scene, lp);
    // The G-buffer and prediction images need less per pixel than a render; its estimate bounds them.
    requireRenderMemory(ro.width, ro.height);
    // Best of N frames: the first pays for page faults and thread start-up.
    double bestG = 1e30, bestN = 1e30, bestD = 1e30, bestGather = 1e30;
    Prediction pr;
    for (int f = 0; f < std::max(1, a.frames); ++f) {
        Stopwatch g;
        const GBuffer gb = predictor.gbuffer(lp, ro.width, ro.height);
        bestG = std::min(bestG, g.seconds());
        pr = predictor.predict(gb);
        bestN = std::min(bestN, pr.inferenceSeconds);
        bestD = std::min(bestD, pr.directSeconds);
        bestGather = std::min(bestGather, pr.gatherSeconds);
    }
    for (const std::string& f : writePredictionImages(a.out, pr, a.exposure)) std::printf("wrote %s\n", f.c_str());
    for (const std::string& why : pr.unavailableWhy) std::printf("unavailable: %s\n", why.c_str());
    if (pr.pixelsWithoutNetwork)
        std::printf("%zu visible objects have no network: %llu pixels black\n", pr.objectsWithoutNetwork.size(),
                    (unsigned long long)pr.pixelsWithoutNetwork);
    if (pr.nonFinite) std::printf("warning: %llu non-finite values kept out of the images\n", (unsigned long long)pr.nonFinite);
    const std::string gathered =
        pr.pixelsGathered ? ", glossy gather " + std::to_string(1e3 * bestGather) + " ms for " +
                                std::to_string(pr.pixelsGathered) + " pixels"
                          : std::string();
    std::printf("%dx%d, light at (%.3f, %.3f, %.3f), direct light %s: %.2f ms per frame (G-buffer %.2f ms, networks %.2f ms%s%s), "
                "best of %d\n", ro.width, ro.height, lp.x, lp.y, lp.z, predictor.settings().directName(),
                1e3 * (bestG + bestN + bestD + (pr.pixelsGathered ? bestGather : 0.0)), 1e3 * bestG, 1e3 * bestN,
                bestD > 0 ? (", exact direct " + std::to_string(1e3 * bestD) + " ms").c_str() : "", gathered.c_str(),
                std::max(1, a.frames));
    return 0;
}
}  // namespace

void addPredictCommand(CLI::App& app, int& exitCode) {
    auto a = std::make_shared<PredictArgs>();
    CLI::App* cmd = app.add_subcommand("predict", "Predict direct, indirect and global images with the networks");
    addPredictionOptions(cmd, *a);
    cmd->add_option("--models", a->models, "model directory (rrf train --out)")->required();
    addVec3Option(cmd, "--light-pos", a->lightPos, "light centre x,y,z (default: the scene's)");
    cmd->add_option("--frames", a->frames, "frames to time (best is reported)")->check(positive());
    cmd->add_option("--exposure", a->exposure, "exposure in stops for PNG output")->check(finiteNumber());
    cmd->callback([a, &exitCode] { exitCode = runPredict(*a); });
}

}  // namespace rrf::cli
