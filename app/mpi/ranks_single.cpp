// Ranks in a build without MPI (RRF_WITH_MPI=OFF or MPI not found): always one process.
#include "app/mpi/ranks.h"

namespace rrf::mpi {

bool mpiBuilt() { return false; }

const Ranks& ranks() {
    static const Ranks one(0, 1);
    return one;
}

std::vector<std::string> Ranks::gather(const std::string& bytes) const { return {bytes}; }

void Ranks::broadcast(std::string&) const {}

void Ranks::barrier() const {}

void stopJobOnError(int) {}

}  // namespace rrf::mpi
