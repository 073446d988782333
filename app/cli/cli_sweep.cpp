// `rrf sweep`: error against wall time while one setting varies (core/pipeline/sweep.h), written as CSV,
// JSON and a table. Under an MPI launcher the ranks share the sweep's tasks and rank 0 writes the
// files of the single-process run (docs/cluster.md).
#include <algorithm>
#include <cstdio>
#include <iterator>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "app/cli/cli_common.h"
#include "app/cli/cli_evaluation.h"
#include "core/pipeline/run_recording.h"
#include "app/cli/cli_flags.h"
#include "app/cli/commands.h"
#include "app/cli/cli_ranks.h"
#include "app/mpi/gather_parts.h"
#include "app/mpi/ranks.h"
#include "core/data/record_layout.h"
#include "core/pipeline/sweep.h"
#include "core/pipeline/sweep_file.h"
#include "core/pipeline/sweep_parts.h"
#include "core/nn/training_split.h"
#include "core/pipeline/time_estimate.h"
#include "core/project/project.h"
#include "core/project/project_file.h"
#include "core/render/render_outputs.h"
#include "core/util/byte_stream.h"
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

/// The estimated seconds of each task of a checked sweep with `threads` threads, the cost the ranks'
/// assignment balances (core/pipeline/time_estimate.h, from the settings alone): a path-tracer series
/// its largest spp × pixels at the reference machine's path rate; a point its training (the low end
/// of estimateTraining's range, root networks for their max epochs, on the records its data holds at
/// most: the high end assumes every kd-tree level splits, which the default goal rarely lets happen)
/// plus, where it makes its own data, the midpoint of estimateGenerate's. Epochs cut short by the
/// error goal, kd-tree growth and the encodings' cost are not modelled; the prediction is small beside
/// training and left out.
std::vector<double> sweepTaskSeconds(const Scene& scene, const SweepOptions& o, int threads) {
    const PathRate rate = PathRate::of(0, threads);
    const int inputs = RecordLayout::forScene(scene).inputCount(), objects = int(scene.objects.size());
    auto mid = [](const StageEstimate& e) { return 0.5 * (e.low + e.high); };
    std::vector<double> seconds;
    for (const SweepTask& t : sweepTasks(o)) {
        if (t.series) {
            seconds.push_back(double(o.width) * double(o.height) * double(t.maxSpp) / rate.samplesPerSecond);
            continue;
        }
        double s = estimateTraining(t.training, expectedRecords(t.sampling), objects, inputs, threads).low;
        if (t.newData) s += mid(estimateGenerate(t.sampling, rate));
        seconds.push_back(s);
    }
    return seconds;
}

/// The estimated seconds of each task (sweepTaskSeconds) as rank 0 computes them with its `threads`,
/// sent to every rank: a rank's thread count (--threads, else its node's cores) scales the estimate,
/// so ranks on unlike nodes computing apart would assign the tasks differently, and the join would
/// then miss some. The bits of the doubles travel, so every rank assigns the same.
std::vector<double> rankTaskSeconds(const Scene& scene, const SweepOptions& o, const mpi::Ranks& ranks, int threads) {
    std::string sent;
    if (ranks.isRoot()) {
        ByteWriter out;
        for (double s : sweepTaskSeconds(scene, o, threads)) out.f64(s);
        sent = out.take();
    }
    ranks.broadcast(sent);
    std::vector<double> seconds(sent.size() / sizeof(double));
    ByteReader in(sent, "task estimates from rank 0");
    for (double& s : seconds) s = in.f64();
    return seconds;
}

