// The stages split across MPI ranks, shared by generate, train, evaluate, sweep and pipeline (cli_ranks.h).
#include "app/cli/cli_ranks.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>

#include "app/cli/cli_common.h"
#include "app/mpi/gather_parts.h"
#include "core/data/cell_split.h"
#include "core/data/dataset_part.h"
#include "core/nn/training_part.h"
#include "core/render/render_rows.h"
#include "core/nn/training_split.h"
#include "core/util/byte_stream.h"
#include "core/util/stopwatch.h"

namespace rrf::cli {

namespace {
/// This rank's cells of an MPI job: the grid split into contiguous ranges of near-equal cost, the
/// predicted records × spp (core/data/cell_split.h), logged with the share of the work they hold.
/// Rank 0 alone predicts the costs (first hits traced by Embree) and sends them to the others: nodes
/// with different instruction sets may see a ray graze an edge differently, and ranges computed
/// apart would then not tile the grid. The split of the same costs is exact integer arithmetic.
CellRange rankCells(const DataGenerator& gen, const mpi::Ranks& ranks) {
    const Stopwatch clock;
    std::string sent;
    if (ranks.isRoot()) {
        ByteWriter out;
        for (uint64_t cost : cellCosts(gen)) out.u64(cost);
        sent = out.take();
    }
    ranks.broadcast(sent);
    std::vector<uint64_t> costs(sent.size() / sizeof(uint64_t));
    ByteReader in(sent, "cell costs from rank 0");
    for (uint64_t& cost : costs) cost = in.u64();
    const std::vector<CellRange> ranges = splitCellsByCost(costs, ranks.size());
    const CellRange mine = ranges[size_t(ranks.rank())];
    uint64_t total = 0, own = 0;
    for (size_t c = 0; c < costs.size(); ++c) {
        total += costs[c];
        if (int(c) >= mine.begin && int(c) < mine.end) own += costs[c];
    }
    const uint64_t spp = uint64_t(gen.settings().spp);
    if (mine.size() == 0)
        std::printf("%s: no cells (%d ranks for %zu cells)\n", ranks.name().c_str(), ranks.size(), costs.size());
    else
        std::printf("%s: cells %d-%d of %zu (%llu records predicted, %.1f%% of the paths; contiguous ranges balanced by "
                    "predicted records, planned in %.2f s)\n",
                    ranks.name().c_str(), mine.begin, mine.end - 1, costs.size(), (unsigned long long)(own / spp),
                    total ? 100.0 * double(own) / double(total) : 0.0, clock.seconds());
    std::fflush(stdout);
    return mine;
}

/// This rank's objects in an MPI job and the assignment of every object (the positions of
/// trainingObjectOrder) to ranks.
struct RankShare {
    ObjectTrainingOptions options;     ///< the run's options with `objects` this rank's (in order)
    std::vector<int> rankOfPosition;   ///< rank of each object of trainingObjectOrder
};

/// Assigns the objects to the ranks by the longest-first rule on record counts and logs this
/// rank's share (core/nn/training_split.h). One rank: every object, nothing logged.
RankShare rankShare(const std::vector<ObjectSamples>& samples, const ObjectTrainingOptions& options,
                    const mpi::Ranks& ranks, const Scene& scene) {
    RankShare share{options, {}};
    if (ranks.size() == 1) return share;
    const std::vector<int> order = trainingObjectOrder(samples, options);
    const std::vector<uint64_t> costs = trainingCosts(samples, order);
    share.rankOfPosition = assignLongestFirst(costs, ranks.size());
    share.options.objects.clear();
    uint64_t total = 0, own = 0;
    std::string list;
    for (size_t p = 0; p < order.size(); ++p) {
        total += costs[p];
        if (share.rankOfPosition[p] != ranks.rank()) continue;
        share.options.objects.push_back(order[p]);
        own += costs[p];
        const std::string name = order[p] >= 0 && size_t(order[p]) < scene.objects.size() ? scene.objects[size_t(order[p])].name : "?";
        list += (list.empty() ? "" : ", ") + std::to_string(order[p]) + " " + name + " (" + std::to_string(costs[p]) + ")";
    }
    if (share.options.objects.empty())
        std::printf("%s: no objects (%d ranks for %zu objects)\n", ranks.name().c_str(), ranks.size(), order.size());
    else
        std::printf("%s: objects %s: %llu of %llu records (%.1f%%; longest first by record count)\n", ranks.name().c_str(),
                    list.c_str(), (unsigned long long)own, (unsigned long long)total,
                    total ? 100.0 * double(own) / double(total) : 0.0);
    std::fflush(stdout);
    return share;
}

}  // namespace

GeneratedData generateOnRanks(const DataGenerator& gen, const mpi::Ranks& ranks, int shardK, int shardN) {
    const CellRange cells = ranks.size() > 1 ? rankCells(gen, ranks) : CellRange{};
    GeneratorProgress progress;
    std::atomic<bool> cancel{false};
    GeneratedData data;
    const double cpuStart = processCpuSeconds();
    runWithProgress(
        "generate",
        [&] {
            data = ranks.size() > 1 ? gen.runCells(cells.begin, cells.end, ranks.rank(), ranks.size(), &cancel, &progress)
                                    : gen.run(shardK, shardN, &cancel, &progress);
        },
        [&] { return std::make_pair(progress.fraction(), std::to_string(progress.records.load()) + " records"); },
        [&] { cancel = true; });
    if (ranks.size() == 1) return data;
    if (data.cancelled) {
        std::fprintf(stderr, "%s: generate cancelled\n", ranks.name().c_str());
        mpi::stopJobOnError(130);
    }
    // Rank 0 joins the ranks' parts into the single-process run's data (core/data/dataset_part.h).
    char summary[160];
    std::snprintf(summary, sizeof summary, "%llu records in %.2f s (%.2f s CPU)", (unsigned long long)data.stats.records,
                  data.seconds, processCpuSeconds() - cpuStart);
    mpi::GatheredParts<NamedPart> gathered = mpi::gatherParts<NamedPart>(
        ranks, summary, encodeGeneratedPart(data),
        [](const std::string& bytes, const std::string& name) { return NamedPart{name, decodeGeneratedPart(bytes, name)}; });
    if (!ranks.isRoot()) return {};
    data = joinGeneratedParts(std::move(gathered.parts));
    std::printf("rank 0 waited %.2f s for the other ranks, then gathered and joined %d parts in %.2f s (slowest rank "
                "%.2f s)\n",
                gathered.waitedSeconds, ranks.size(), gathered.joinClock.seconds(), data.seconds);
    return data;
}

GeneratedData generateOnAllRanks(const DataGenerator& gen, const mpi::Ranks& ranks) {
    GeneratedData data = generateOnRanks(gen, ranks);
    if (ranks.size() == 1) return data;
    std::string bytes = ranks.isRoot() ? encodeGeneratedPart(data) : std::string();
    ranks.broadcast(bytes);
    return ranks.isRoot() ? data : decodeGeneratedPart(bytes, "the data from rank 0");
}

Reference renderOnRanks(const Scene& scene, const Vec3& lp, const RenderOptions& options, const std::string& label,
                        const mpi::Ranks& ranks) {
    if (ranks.size() == 1) return renderWithProgress(scene, lp, options, label);
    RenderOptions mine = options;
    mine.rowOffset = ranks.rank();
    mine.rowStride = ranks.size();
    const int rows = options.height > ranks.rank() ? (options.height - ranks.rank() + ranks.size() - 1) / ranks.size() : 0;
    std::printf("%s: %s rows y mod %d = %d (%d of %d rows, interleaved)\n", ranks.name().c_str(), label.c_str(), ranks.size(),
                ranks.rank(), rows, options.height);
    std::fflush(stdout);
    std::atomic<bool> cancel{false};
    std::atomic<double> progress{0.0};
    LightRender rendered;
    runWithProgress(
        label, [&] { rendered = renderAtLight(scene, lp, mine, &cancel, &progress); },
        [&] { return std::make_pair(progress.load(), std::string()); }, [&] { cancel = true; });
    if (rendered.cancelled) {
        std::fprintf(stderr, "%s: interrupted while rendering the %s\n", ranks.name().c_str(), label.c_str());
        mpi::stopJobOnError(130);
    }
    const RenderState& state = rendered.state;
    char summary[160];
    std::snprintf(summary, sizeof summary, "%s rows in %.2f s", label.c_str(), state.seconds);
    mpi::GatheredParts<std::string> gathered = mpi::gatherParts<std::string>(
        ranks, summary, encodeRenderRows(state, ranks.rank(), ranks.size()),
        [](const std::string& bytes, const std::string&) { return bytes; });
    if (!ranks.isRoot()) return {};
    std::vector<std::string> names;
    for (int r = 0; r < ranks.size(); ++r) names.push_back(mpi::Ranks(r, ranks.size()).name());
    const Reference joined = referenceOf(Renderer::snapshotOf(joinRenderRows(gathered.parts, names)), rendered.lightPosition);
    std::printf("rank 0 waited %.2f s for the other ranks, then gathered and joined %d parts in %.2f s\n", gathered.waitedSeconds,
                ranks.size(), gathered.joinClock.seconds());
    return joined;
}

ObjectTrainingOptions RankTraining::mine(const std::vector<ObjectSamples>& samples, const ObjectTrainingOptions& options) {
    clock_ = Stopwatch();
    cpuStart_ = processCpuSeconds();
    RankShare share = rankShare(samples, options, ranks_, scene_);
    rankOfPosition_ = std::move(share.rankOfPosition);
    return share.options;
}

TrainingRun RankTraining::join(TrainingRun run, const ObjectTrainingOptions& options) {
    char summary[160];
    std::snprintf(summary, sizeof summary, "trained %d networks in %.2f s (%.2f s CPU)", run.networks, run.seconds,
                  processCpuSeconds() - cpuStart_);
    mpi::GatheredParts<TrainingRun> gathered =
        mpi::gatherParts<TrainingRun>(ranks_, summary, encodeTrainingPart(run), decodeTrainingPart);
    if (!ranks_.isRoot()) return run;
    std::vector<TrainingRun>& decoded = gathered.parts;
    const double slowest = std::max_element(decoded.begin(), decoded.end(), [](const TrainingRun& x, const TrainingRun& y) {
                               return x.seconds < y.seconds;
                           })->seconds;
    run = joinTrainingParts(std::move(decoded), rankOfPosition_, networksPerObject(options));
    // The job's wall time as rank 0 saw it, from the start of training to the joined models.
    run.seconds = clock_.seconds();
    std::printf("rank 0 waited %.2f s for the other ranks, then gathered and joined %d parts in %.2f s (slowest rank "
                "%.2f s, %.2f s in all)\n",
                gathered.waitedSeconds, ranks_.size(), gathered.joinClock.seconds(), slowest, run.seconds);
    return run;
}

TrainingShare* rankTrainingOrNull(std::optional<RankTraining>& storage, const mpi::Ranks& ranks, const Scene& scene) {
    if (ranks.size() == 1) return nullptr;
    storage.emplace(ranks, scene);
    return &*storage;
}

void obtainRankReferences(const mpi::Ranks& ranks, const std::vector<Vec3>& lights, const ReferenceSource& source) {
    const std::vector<int> rankOf = assignLongestFirst(std::vector<uint64_t>(lights.size(), 1), ranks.size());
    std::string mine;
    for (size_t k = 0; k < lights.size(); ++k)
        if (rankOf[k] == ranks.rank()) mine += (mine.empty() ? "" : ", ") + std::to_string(k + 1);
    std::printf("%s: references %s of %zu (light k to rank k mod %d)\n", ranks.name().c_str(),
                mine.empty() ? "none" : mine.c_str(), lights.size(), ranks.size());
    std::fflush(stdout);
    const Stopwatch clock;
    for (size_t k = 0; k < lights.size(); ++k)
        if (rankOf[k] == ranks.rank()) source(k, lights[k]);
    std::printf("%s: references done in %.2f s\n", ranks.name().c_str(), clock.seconds());
    std::fflush(stdout);
    ranks.barrier();
}

}  // namespace rrf::cli
