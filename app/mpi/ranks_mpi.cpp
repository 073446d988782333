// Ranks of an MPI job (built when RRF_WITH_MPI finds MPI; app/mpi/ranks.h).
#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "app/mpi/ranks.h"

namespace rrf::mpi {

namespace {
/// Largest piece of one message: MPI counts are ints, so a buffer of 2 GiB or more goes in pieces.
constexpr uint64_t kPiece = uint64_t(1) << 30;

bool mpiInitialised = false;

void checkMpi(int status, const char* what) {
    if (status != MPI_SUCCESS) {
        char text[MPI_MAX_ERROR_STRING];
        int length = 0;
        MPI_Error_string(status, text, &length);
        throw std::runtime_error(std::string("MPI ") + what + " failed: " + std::string(text, size_t(length)));
    }
}

void finalizeMpi() {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized) MPI_Finalize();
}
}  // namespace

bool mpiBuilt() { return true; }

const Ranks& ranks() {
    static const Ranks world = [] {
        if (!launchFromEnvironment().launched) return Ranks(0, 1);
        int provided = 0;
        checkMpi(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "initialisation");
        mpiInitialised = true;
        std::atexit(finalizeMpi);
        // Errors come back as codes (turned into exceptions by check), not as aborts inside MPI.
        MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
        int rank = 0, size = 1;
        MPI_Comm_rank(MPI_COMM_WORLD, &rank);
        MPI_Comm_size(MPI_COMM_WORLD, &size);
        return Ranks(rank, size);
    }();
    return world;
}

std::vector<std::string> Ranks::gather(const std::string& bytes) const {
    if (size_ == 1) return {bytes};
    // Point to point from every rank to rank 0 in rank order: a length, then the bytes in pieces.
    if (rank_ != 0) {
        uint64_t n = bytes.size();
        checkMpi(MPI_Send(&n, 1, MPI_UINT64_T, 0, 0, MPI_COMM_WORLD), "send");
        for (uint64_t at = 0; at < n; at += kPiece)
            checkMpi(MPI_Send(bytes.data() + at, int(std::min(kPiece, n - at)), MPI_BYTE, 0, 1, MPI_COMM_WORLD), "send");
        return {};
    }
    std::vector<std::string> all(static_cast<size_t>(size_));
    all[0] = bytes;
    for (int r = 1; r < size_; ++r) {
        uint64_t n = 0;
        checkMpi(MPI_Recv(&n, 1, MPI_UINT64_T, r, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "receive");
        std::string& buffer = all[size_t(r)];
        buffer.resize(size_t(n));
        for (uint64_t at = 0; at < n; at += kPiece)
            checkMpi(MPI_Recv(buffer.data() + at, int(std::min(kPiece, n - at)), MPI_BYTE, r, 1, MPI_COMM_WORLD,
                           MPI_STATUS_IGNORE),
                  "receive");
    }
    return all;
}

void Ranks::broadcast(std::string& bytes) const {
    if (size_ == 1) return;
    uint64_t n = bytes.size();
    checkMpi(MPI_Bcast(&n, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD), "broadcast");
    bytes.resize(size_t(n));
    for (uint64_t at = 0; at < n; at += kPiece)
        checkMpi(MPI_Bcast(bytes.data() + at, int(std::min(kPiece, n - at)), MPI_BYTE, 0, MPI_COMM_WORLD), "broadcast");
}

void Ranks::barrier() const {
    if (size_ > 1) checkMpi(MPI_Barrier(MPI_COMM_WORLD), "barrier");
}

void stopJobOnError(int code) {
    if (!mpiInitialised || ranks().size() == 1) return;
    std::fflush(stdout);
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, code);
}

}  // namespace rrf::mpi
