#pragma once
/// The processes one `rrf` command runs on (docs/cluster.md): the ranks of an MPI job when rrf was
/// built with MPI (CMake option RRF_WITH_MPI) and started by an MPI launcher (mpirun, srun), else one
/// process. The commands that split their work (generate, train) ask for ranks(); everything that
/// touches MPI lives behind this header (app/mpi/ranks_mpi.cpp, or app/mpi/ranks_single.cpp in a
/// build without MPI), so core/ and the rest of the CLI never include <mpi.h>.
///
/// Only the calling (main) thread talks to MPI (MPI_THREAD_FUNNELED): the commands' worker threads
/// compute, the main thread sends and receives before and after.

#include <string>
#include <vector>

namespace rrf::mpi {

/// Rank and size as an MPI launcher announces them in the environment (Open MPI's
/// OMPI_COMM_WORLD_RANK/SIZE, PMIx's PMIX_RANK, PMI's PMI_RANK/PMI_SIZE, as mpirun, mpiexec and
/// Slurm's srun set them), read without starting MPI; {0, 1, false} when none is set.
struct Launch {
    int rank = 0, size = 1;
    bool launched = false;  ///< an MPI launcher started this process
};
Launch launchFromEnvironment();

/// Whether this build has MPI support (RRF_WITH_MPI found MPI at configure time).
bool mpiBuilt();

/// The processes of this command. Collective calls (gather, barrier) must be made by every rank in
/// the same order.
class Ranks {
public:
    Ranks(int rank, int size) : rank_(rank), size_(size) {}
    int rank() const { return rank_; }
    int size() const { return size_; }
    bool isRoot() const { return rank_ == 0; }
    /// "rank k/n" (k counted from 0, as MPI and `--shard k/n` count) for logs and errors.
    std::string name() const;
    /// Rank 0 receives every rank's `bytes` (index = rank, its own included); the others get an
    /// empty vector. Any size (sent in pieces below MPI's 2 GiB message limit).
    std::vector<std::string> gather(const std::string& bytes) const;
    /// Every rank receives rank 0's `bytes` (replacing its own). Any size, as gather.
    void broadcast(std::string& bytes) const;
    /// Every rank waits until all have arrived.
    void barrier() const;

private:
    int rank_, size_;
};

/// This process's ranks: MPI is initialised on the first call when this build has MPI and a
/// launcher started the process, and finalised when the program exits normally. main() makes the
/// first call before parsing the command line when a launcher started more than one process, so
/// every error on any rank can end the job (stopJobOnError).
const Ranks& ranks();

/// Ends the whole job after an error: in an MPI job of more than one rank, MPI_Abort with `code`,
/// so no other rank waits forever in a collective call; otherwise returns (the caller exits with
/// `code`). The caller prints the message first.
void stopJobOnError(int code);

}  // namespace rrf::mpi
