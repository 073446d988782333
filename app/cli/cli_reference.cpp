// `rrf reference`: the project's reference store (core/eval/reference_store.h) — render (or reuse,
// or continue) converged references at the scene's light, a given position or K held-out
// positions; list the stored ones; prune those of an older scene.
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/cli/cli_common.h"
#include "app/cli/cli_evaluation.h"
#include "core/pipeline/run_recording.h"
#include "app/cli/cli_flags.h"
#include "app/cli/commands.h"
#include "core/eval/held_out.h"
#include "core/project/project.h"
#include "core/project/project_file.h"

namespace rrf::cli {

namespace {
struct ReferenceArgs {
    std::string input;
    std::string estimator;
    std::optional<Vec3> lightPos;
    int heldOut = 0, sppCap = -1, threads = 0, width = -1, height = -1;
    double noise = -1;
    long long seed = 1;
    bool list = false, prune = false;
};

std::string num(double v) {
    if (!std::isfinite(v)) return "unknown";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

void listEntries(const ReferenceStore& store, uint64_t sceneHash) {
    const std::vector<StoredReference> entries = store.list(sceneHash);
    std::printf("%zu reference(s) in %s\n", entries.size(), store.dir().c_str());
    if (entries.empty()) return;
    std::printf("%-16s  %-9s  %-26s  %9s  %6s  %9s  %9s  %9s  %8s\n", "id", "state", "light", "size", "spp", "direct",
                "indirect", "global", "seconds");
    for (const StoredReference& e : entries) {
        if (!e.problem.empty()) {
            std::printf("damaged: %s\n", e.problem.c_str());
            continue;
        }
        char light[64], size[32];
        std::snprintf(light, sizeof light, "%.3f,%.3f,%.3f", e.key.lightPosition.x, e.key.lightPosition.y, e.key.lightPosition.z);
        std::snprintf(size, sizeof size, "%dx%d", e.key.width, e.key.height);
        std::printf("%-16s  %-9s  %-26s  %9s  %6d  %9s  %9s  %9s  %8.1f\n", e.key.id().c_str(),
                    e.stale ? "stale" : e.complete ? "complete" : "partial", light, size, e.spp,
                    num(e.noise.relativeRmse[int(Term::Direct)]).c_str(), num(e.noise.relativeRmse[int(Term::Indirect)]).c_str(),
                    num(e.noise.relativeRmse[int(Term::Global)]).c_str(), e.seconds);
    }
    std::printf("noise: relative RMSE noise floor per term over the footprint mask; stale: made for another version of "
                "the scene (rrf reference --prune removes it)\n");
}

int runReference(const ReferenceArgs& a) {
    Project p = loadProjectOrScene(a.input);
    applyEstimatorFlag(a.estimator, p.render.estimator);
    auto threads = limitThreads(a.threads);
    ReferenceStore store = projectReferenceStore(p);
    const uint64_t hash = p.scene.contentHash();
    if (a.prune) {
        const int removed = store.pruneStale(hash);
        std::printf("removed %d stale or damaged reference(s) from %s\n", removed, store.dir().c_str());
    }
    if (a.list) listEntries(store, hash);
    if ((a.list || a.prune) && !a.lightPos && a.heldOut == 0) return 0;
    std::vector<Vec3> lights;
    if (a.heldOut > 0) lights = heldOutLightPositions(p.scene.lightRange(), a.heldOut, uint64_t(a.seed));
    else lights = {a.lightPos.value_or(p.scene.lightPosition())};
    const NoiseTarget target = noiseTargetFor(p, a.noise, a.sppCap);
    const auto [width, height] = referenceSize(p, a.width, a.height);
    std::printf("rrf reference: %s, %zu light position(s), %dx%d, relative noise <= %g, at most %d spp, %d per pass\n",
                a.input.c_str(), lights.size(), width, height, target.relativeRmse, target.sppCap, target.sppPerPass);
    for (size_t k = 0; k < lights.size(); ++k) {
        const ReferenceKey key = ReferenceKey::of(p.scene, lights[k], width, height, p.render);
        obtainWithProgress(store, p, lights[k], width, height, target, {},
                           "reference " + std::to_string(k + 1) + "/" + std::to_string(lights.size()));
        std::printf("  -> %s (rrf evaluate --reference reads it)\n", outputPath(store.dir(), key.id()).c_str());
    }
    return 0;
}
}  // namespace

void addReferenceCommand(CLI::App& app, int& exitCode) {
    auto a = std::make_shared<ReferenceArgs>();
    CLI::App* cmd = app.add_subcommand(
        "reference", "Render, reuse or continue converged references in the project's store (<project dir>/references)");
    cmd->add_option("input", a->input, "project or scene JSON file")->required();
    CLI::Option* lp = addVec3Option(cmd, "--light-pos", a->lightPos, "light centre x,y,z (default: the scene's)");
    cmd->add_option("--held-out", a->heldOut, "the references of K held-out light positions (as rrf evaluate --held-out)")
        ->check(positive())
        ->excludes(lp);
    cmd->add_option("--seed", a->seed, "seed of the held-out light positions")->check(nonNegative());
    addNoiseTargetFlags(cmd, a->noise, a->sppCap, "each reference", "the project's, 4096", false);
    cmd->add_option("--width", a->width, "image width (default: the project's)")->check(CLI::Range(1, kMaxImageSide));
    cmd->add_option("--height", a->height, "image height (default: the project's)")->check(CLI::Range(1, kMaxImageSide));
    cmd->add_option("--threads", a->threads, "worker threads (0 = all cores)")->check(nonNegative());
    addEstimatorOption(cmd, a->estimator, "the references");
    cmd->add_flag("--list", a->list, "list the stored references (with --light-pos or --held-out: also render)");
    cmd->add_flag("--prune", a->prune, "remove the references of older versions of the scene and damaged entries");
    cmd->callback([a, &exitCode] { exitCode = runReference(*a); });
}

}  // namespace rrf::cli
