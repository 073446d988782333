#pragma once
/// A steady-clock stopwatch for the timings every stage prints and records.

#include <chrono>
#include <ctime>

namespace rrf {

/// Wall-clock seconds since construction (steady clock).
class Stopwatch {
public:
    Stopwatch() : start_(std::chrono::steady_clock::now()) {}
    double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

private:
    std::chrono::steady_clock::time_point start_;
};

/// CPU seconds (all threads, user + system) this process has used so far. On a shared machine the
/// CPU time of a piece of work says what it costs when its wall time also counts other jobs' share
/// of the cores (the MPI ranks log both, bench/bench_mpi.py compares them).
inline double processCpuSeconds() { return double(std::clock()) / double(CLOCKS_PER_SEC); }

}  // namespace rrf
