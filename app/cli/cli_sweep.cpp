// `rrf sweep`: error against wall time while one setting varies (core/eval/sweep.h), written as CSV,
// JSON and a table.
#include <cstdio>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "app/cli/cli_common.h"
#include "app/cli/cli_evaluation.h"
#include "core/project/run_recording.h"
#include "app/cli/cli_flags.h"
#include "app/cli/commands.h"
#include "core/eval/sweep.h"
#include "core/project/project.h"
#include "core/render/render_outputs.h"
#include "core/util/stopwatch.h"

namespace rrf::cli {

namespace {
struct SweepArgs : PredictionArgs {
    std::string what;
    std::vector<std::string> values;
    int referenceSpp = -1, sppCap = -1;
    double noise = -1;
    long long seed = 1;
    ExperimentFlags experiment;
};

int runSweepCommand(const SweepArgs& a) {
    const Project p = loadProjectOrScene(a.input);
    auto threads = limitThreads(a.threads);
    SweepOptions o;
    o.what = a.what;
    o.values = a.values;
    o.width = a.width > 0 ? a.width : 128;
    o.height = a.height > 0 ? a.height : 128;
    o.referenceSpp = a.referenceSpp > 0 ? a.referenceSpp : 0;
    // Without --reference-spp, the reference comes from the project's store, converged to the target.
    ReferenceStore store = projectReferenceStore(p);
    if (a.referenceSpp <= 0) o.store = &store;
    o.referenceTarget = noiseTargetFor(p, a.noise, a.sppCap);
    experimentSettings(p, a.experiment, &quickPreset(), o.sampling, o.training);
    o.prediction = a.prediction.applied(p.prediction);
    o.seed = uint64_t(a.seed);
    std::atomic<bool>& interrupted = installInterruptHandler();
    o.cancel = &interrupted;
    o.log = [](const std::string& m) {
        std::printf("  %s\n", m.c_str());
        std::fflush(stdout);
    };
    std::printf("rrf sweep %s: %s, %dx%d; %s\n", a.what.c_str(), a.input.c_str(), o.width, o.height,
                describeExperiment(o.sampling, o.training).c_str());
    std::fflush(stdout);
    Stopwatch clock;
    const SweepResult r = runSweep(p.scene, o);
    makeDirectories(a.out);
    const std::string base = outputPath(a.out, "sweep_" + a.what);
    writeReported(base + ".csv", sweepCsv(p.scene, r));
    writeReported(base + ".json", sweepJson(p.scene, r).dump(2) + "\n");
    const std::string curves = sweepCurveCsv(r);
    if (!curves.empty()) writeReported(base + "_curves.csv", curves);
    const std::string table = sweepTable(r);
    writeReported(base + ".txt", table);
    std::printf("\nlight at (%.3f, %.3f, %.3f), reference %d spp (%.1f s); error of the global image (object pixels the "
                "footprint mask keeps)\n%s",
                r.lightPosition.x, r.lightPosition.y, r.lightPosition.z, r.referenceSpp, r.referenceSeconds, table.c_str());
    std::printf("sweep took %.1f s%s\n", clock.seconds(), r.cancelled ? " (interrupted)" : "");
    return r.cancelled ? 130 : 0;
}
}  // namespace

void addSweepCommand(CLI::App& app, int& exitCode) {
    auto a = std::make_shared<SweepArgs>();
    CLI::App* cmd = app.add_subcommand("sweep", "Error against wall time while one setting varies");
    addPredictionOptions(cmd, *a);
    cmd->add_option("--what", a->what, "what varies")->required()
        ->check(CLI::IsMember(std::vector<std::string>(std::begin(kSweepKinds), std::end(kSweepKinds))));
    cmd->add_option("--values", a->values,
                    "the settings to compare, one per value, each spelled as its own flag: spp: 1 4 16; "
                    "grid (as --grid): 2,2,2 4,4,4 6,6,3; dirs (as --dirs): 50 200; hidden (as --hidden): 5 10,5 20,10; "
                    "trainer: lm adam; goal (error goal and kd-tree split goal): 0.1 0.05 0.03; leaves (most kd-tree leaves "
                    "per network): 1 4 16; record_spp (most paths per record): 64 256 1024; encoding (as --encoding): raw frequency "
                    "hash_grid (default: a small series of each)")
        ->type_name("VALUE");
    CLI::Option* fixed = cmd->add_option("--reference-spp", a->referenceSpp,
                                         "render the reference at this fixed spp: no noise target, not stored (default: "
                                         "the project's reference store, converged to the noise target)")
                             ->check(positive());
    addNoiseTargetFlags(cmd, a->noise, a->sppCap, "the reference", "the project's, 4096", false, fixed);
    addExperimentFlags(cmd, a->experiment);
    cmd->add_option("--seed", a->seed, "seed of the evaluation light and renders")->check(nonNegative());
    cmd->callback([a, &exitCode] { exitCode = runSweepCommand(*a); });
}

}  // namespace rrf::cli
