#pragma once
/// Settings of the training-data generator (the project's "sampling" section), shared by the CLI and
/// the GUI so both generate the same data from the same project; read and written as JSON by
/// data/sampling_settings_json.h.

#include <cstdint>
#include <string>
#include <vector>

#include "core/render/render_settings.h"

namespace rrf {

/// Valid ranges of the settings, one definition for the project reader, the CLI flags, sweep values,
/// the Sampling panel and scripts (each is 1 … the bound).
constexpr int kMaxGridCells = 1000;              ///< cells per axis of "grid"
constexpr int kMaxDirections = 10000000;         ///< "directions"
constexpr int kMaxSamplesPerRecord = 1000000;    ///< "spp" (paths per record)
constexpr int kMaxSamplingDepth = 1000;          ///< "max_depth"
// Cell indices are int: the largest grid must not overflow it (1000³ = 1e9 < 2^31 − 1).
static_assert(int64_t(kMaxGridCells) * kMaxGridCells * kMaxGridCells <= INT32_MAX, "grid cell count must fit an int");

/// The initialisers are the project's defaults, the only ones: what a project file without a
/// "sampling" section, or a section without the key, gets. The grid and directions are an 8³ grid ×
/// 300 directions, 64 paths per record doubled adaptively up to max_spp: the data that lets the
/// default networks reach the default preset's held-out error (docs/results.md,
/// pipeline-cornell-default). The report's 15³ × 1200 is the paper preset (core/pipeline/presets.h).
struct SamplingSettings {
    int nx = 8, ny = 8, nz = 8;     ///< jitter grid over the scene bounds
    int directions = 300;           ///< random directions per viewpoint (N_dir)
    /// Paths per record for the direct/indirect targets: all of them when max_spp ≤ spp, otherwise
    /// the first round of the adaptive sampling below.
    int spp = 64;
    /// "max_spp": adaptive sampling (docs/design.md §8). After spp paths a record whose relative
    /// noise (core/data/record_noise.h) is above noise_target doubles its paths, until the noise is
    /// at most noise_target or max_spp paths were traced. ≤ spp: exactly spp paths per record.
    int maxSpp = 1024;
    /// "noise_target": the relative standard error a record's targets are sampled down to: the
    /// trainers' default error goal (0.05), so a record's noise is below the goal (the trainers also
    /// subtract the measured noise from their validation error). In the Cornell box the indirect
    /// term needs about the max_spp cap's paths for it (docs/results-history.md, §8).
    double noiseTarget = 0.05;
    uint64_t seed = 1;
    bool fixedLight = false;        ///< true: every record uses the scene's light position
    /// Auto: bidirectional where glossy lobes form caustics (its records reach the noise target
    /// far more often there; docs/results.md), the path tracer's NEE elsewhere.
    Estimator estimator = Estimator::Auto;
    int maxDepth = 64;

    int cellCount() const { return nx * ny * nz; }
    /// Every setting equal (what the section's JSON compares).
    bool operator==(const SamplingSettings& o) const {
        return nx == o.nx && ny == o.ny && nz == o.nz && directions == o.directions && spp == o.spp &&
               maxSpp == o.maxSpp && noiseTarget == o.noiseTarget && seed == o.seed && fixedLight == o.fixedLight &&
               estimator == o.estimator && maxDepth == o.maxDepth;
    }
    bool operator!=(const SamplingSettings& o) const { return !(*this == o); }
    bool adaptive() const { return maxSpp > spp; }
    /// The section's keys ("grid", "directions", ...), e.g. for a script step that takes them.
    static const std::vector<std::string>& keys();
};

}  // namespace rrf
