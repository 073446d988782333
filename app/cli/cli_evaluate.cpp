// `rrf evaluate`: the networks' predictions against path-traced references at the scene's light, at
// a given position, at K held-out positions, or against a saved `rrf render` output.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "app/cli/cli_common.h"
#include "app/cli/cli_evaluation.h"
#include "app/cli/cli_flags.h"
#include "app/cli/commands.h"
#include "core/eval/held_out.h"
#include "core/nn/model_set.h"
#include "core/project/project.h"
#include "core/render/render_outputs.h"

namespace rrf::cli {

namespace {
struct EvaluateArgs : PredictionArgs {
    std::string models, reference;
    std::optional<Vec3> lightPos;
    int heldOut = 0, spp = -1;
    long long seed = 1;
    float exposure = 0.f;
};

int runEvaluate(const EvaluateArgs& a) {
    const Project p = loadProjectOrScene(a.input);
    auto threads = limitThreads(a.threads);
    const ModelSet models = loadModelSet(a.models, p.scene.contentHash());
    const Predictor predictor(p.scene, models, a.prediction.applied(p.prediction));
    makeDirectories(a.out);
    std::printf("rrf evaluate: %s with %s (direct light: %s)\n", a.input.c_str(), a.models.c_str(), predictor.settings().directName());
    for (const std::string& l : predictor.describe()) std::printf("  %s\n", l.c_str());
    const RenderOptions ro = referenceOptions(p, a.spp, a.width, a.height);
    if (!a.reference.empty()) {
        const Reference ref = loadReference(a.reference);
        std::printf("reference: %s (%d spp, light at %.3f,%.3f,%.3f; noise %s)\n", a.reference.c_str(), ref.spp,
                    ref.lightPosition.x, ref.lightPosition.y, ref.lightPosition.z,
                    ref.variance(Term::Global).empty() ? "unknown: no variance images, noise floors are not known"
                                                       : "known from its variance images");
        evaluateAll(p, predictor, {ref.lightPosition}, ro, &ref, a.out, a.exposure);
        return 0;
    }
    std::vector<Vec3> lights;
    if (a.heldOut > 0) {
        lights = heldOutLightPositions(p.scene.lightRange(), a.heldOut, uint64_t(a.seed));
        std::printf("%d held-out light positions (seed %lld), references %dx%d at %d spp\n", a.heldOut, a.seed, ro.width,
                    ro.height, ro.spp);
    } else {
        lights = {a.lightPos.value_or(p.scene.lightPosition())};
    }
    evaluateAll(p, predictor, lights, ro, nullptr, a.out, a.exposure);
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
    cmd->add_option("--reference", a->reference, "use this rrf render output instead of rendering")->excludes(lp);
    cmd->add_option("--spp", a->spp, "reference samples per pixel (default: the project's)")->check(positive());
    cmd->add_option("--seed", a->seed, "seed of the held-out light positions")->check(nonNegative());
    cmd->add_option("--exposure", a->exposure, "exposure in stops for PNG output");
    cmd->callback([a, &exitCode] { exitCode = runEvaluate(*a); });
}

}  // namespace rrf::cli
