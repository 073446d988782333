#pragma once
/// Memory estimates checked before large allocations (image buffers, training records, OBJ files):
/// a request the machine cannot satisfy is refused up front with the estimate in the message,
/// instead of ending in std::bad_alloc or the kernel's out-of-memory kill halfway through a run.

#include <cstdint>
#include <string>

namespace rrf {

/// Bytes this process may still allocate: the smaller of the kernel's MemAvailable
/// (/proc/meminfo, memory obtainable without swapping) and the process's address-space and data
/// limits (RLIMIT_AS, RLIMIT_DATA, e.g. `ulimit -v`). UINT64_MAX when none of them is known.
uint64_t availableMemoryBytes();

/// "1.5 GiB", "640 MiB", "12 KiB", "100 bytes".
std::string formatBytes(uint64_t bytes);

/// "" when `estimate` ≤ `available`; otherwise "needs about <estimate> (<what>), but only
/// <available> of memory is available".
std::string memoryShortfall(uint64_t estimate, uint64_t available, const std::string& what);

/// Throws InputError(file, where, memoryShortfall(...)) when `estimate` exceeds
/// availableMemoryBytes(). `what` says what the estimate counts ("2000 × 2000 pixels × 328 bytes").
void requireMemory(uint64_t estimate, const std::string& what, const std::string& file, const std::string& where);

/// a × b × c saturating at UINT64_MAX instead of wrapping (estimates of absurd requests stay absurd).
uint64_t saturatingProduct(uint64_t a, uint64_t b, uint64_t c = 1);

}  // namespace rrf
