#pragma once
/// The end of every rank's share of a split command (`rrf generate`, `rrf train`; docs/cluster.md):
/// each rank logs what it did, waits for the others, and sends its part to rank 0, which decodes the
/// parts in rank order for the command to join.

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "app/mpi/ranks.h"
#include "core/util/stopwatch.h"

namespace rrf::mpi {

/// What rank 0 holds once every rank has sent its part.
template <class Part>
struct GatheredParts {
    std::vector<Part> parts;    ///< one per rank, in rank order; empty on the other ranks
    double waitedSeconds = 0;   ///< time spent at the barrier waiting for the slowest rank
    Stopwatch joinClock;        ///< started when the transfer began: transfer, decode and the caller's join
};

/// Logs "<rank k/n>: <summary>", waits at a barrier, then sends `bytes` to rank 0, which turns each
/// rank's bytes into a Part with `decode(bytes, rank name)` (the name for its error messages),
/// freeing the bytes as it goes. The barrier separates waiting for the slowest rank from the
/// transfer and join in rank 0's log (bench/bench_mpi.py reads the latter). Collective: every rank
/// calls it.
template <class Part, class Decode>
GatheredParts<Part> gatherParts(const Ranks& ranks, const std::string& summary, std::string bytes, Decode decode) {
    std::printf("%s: %s\n", ranks.name().c_str(), summary.c_str());
    std::fflush(stdout);
    GatheredParts<Part> gathered;
    const Stopwatch waitClock;
    ranks.barrier();
    gathered.waitedSeconds = waitClock.seconds();
    gathered.joinClock = Stopwatch();
    std::vector<std::string> all = ranks.gather(bytes);
    std::string().swap(bytes);
    for (size_t r = 0; r < all.size(); ++r) {
        gathered.parts.push_back(decode(all[r], Ranks(int(r), ranks.size()).name()));
        std::string().swap(all[r]);
    }
    return gathered;
}

}  // namespace rrf::mpi
