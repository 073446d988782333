#pragma once
/// Training-data generator (docs/design.md §8).
///
/// For every kept viewpoint of the jitter grid, N_dir uniformly random directions are traced; the
/// first hit of each makes one record: inputs (hit point, view direction, light position, normal,
/// BRDF parameters), targets (direct and indirect RGB, each the mean of `spp` paths of the same
/// estimators as the renderer, more where adaptive sampling asks for them) and the variance of each
/// target's mean. Each record draws its own light position uniformly from the light
/// region (the light keeps its shape, orientation and radiance). Rays that escape or hit an emitter
/// are counted, not stored; samples that are NaN/Inf are dropped and counted.
///
/// Every random number is keyed by (seed, cell or record index, sample), and records are grouped by
/// object in cell order, so the output is identical for any thread count, and shard k of n (a
/// contiguous block of cells) merges with the others into the bytes of the unsharded run.

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/render/bdpt.h"
#include "core/render/path_tracer.h"
#include "core/data/generator_stats.h"
#include "core/data/record_layout.h"
#include "core/data/sampling_settings.h"
#include "core/util/json_text.h"

namespace rrf {

/// Live counters, readable from another thread while the generator runs.
struct GeneratorProgress {
    std::atomic<uint64_t> cellsDone{0};
    std::atomic<uint64_t> records{0};
    std::atomic<uint64_t> paths{0};
    uint64_t cellsInShard = 0;
    double fraction() const { return cellsInShard ? double(cellsDone) / double(cellsInShard) : 1.0; }
};

/// The cells of the jitter grid one run covers: the dataset header's "shard".
struct DatasetShard {
    int index = 0, count = 1;        ///< part k of n
    int cellBegin = 0, cellEnd = 0;  ///< cells [cellBegin, cellEnd) of the grid
    int cellsTotal = 0;              ///< cells of the whole grid
};

/// A run's records and what its dataset header says about them. The header (core/data/dataset_file.h)
/// is written and read by its codec (core/data/dataset_header_json.h) from the typed fields here.
struct GeneratedData {
    /// The header's descriptive keys, which travel to the file unchanged and are only compared as a
    /// whole between parts of one run: "format", "scene_hash", "settings", "light_region",
    /// "grid_bounds", "effects", "estimator", "objects" (ids and names), and any key of a part read
    /// back that this build does not know.
    JsonText description;
    /// The record columns ("input_layout", "target_layout", "noise_layout"; "floats_per_record" is
    /// layout.floatsPerRecord()).
    RecordLayout layout;
    /// The header names the noise columns: false only for a version 1 dataset read back (no
    /// "noise_layout"), which a merge writes back without one.
    bool noiseLayoutWritten = true;
    DatasetShard shard;                           ///< "shard"
    std::vector<std::vector<float>> perObject;    ///< records per object (in Scene::objects order)
    GeneratorStats stats;                         ///< what the run did (the header's "stats")
    uint64_t sceneHash = 0;
    double seconds = 0.0;                         ///< wall time (reported, never stored in the file)
    bool cancelled = false;
};

/// Throws SettingError naming the setting "shard" unless 0 <= shardIndex < shardCount (part k of n).
/// DataGenerator::run checks it; front ends call it first to refuse a bad shard before any work.
void checkShard(int shardIndex, int shardCount);

class DataGenerator {
public:
    /// `scene` must outlive the generator. Throws InputError if the settings do not fit the scene.
    DataGenerator(const Scene& scene, const SamplingSettings& settings);

    /// Generates shard `shardIndex` of `shardCount` (cells [k·C/n, (k+1)·C/n)). Stops early when
    /// `cancel` becomes true, within one record of each worker (then `cancelled` is set, the data is
    /// empty and must not be written). Throws SettingError naming the setting "shard" unless
    /// 0 <= shardIndex < shardCount, SettingError "grid and directions" when memoryEstimate exceeds
    /// the available memory, and InputError naming the scene when every sample was NaN or infinite.
    GeneratedData run(int shardIndex = 0, int shardCount = 1, const std::atomic<bool>* cancel = nullptr,
                      GeneratorProgress* progress = nullptr) const;

    /// Generates the cells [cellBegin, cellEnd) as part `partIndex` of `partCount` (a rank's share of
    /// an MPI job, core/data/cell_split.h): run(k, n) is runCells over shard k's cells. Parts that
    /// tile the grid join (core/data/dataset_part.h) into the bytes of the unsharded run. Throws
    /// SettingError naming "shard" unless 0 <= partIndex < partCount and 0 <= cellBegin <= cellEnd
    /// <= cells, and what run() throws.
    GeneratedData runCells(int cellBegin, int cellEnd, int partIndex, int partCount,
                           const std::atomic<bool>* cancel = nullptr, GeneratorProgress* progress = nullptr) const;

    /// The records each cell of the grid makes, predicted by tracing only each direction's first hit
    /// (one ray a direction instead of its paths): 0 for a dropped viewpoint, else the directions
    /// that hit an object. Equal to the records run() stores but for those whose every sample is NaN
    /// or infinite. The cost model of the MPI ranks' cell ranges (core/data/cell_split.h).
    std::vector<uint64_t> cellRecordCounts() const;

    /// The settings the generator runs with.
    const SamplingSettings& settings() const { return settings_; }

    /// Why a ray did or did not make a record.
    enum class RecordOutcome { Stored, Escaped, HitEmitter, NoFiniteSample };

    /// Estimates the record of one ray (viewpoint, dir) with the light centre at `lightPos`
    /// (layout().floatsPerRecord() floats: inputs, target means, variances of the means); returns
    /// false if the ray escapes, hits an emitter or has no finite sample (`outcome`, if given, says
    /// which). `recordIndex` keys the random numbers. `paths` receives the paths traced, `atCap`
    /// whether adaptive sampling stopped at max_spp with the noise still above its target. Exposed
    /// for tests that compare records with rendered pixels.
    bool estimateRecord(const Vec3& viewpoint, const Vec3& dir, const Vec3& lightPos, uint64_t recordIndex,
                        float* record, int& objectId, TraceCounters& counters, uint64_t& nonFinite,
                        RecordOutcome* outcome = nullptr, int* paths = nullptr, bool* atCap = nullptr) const;

    /// Upper bound on the bytes a run over `cells` cells holds: every direction of every cell storing
    /// a record (its floats and object id) plus the per-cell bookkeeping. run() refuses with a
    /// SettingError naming "grid and directions" when it exceeds the memory available.
    uint64_t memoryEstimate(uint64_t cells) const;
    /// The same bound before a generator exists (a scene's RecordLayout::floatsPerRecord() and the
    /// settings), so a front end can refuse at the control instead of after starting the job.
    static uint64_t memoryEstimate(const SamplingSettings& settings, int floatsPerRecord, uint64_t cells);

    const RecordLayout& layout() const { return layout_; }
    const PathTracer& tracer() const { return tracer_; }
    /// The estimator the records are traced with (settings.estimator, Auto resolved) and why.
    const EstimatorChoice& estimatorChoice() const { return choice_; }
    /// Region the light centre is drawn from (a single point when the light is fixed).
    Bounds3 lightRegion() const;

private:
    const Scene& scene_;
    SamplingSettings settings_;
    RecordLayout layout_;
    Accel accel_;
    EstimatorChoice choice_;
    PathTracer tracer_;
    std::unique_ptr<BidirectionalTracer> bdpt_;  ///< set when choice_ is BDPT
};

}  // namespace rrf
