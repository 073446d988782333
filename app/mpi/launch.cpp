// The launcher's rank and size from the environment, and Ranks::name (shared by both builds).
#include <cstdlib>
#include <string>
#include <utility>

#include "app/mpi/ranks.h"

namespace rrf::mpi {

namespace {
/// The integer value of environment variable `name`, or -1 when unset or not a number.
int envInt(const char* name) {
    const char* v = std::getenv(name);
    if (!v || !*v) return -1;
    char* end = nullptr;
    const long n = std::strtol(v, &end, 10);
    return *end == '\0' && n >= 0 && n < (1L << 30) ? int(n) : -1;
}
}  // namespace

Launch launchFromEnvironment() {
    // Open MPI's mpirun, then PMIx (srun --mpi=pmix, prterun), then PMI-1/2 (MPICH's hydra, srun --mpi=pmi2).
    const std::pair<const char*, const char*> vars[] = {
        {"OMPI_COMM_WORLD_RANK", "OMPI_COMM_WORLD_SIZE"}, {"PMIX_RANK", "PMIX_SIZE"}, {"PMI_RANK", "PMI_SIZE"}};
    for (const auto& [rankVar, sizeVar] : vars) {
        const int rank = envInt(rankVar);
        if (rank < 0) continue;
        Launch l;
        l.launched = true;
        l.rank = rank;
        // PMIx announces no size in the environment: Slurm's does (SLURM_NTASKS); otherwise MPI will tell.
        const int size = envInt(sizeVar) > 0 ? envInt(sizeVar) : envInt("SLURM_NTASKS");
        l.size = size > rank ? size : rank + 1;
        return l;
    }
    return {};
}

std::string Ranks::name() const { return "rank " + std::to_string(rank_) + "/" + std::to_string(size_); }

}  // namespace rrf::mpi
