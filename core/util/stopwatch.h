#pragma once
/// A steady-clock stopwatch for the timings every stage prints and records.

#include <chrono>

namespace rrf {

/// Wall-clock seconds since construction (steady clock).
class Stopwatch {
public:
    Stopwatch() : start_(std::chrono::steady_clock::now()) {}
    double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

private:
    std::chrono::steady_clock::time_point start_;
};

}  // namespace rrf
