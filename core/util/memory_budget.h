#pragma once
/// Memory estimates checked before large allocations (image buffers, training records, OBJ files,
/// decoded images): a request the machine cannot satisfy is refused up front with the estimate in
/// the message, instead of ending in std::bad_alloc or the kernel's out-of-memory kill halfway
/// through a run.
///
/// What "available" means: the smallest of
///  - the kernel's MemAvailable (/proc/meminfo: memory obtainable without swapping);
///  - the room left under the memory limit of the process's cgroup and of each cgroup above it
///    (cgroup v2 `memory.max`, "max" = no limit; cgroup v1 `memory.limit_in_bytes`), found through
///    /proc/self/cgroup. A container or a Slurm job is usually limited there, not by MemAvailable,
///    and exceeding it gets the process OOM-killed. Room = limit − (usage − inactive file cache):
///    the kernel reclaims inactive page cache before it kills, as MemAvailable counts it too;
///  - the process's address-space and data limits (RLIMIT_AS, RLIMIT_DATA, e.g. `ulimit -v`).
/// The files are read below a root directory ("" = the real /proc and /sys), so tests and fuzz
/// targets can give the budget files of their own: setMemoryInfoRoot(), or the environment
/// variable RRF_MEMORY_INFO_ROOT read at the first query (for tests that run the `rrf` program).

#include <cstdint>
#include <string>

namespace rrf {

/// Bytes this process may still allocate (see the file comment), from the files under the root set
/// by setMemoryInfoRoot (default: $RRF_MEMORY_INFO_ROOT, else the real files). UINT64_MAX when
/// none of the figures is known.
uint64_t availableMemoryBytes();

/// The same from the files below `root` ("" = the real ones), and the process's rlimits.
uint64_t availableMemoryBytes(const std::string& root);

/// Room under the memory limits of the process's cgroups as read below `root` (the smallest over
/// its cgroup and the ones above it, v2 and v1); UINT64_MAX when no limit is set or none can be read.
uint64_t cgroupMemoryRoomBytes(const std::string& root);

/// Makes availableMemoryBytes() read below `root` from now on (thread-safe).
void setMemoryInfoRoot(const std::string& root);

/// "1.5 GiB", "640 MiB", "12 KiB", "100 bytes".
std::string formatBytes(uint64_t bytes);

/// "" when `estimate` ≤ `available`; otherwise "needs about <estimate> (<what>), but only
/// <available> of memory is available".
std::string memoryShortfall(uint64_t estimate, uint64_t available, const std::string& what);

/// Throws InputError(file, where, memoryShortfall(...)) when `estimate` exceeds
/// availableMemoryBytes(). `what` says what the estimate counts ("2000 × 2000 pixels × 328 bytes").
void requireMemory(uint64_t estimate, const std::string& what, const std::string& file, const std::string& where);

/// Throws InputError(file, "", ...) when decoding a `width` x `height` image needs more memory than is
/// available: `decoderBytesPerPixel` for the decoder's own planes plus the 12 bytes per pixel of the
/// RGB float Image. Image headers state sizes that compressed data need not back (a PNG or EXR of a
/// few bytes can declare 16384 x 16384 pixels, which tinyexr and stb_image allocate before they
/// read any data), so the readers check the header's size first.
void requireDecodeMemory(int64_t width, int64_t height, int64_t decoderBytesPerPixel, const std::string& file);

/// a × b × c saturating at UINT64_MAX instead of wrapping (estimates of absurd requests stay absurd).
uint64_t saturatingProduct(uint64_t a, uint64_t b, uint64_t c = 1);

}  // namespace rrf
