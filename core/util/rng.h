#pragma once
/// Counter-based random numbers.
///
/// Every random number in RRF Workbench is a pure function of (seed, stream, sample, dimension):
/// `stream` is a pixel index or a record index, `sample` the sample index within it. No generator
/// state is shared between threads, so images and datasets are bit-identical for any thread count
/// and any sharding. (The seed report seeded std::mt19937 with time ^ thread id, which is neither
/// reproducible nor guaranteed independent.)
///
/// The generator is SplitMix64 run from a key that is itself a hash of (seed, stream, sample):
/// output n is mix64(key + (n+1)·γ), with γ the 64-bit golden ratio. SplitMix64 passes BigCrush
/// and its outputs for distinct keys are decorrelated by the avalanche of mix64.

#include <cstdint>

namespace rrf {

/// Stafford's "Mix13" finaliser (as used by SplitMix64): a bijection with full avalanche.
constexpr uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

class Rng {
public:
    static constexpr uint64_t kGamma = 0x9E3779B97F4A7C15ULL;

    /// Stream for (seed, stream, sample). Distinct triples give independent-looking sequences.
    constexpr Rng(uint64_t seed, uint64_t stream, uint64_t sample = 0) : state_(keyed(streamKey(seed, stream), sample)) {}

    /// The part of the key that depends on (seed, stream) only, so that a loop over one stream's
    /// samples hashes it once: Rng::ofStream(streamKey(seed, stream), sample) == Rng(seed, stream, sample).
    static constexpr uint64_t streamKey(uint64_t seed, uint64_t stream) {
        return mix64(mix64(seed + kGamma) ^ (stream + 0x632BE59BD9B4E019ULL));
    }
    static constexpr Rng ofStream(uint64_t key, uint64_t sample) { return Rng(keyed(key, sample)); }

    /// The counter itself, and the Rng at a counter: for code that draws a path's numbers in SIMD
    /// lanes (render/path_lanes.h) and hands the path back. Rng::ofState(r.state()) == r.
    constexpr uint64_t state() const { return state_; }
    static constexpr Rng ofState(uint64_t state) { return Rng(state); }

    constexpr uint64_t nextU64() {
        state_ += kGamma;
        return mix64(state_);
    }
    constexpr uint32_t nextU32() { return uint32_t(nextU64() >> 32); }

    /// Uniform float in [0, 1): 24 random mantissa bits, never returns 1.
    constexpr float uniform() { return float(nextU32() >> 8) * 0x1.0p-24f; }
    /// Uniform double in [0, 1): 53 random bits.
    constexpr double uniformDouble() { return double(nextU64() >> 11) * 0x1.0p-53; }
    /// Uniform integer in [0, n) (n > 0), Lemire's multiply-shift (bias < 2^-32 · n).
    constexpr uint32_t uniformInt(uint32_t n) { return uint32_t((uint64_t(nextU32()) * n) >> 32); }

private:
    explicit constexpr Rng(uint64_t state) : state_(state) {}
    static constexpr uint64_t keyed(uint64_t key, uint64_t sample) { return mix64(key ^ (sample + 0x8CB92BA72F3D8DD7ULL)); }
    uint64_t state_;
};

}  // namespace rrf