/// The sweep of an MPI job of more than one rank: the reference is rendered split by rows
/// (renderOnRanks) at a fixed spp or obtained from the store by rank 0, and rank 0 sends it to every
/// rank; a network sweep's shared dataset is generated split by cells, joined on rank 0 and sent to
/// every rank; the tasks go to the ranks longest first by estimated seconds
/// (rankTaskSeconds, assignLongestFirst), each rank runs its own with all its threads, and rank 0
/// joins the parts into the single-process result. The other ranks return an empty result but for
/// `cancelled`, which says whether any rank was interrupted.
SweepResult sweepOnRanks(const Scene& scene, const SweepOptions& o, const mpi::Ranks& ranks, int threads) {
    std::string bytes;
    if (!o.store) {
        // A fixed-spp reference: each rank renders its interleaved rows and rank 0 joins them into the
        // single-process render, bit for bit (renderOnRanks stops the job on Ctrl-C).
        const RenderOptions ro = sweepReferenceOptions(o);
        if (ranks.isRoot() && o.log)
            o.log("reference: " + std::to_string(ro.spp) + " spp at " + std::to_string(ro.width) + "x" + std::to_string(ro.height));
        const Reference reference = renderOnRanks(scene, sweepLightPosition(scene, o), ro, "reference", ranks);
        if (ranks.isRoot()) bytes = encodeReference(reference);
    } else if (ranks.isRoot()) {
        // From the store: one entry, converged by rank 0 alone (the target is checked on the whole image).
        const Reference reference = obtainSweepReference(scene, o);
        if (reference.cancelled || (o.cancel && o.cancel->load())) {
            std::fprintf(stderr, "%s: sweep cancelled while obtaining the reference\n", ranks.name().c_str());
            mpi::stopJobOnError(130);
        }
        bytes = encodeReference(reference);
    }
    ranks.broadcast(bytes);
    Reference reference = decodeReference(bytes, "the reference from rank 0");
    std::string().swap(bytes);
    std::shared_ptr<const GeneratedData> data;
    if (sweepSharesData(o)) data = std::make_shared<const GeneratedData>(generateOnAllRanks(DataGenerator(scene, o.sampling), ranks));
    const SweepInputs inputs = sweepInputs(scene, o, std::move(reference), std::move(data));

    const std::vector<SweepTask> tasks = sweepTasks(o);
    const std::vector<double> seconds = rankTaskSeconds(scene, o, ranks, threads);
    std::vector<uint64_t> costs;
    // Microseconds: integers for the rule, clamped so that an absurd estimate still converts (a
    // double beyond uint64_t's range would be undefined behaviour); beyond 2^62 µs the order of
    // tasks no longer matters in practice.
    for (double s : seconds) costs.push_back(uint64_t(std::clamp(s * 1e6, 0.0, 4.0e18)));
    const std::vector<int> rankOf = assignLongestFirst(costs, ranks.size());
    std::vector<int> mine;
    std::string points, series;
    double own = 0, total = 0;
    for (size_t t = 0; t < tasks.size(); ++t) {
        total += seconds[t];
        if (rankOf[t] != ranks.rank()) continue;
        mine.push_back(int(t));
        own += seconds[t];
        if (tasks[t].series) series = o.what == "spp" ? "the spp series" : "the path tracer's series";
        else points += (points.empty() ? "points " : ", ") + std::to_string(t) + " (" + tasks[t].label + ")";
    }
    const std::string share = points + (!points.empty() && !series.empty() ? " and " : "") + series;
    std::printf("%s: sweep %s: %.1f%% of the estimated %.3g s (longest first by estimated seconds)\n", ranks.name().c_str(),
                share.empty() ? "nothing" : share.c_str(), total > 0 ? 100.0 * own / total : 0.0, total);
    std::fflush(stdout);
    const Stopwatch clock;
    const double cpuStart = processCpuSeconds();
    const SweepPart part = runSweepTasks(scene, o, inputs, mine);
    char summary[160];
    std::snprintf(summary, sizeof summary, "ran %zu sweep task(s) in %.2f s (%.2f s CPU)", mine.size(), clock.seconds(),
                  processCpuSeconds() - cpuStart);
    mpi::GatheredParts<SweepPart> gathered = mpi::gatherParts<SweepPart>(ranks, summary, encodeSweepPart(part), decodeSweepPart);
    SweepResult r;
    if (ranks.isRoot()) {
        r = joinSweepParts(scene, o, inputs, std::move(gathered.parts));
        std::printf("rank 0 waited %.2f s for the other ranks, then gathered and joined %d parts in %.2f s\n",
                    gathered.waitedSeconds, ranks.size(), gathered.joinClock.seconds());
    }
    // Whether any rank was interrupted, known on rank 0 from the parts: every rank's exit status says it.
    std::string cancelled = r.cancelled ? "1" : "0";
    ranks.broadcast(cancelled);
    r.cancelled = cancelled == "1";
    return r;
}

int runSweepCommand(const SweepArgs& a) {
    const mpi::Ranks& ranks = mpi::ranks();
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
    // In an MPI job every rank logs its own tasks, each line under its name.
    const std::string who = ranks.size() > 1 ? ranks.name() + ": " : "";
    o.log = [who](const std::string& m) {
        std::printf("  %s%s\n", who.c_str(), m.c_str());
        std::fflush(stdout);
    };
    if (ranks.isRoot())
        std::printf("rrf sweep %s: %s, %dx%d; %s\n", a.what.c_str(), a.input.c_str(), o.width, o.height,
                    describeExperiment(o.sampling, o.training).c_str());
    std::fflush(stdout);
    Stopwatch clock;
    const SweepResult r = ranks.size() == 1 ? runSweep(p.scene, o)
                                            : sweepOnRanks(p.scene, checkedSweepOptions(p.scene, o), ranks,
                                                           a.threads > 0 ? a.threads : int(std::thread::hardware_concurrency()));
    if (!ranks.isRoot()) return r.cancelled ? 130 : 0;
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
                    "hash_grid; ensemble (as --ensemble): 1 2 4 (default: a small series of each)")
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
