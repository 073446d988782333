// `rrf generate`: training records (jitter grid × directions × light positions) for a project's
// scene, whole or as shard k of n; under an MPI launcher (`mpirun -n N rrf generate`) the ranks share
// the cells and rank 0 writes the dataset of the single-process run (docs/cluster.md).
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "app/cli/cli_common.h"
#include "core/pipeline/generate_stage.h"
#include "app/cli/cli_ranks.h"
#include "app/cli/cli_flags.h"
#include "app/cli/commands.h"
#include "app/mpi/ranks.h"
#include "core/data/data_generator.h"
#include "core/data/dataset_file.h"
#include "core/project/project.h"
#include "core/project/project_file.h"
#include "core/util/error.h"
#include "core/util/stopwatch.h"

namespace rrf::cli {

namespace {
struct GenerateArgs {
    std::string input, out;
    std::vector<int> shard{0, 1};  ///< k of n; checkShard refuses all but 0 <= k < n
    int threads = 0;
    SettingFlags<SamplingSettings> sampling;
};

int runGenerate(const GenerateArgs& a) {
    const Project project = loadProjectOrScene(a.input);
    refuseOverwritingInputs(a.out, projectInputs(project));
    const SamplingSettings s = a.sampling.applied(project.samplingOrDefault());
    const int k = a.shard[0], n = a.shard[1];
    checkShard(k, n);
    const mpi::Ranks& ranks = mpi::ranks();
    if (ranks.size() > 1 && n > 1)
        throw InputError("command line", "--shard",
                         "cannot be combined with an MPI job (" + std::to_string(ranks.size()) +
                             " ranks): the ranks split the cells themselves; use --shard in single-process runs");
    auto threads = limitThreads(a.threads);

    DataGenerator gen(project.scene, s);
    if (ranks.isRoot()) {
        const std::string split = ranks.size() > 1 ? std::to_string(ranks.size()) + " MPI ranks"
                                                   : "shard " + std::to_string(k) + "/" + std::to_string(n);
        std::printf("rrf generate: %s, grid %dx%dx%d, %d directions, %d spp, seed %llu, %s\n", a.input.c_str(), s.nx,
                    s.ny, s.nz, s.directions, s.spp, (unsigned long long)s.seed, split.c_str());
    }
    if (s.adaptive() && ranks.isRoot())
        std::printf("adaptive paths per record: %d, doubling up to %d until the relative noise is <= %g\n", s.spp,
                    s.maxSpp, s.noiseTarget);
    if (ranks.isRoot()) {
        std::printf("inputs (%d): ", gen.layout().inputCount());
        for (const std::string& name : gen.layout().inputs) std::printf("%s ", name.c_str());
        std::printf("\n");
    }
    std::fflush(stdout);
    const double cpuStart = processCpuSeconds();
    GenerateRequest request;
    request.datasetPath = a.out;
    request.generate = [&](const DataGenerator& g) { return generateOnRanks(g, ranks, k, n); };
    request.writes = ranks.isRoot();
    const GenerateOutcome outcome = generateStage(gen, request, {});
    const GeneratedData& data = outcome.data;
    if (data.cancelled) {
        std::fprintf(stderr, "generate: cancelled, no dataset written (%s untouched)\n", a.out.c_str());
        return 130;
    }
    if (!ranks.isRoot()) return 0;
    const GeneratorStats& st = data.stats;
    std::printf("%llu records in %.2f s (%.2f s CPU%s): %srecords/s, %spath samples/s, %srays/s\n",
                (unsigned long long)st.records, data.seconds, processCpuSeconds() - cpuStart,
                ranks.size() > 1 ? " of rank 0" : "", humanCount(double(st.records) / data.seconds).c_str(),
                humanCount(double(st.paths) / data.seconds).c_str(),
                humanCount(double(st.rays + st.shadowRays) / data.seconds).c_str());
    std::printf("cells: %llu in shard, %llu dropped inside objects, %llu dropped outside the scene, %llu dropped behind "
                "a surface\n",
                (unsigned long long)st.cells(), (unsigned long long)st.cellsDroppedInsideObject,
                (unsigned long long)st.cellsDroppedOutsideScene, (unsigned long long)st.cellsDroppedBehindSurface);
    std::printf("paths: %.1f per record; %llu records at max_spp with noise above the target\n",
                st.records ? double(st.paths) / double(st.records) : 0.0, (unsigned long long)st.recordsAtSppCap);
    std::printf("rays escaped: %llu, rays hitting an emitter: %llu, NaN/Inf samples dropped: %llu\n",
                (unsigned long long)st.raysEscaped, (unsigned long long)st.raysHitEmitter,
                (unsigned long long)st.nonFiniteSamplesDropped);
    for (size_t i = 0; i < st.recordsPerObject.size(); ++i) {
        const NoiseSummary& noise = st.noisePerObject[i];
        std::printf("  object %zu %-12s %10llu records, relative noise median %.4g, p90 %.4g\n", i,
                    project.scene.objects[i].name.c_str(), (unsigned long long)st.recordsPerObject[i], noise.median,
                    noise.p90);
    }
    std::printf("wrote %s\n", a.out.c_str());
    return 0;
}
}  // namespace

void addGenerateCommand(CLI::App& app, int& exitCode) {
    auto a = std::make_shared<GenerateArgs>();
    CLI::App* cmd = app.add_subcommand("generate", "Generate training records (jitter grid x directions x lights)");
    cmd->add_option("input", a->input, "project or scene JSON file")->required();
    cmd->add_option("--out", a->out, "output dataset file (.rrfd)")->required();
    addSamplingFlags(cmd, a->sampling, "--spp");
    a->sampling.add<long long>(cmd, "--seed", "random seed", [](SamplingSettings& s, const long long& seed) { s.seed = uint64_t(seed); })
        ->check(nonNegative());
    a->sampling.add<int>(cmd, "--max-spp", "adaptive sampling: most paths per record (<= --spp: fixed paths per record)",
                         [](SamplingSettings& s, const int& n) { s.maxSpp = n; })
        ->check(CLI::Range(1, kMaxSamplesPerRecord));
    a->sampling.add<double>(cmd, "--noise-target", "adaptive sampling: relative noise a record is sampled down to",
                            [](SamplingSettings& s, const double& t) { s.noiseTarget = t; })
        ->check(finiteNumber())
        ->check(CLI::PositiveNumber);
    cmd->add_option("--threads", a->threads, "worker threads (0 = all cores)")->check(nonNegative());
    addCheckedOption<std::vector<int>>(
        cmd, "--shard", "generate part k of n (e.g. 0/4); merge the parts with `rrf merge`",
        [a](const std::vector<int>& kn) { a->shard = kn; }, exactly<int>(2, "k/n"))
        ->delimiter('/')
        ->allow_extra_args(false)
        ->type_name("K/N");
    cmd->callback([a, &exitCode] { exitCode = runGenerate(*a); });
}

}  // namespace rrf::cli
