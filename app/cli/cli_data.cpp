// `rrf generate`, `rrf merge`, `rrf inspect`: training data.
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "core/data/data_generator.h"
#include "core/data/dataset_file.h"
#include "core/data/dataset_summary.h"
#include "core/util/error.h"
#include "core/project/project.h"

namespace rrf::cli {

namespace {
struct GenerateArgs {
    std::string input, out, grid, shard;
    int dirs = -1, spp = -1, threads = 0;
    long long seed = -1;
};

void parseShard(const std::string& text, int& k, int& n) {
    char slash = 0;
    std::istringstream in(text);
    if (!(in >> k >> slash >> n) || slash != '/' || !in.eof() || n < 1 || k < 0 || k >= n)
        throw InputError("command line", "--shard", "expected k/n with 0 <= k < n (e.g. 0/4), got '" + text + "'");
}

int runGenerate(const GenerateArgs& a) {
    const Project project = loadProjectOrScene(a.input);
    SamplingSettings s = project.samplingOrDefault();
    if (!a.grid.empty()) {
        const Vec3 g = parseVec3(a.grid, "--grid");
        if (g.x < 1 || g.y < 1 || g.z < 1 || g.x != float(int(g.x)) || g.y != float(int(g.y)) || g.z != float(int(g.z)))
            throw InputError("command line", "--grid", "expected three positive integers nx,ny,nz, got '" + a.grid + "'");
        s.nx = int(g.x);
        s.ny = int(g.y);
        s.nz = int(g.z);
    }
    if (a.dirs > 0) s.directions = a.dirs;
    if (a.spp > 0) s.spp = a.spp;
    if (a.seed >= 0) s.seed = uint64_t(a.seed);
    int k = 0, n = 1;
    if (!a.shard.empty()) parseShard(a.shard, k, n);
    auto threads = limitThreads(a.threads);

    DataGenerator gen(project.scene, s);
    std::printf("rrf generate: %s, grid %dx%dx%d, %d directions, %d spp, seed %llu, shard %d/%d\n", a.input.c_str(), s.nx,
                s.ny, s.nz, s.directions, s.spp, (unsigned long long)s.seed, k, n);
    std::printf("inputs (%d): ", gen.layout().inputCount());
    for (const std::string& name : gen.layout().inputs) std::printf("%s ", name.c_str());
    std::printf("\n");
    std::fflush(stdout);
    GeneratorProgress progress;
    std::atomic<bool> cancel{false};
    GeneratedData data;
    runWithProgress(
        "generate", [&] { data = gen.run(k, n, &cancel, &progress); },
        [&] { return std::make_pair(progress.fraction(), std::to_string(progress.records.load()) + " records"); },
        [&] { cancel = true; });
    if (data.cancelled) {
        std::fprintf(stderr, "generate: cancelled, no dataset written (%s untouched)\n", a.out.c_str());
        return 130;
    }
    writeDataset(a.out, data.header, data.sceneHash, data.perObject);
    const GeneratorStats& st = data.stats;
    std::printf("%llu records in %.2f s: %srecords/s, %spath samples/s, %srays/s\n", (unsigned long long)st.records,
                data.seconds, humanCount(double(st.records) / data.seconds).c_str(),
                humanCount(double(st.paths) / data.seconds).c_str(),
                humanCount(double(st.rays + st.shadowRays) / data.seconds).c_str());
    std::printf("cells: %llu in shard, %llu dropped inside objects, %llu dropped outside the scene\n",
                (unsigned long long)st.cells(), (unsigned long long)st.cellsDroppedInsideObject,
                (unsigned long long)st.cellsDroppedOutsideScene);
    std::printf("rays escaped: %llu, rays hitting an emitter: %llu, NaN/Inf samples dropped: %llu\n",
                (unsigned long long)st.raysEscaped, (unsigned long long)st.raysHitEmitter,
                (unsigned long long)st.nonFiniteSamplesDropped);
    for (size_t i = 0; i < st.recordsPerObject.size(); ++i)
        std::printf("  object %zu %-12s %10llu records\n", i, project.scene.objects[i].name.c_str(),
                    (unsigned long long)st.recordsPerObject[i]);
    std::printf("wrote %s\n", a.out.c_str());
    return 0;
}
}  // namespace

void addDataCommands(CLI::App& app, int& exitCode) {
    auto g = std::make_shared<GenerateArgs>();
    CLI::App* gen = app.add_subcommand("generate", "Generate training records (jitter grid x directions x lights)");
    gen->add_option("input", g->input, "project or scene JSON file")->required();
    gen->add_option("--out", g->out, "output dataset file (.rrfd)")->required();
    gen->add_option("--grid", g->grid, "jitter grid nx,ny,nz (default: the project's, else 15,15,15)");
    gen->add_option("--dirs", g->dirs, "directions per viewpoint")->check(CLI::PositiveNumber);
    gen->add_option("--spp", g->spp, "paths per record")->check(CLI::PositiveNumber);
    gen->add_option("--seed", g->seed, "random seed")->check(CLI::NonNegativeNumber);
    gen->add_option("--threads", g->threads, "worker threads (0 = all cores)")->check(CLI::NonNegativeNumber);
    gen->add_option("--shard", g->shard, "generate part k of n (k/n); merge the parts with `rrf merge`");
    gen->callback([g, &exitCode] { exitCode = runGenerate(*g); });

    auto inputs = std::make_shared<std::vector<std::string>>();
    auto mergeOut = std::make_shared<std::string>();
    CLI::App* merge = app.add_subcommand("merge", "Merge dataset shards into one file");
    merge->add_option("inputs", *inputs, "shard files")->required();
    merge->add_option("--out", *mergeOut, "merged dataset file")->required();
    merge->callback([inputs, mergeOut, &exitCode] {
        mergeDatasets(*inputs, *mergeOut);
        std::printf("merged %zu shards into %s\n", inputs->size(), mergeOut->c_str());
        exitCode = 0;
    });

    auto file = std::make_shared<std::string>();
    CLI::App* inspect = app.add_subcommand("inspect", "Print a dataset's header, counts and per-object statistics");
    inspect->add_option("dataset", *file, "dataset file")->required();
    inspect->callback([file, &exitCode] {
        const Dataset data(*file);
        std::fputs(formatDatasetReport(data, summarizeDataset(data)).c_str(), stdout);
        exitCode = 0;
    });
}

}  // namespace rrf::cli
