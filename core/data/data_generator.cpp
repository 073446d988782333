#include "core/data/data_generator.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <tbb/parallel_for.h>

#include "core/util/error.h"
#include "core/util/memory_budget.h"
#include "core/data/dataset_header_json.h"
#include "core/data/jitter_grid.h"
#include "core/data/record_noise.h"
#include "core/util/warp.h"

namespace rrf {

namespace {
// Domain separation of the random streams: directions/light positions and path samples never
// share numbers with each other or with the viewpoints (jitter_grid.cpp).
uint64_t recordSeed(uint64_t seed) { return mix64(seed ^ 0x5245434F52445321ULL); }
uint64_t pathSeed(uint64_t seed) { return mix64(seed ^ 0x5041544853414D50ULL); }

/// The direction and light position of record r: the one place they are drawn (runCells traces
/// them, cellRecordCounts predicts which make a record).
void recordRay(uint64_t recordSeedValue, uint64_t r, const Bounds3& region, Vec3& dir, Vec3& lightPos) {
    Rng rng(recordSeedValue, r);
    const float u1 = rng.uniform(), u2 = rng.uniform();
    dir = sampleUniformSphere(u1, u2);
    const Vec3 e = region.extent();
    lightPos = Vec3(region.lo.x + e.x * rng.uniform(), region.lo.y + e.y * rng.uniform(), region.lo.z + e.z * rng.uniform());
}

struct CellOutput {
    std::vector<float> records;
    std::vector<int32_t> objects;
    uint64_t escaped = 0, emitterHits = 0, nonFinite = 0, emptyRecords = 0, paths = 0, atCap = 0;
    uint8_t status = 0;  ///< ViewpointStatus
};
}  // namespace

DataGenerator::DataGenerator(const Scene& scene, const SamplingSettings& settings)
    : scene_(scene),
      settings_(settings),
      layout_(RecordLayout::forScene(scene)),
      accel_(scene),
      choice_(chooseEstimator(settings.estimator, Effects::derive(scene))),
      tracer_(scene, accel_, choice_.estimator == Estimator::BDPT ? Estimator::NEE : choice_.estimator, settings.maxDepth) {
    if (choice_.estimator == Estimator::BDPT) bdpt_ = std::make_unique<BidirectionalTracer>(tracer_, settings.maxDepth);
    if (scene.objects.empty()) throw InputError(scene.sourcePath, "/shapes", "the scene has no objects to generate data for");
    if (scene.lights.empty()) throw InputError(scene.sourcePath, "/lights", "the scene has no light: every record would be black");
}

Bounds3 DataGenerator::lightRegion() const {
    if (!settings_.fixedLight) return scene_.lightRange();
    Bounds3 r;
    r.expand(scene_.lightPosition());
    return r;
}

bool DataGenerator::estimateRecord(const Vec3& viewpoint, const Vec3& dir, const Vec3& lightPos, uint64_t recordIndex,
                                   float* record, int& objectId, TraceCounters& counters, uint64_t& nonFinite,
                                   RecordOutcome* outcome, int* paths, bool* atCap) const {
    RecordOutcome unused;
    RecordOutcome& result = outcome ? *outcome : unused;
    const Light movable = tracer_.movableLightAt(lightPos);
    Ray ray;
    ray.origin = viewpoint;
    ray.dir = dir;
    Hit hit;
    ++counters.rays;
    if (!tracer_.intersect(ray, movable, hit)) {
        result = RecordOutcome::Escaped;
        return false;
    }
    if (hit.object < 0) {
        result = RecordOutcome::HitEmitter;
        return false;
    }
    const Vec3 wo = -dir;
    // Adaptive sampling (docs/design.md §8): rounds of spp, 2·spp, 4·spp … paths until the relative
    // noise is at most noise_target or max_spp paths were traced. Sample s is always keyed by
    // (seed, record, s), so a fixed-spp run gives the targets of earlier versions bit for bit.
    TargetAccumulator acc;
    const int cap = std::max(settings_.spp, settings_.maxSpp);
    const uint64_t ps = pathSeed(settings_.seed);
    int traced = 0, round = settings_.spp;
    float mean[6], var[6];
    auto summarise = [&] {
        for (int c = 0; c < 6; ++c) {
            mean[c] = float(acc.mean[c]);
            var[c] = float(acc.varianceOfMean(c));
        }
    };
    bool capped = false;
    for (;;) {
        // The paths in batches of up to 16 (the tracer's lanes run them together), added in path order.
        while (traced < round) {
            constexpr int K = Accel::kPacket;
            const int n = std::min(round - traced, K);
            Rng rngs[K] = {Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0),
                           Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0)};
            Radiance Ls[K];
            for (int j = 0; j < n; ++j) rngs[j] = Rng(ps, recordIndex, uint64_t(traced + j));
            if (bdpt_)
                for (int j = 0; j < n; ++j) Ls[j] = bdpt_->shade(hit, wo, movable, rngs[j], counters);
            else
                tracer_.shadeBatch(hit, wo, movable, rngs, n, counters, Ls);
            traced += n;
            for (int j = 0; j < n; ++j) {
                const Radiance& L = Ls[j];
                if (!L.direct.isFinite() || !L.indirect.isFinite()) {
                    ++nonFinite;
                    continue;
                }
                const double sample[6] = {L.direct[0], L.direct[1], L.direct[2], L.indirect[0], L.indirect[1], L.indirect[2]};
                acc.add(sample);
            }
        }
        if (!settings_.adaptive() || acc.n == 0) break;
        summarise();
        const double r = relativeNoise(mean, var);
        if (std::isfinite(r) && r <= settings_.noiseTarget) break;
        if (round >= cap) {
            capped = true;
            break;
        }
        round = int(std::min<int64_t>(int64_t(round) * 2, cap));
    }
    if (paths) *paths = traced;
    if (acc.n == 0) {
        result = RecordOutcome::NoFiniteSample;
        return false;
    }
    if (atCap) *atCap = capped;
    summarise();
    result = RecordOutcome::Stored;
    const Object& obj = scene_.objects[size_t(hit.object)];
    layout_.writeInputs(hit.p, wo, lightPos, hit.shading(), scene_.materials[size_t(obj.material)], record);
    float* t = record + layout_.inputCount();
    for (int c = 0; c < 6; ++c) {
        t[c] = mean[c];
        t[6 + c] = var[c];
    }
    objectId = hit.object;
    return true;
}

uint64_t DataGenerator::memoryEstimate(uint64_t cells) const {
    return memoryEstimate(settings_, layout_.floatsPerRecord(), cells);
}

uint64_t DataGenerator::memoryEstimate(const SamplingSettings& settings, int floatsPerRecord, uint64_t cells) {
    const uint64_t directions = uint64_t(std::max(settings.directions, 0));
    const uint64_t recordBytes = saturatingProduct(directions, uint64_t(std::max(floatsPerRecord, 0)), sizeof(float));
    const uint64_t perCell = recordBytes + sizeof(CellOutput) + saturatingProduct(directions, sizeof(int32_t));
    return saturatingProduct(cells, perCell);
}

std::vector<uint64_t> DataGenerator::cellRecordCounts() const {
    const JitterGrid grid(scene_.bounds(), settings_.nx, settings_.ny, settings_.nz);
    const ViewpointClassifier classifier(tracer_);
    const Bounds3 region = lightRegion();
    const uint64_t rs = recordSeed(settings_.seed);
    std::vector<uint64_t> counts(static_cast<size_t>(grid.cellCount()), 0);
    tbb::parallel_for(0, grid.cellCount(), [&](int cell) {
        const Vec3 vp = grid.viewpoint(cell, settings_.seed);
        if (classifier.classify(vp) != ViewpointStatus::Kept) return;
        uint64_t n = 0;
        for (int j = 0; j < settings_.directions; ++j) {
            Vec3 dir, lp;
            recordRay(rs, uint64_t(cell) * uint64_t(settings_.directions) + uint64_t(j), region, dir, lp);
            Ray ray;
            ray.origin = vp;
            ray.dir = dir;
            Hit hit;
            // As estimateRecord decides: no hit escapes, an emitter's hit makes no record.
            n += tracer_.intersect(ray, tracer_.movableLightAt(lp), hit) && hit.object >= 0;
        }
        counts[size_t(cell)] = n;
    });
    return counts;
}

void checkShard(int shardIndex, int shardCount) {
    if (shardCount < 1 || shardIndex < 0 || shardIndex >= shardCount)
        throw SettingError("shard", "expected part k of n with 0 <= k < n, got k = " + std::to_string(shardIndex) +
                                        ", n = " + std::to_string(shardCount));
}

GeneratedData DataGenerator::run(int shardIndex, int shardCount, const std::atomic<bool>* cancel,
                                 GeneratorProgress* progress) const {
    checkShard(shardIndex, shardCount);
    const int cells = settings_.cellCount();
    const int begin = int(int64_t(cells) * shardIndex / shardCount);
    const int end = int(int64_t(cells) * (shardIndex + 1) / shardCount);
    return runCells(begin, end, shardIndex, shardCount, cancel, progress);
}

GeneratedData DataGenerator::runCells(int begin, int end, int shardIndex, int shardCount, const std::atomic<bool>* cancel,
                                      GeneratorProgress* progress) const {
    checkShard(shardIndex, shardCount);
    const auto start = std::chrono::steady_clock::now();
    const JitterGrid grid(scene_.bounds(), settings_.nx, settings_.ny, settings_.nz);
    const int cells = grid.cellCount();
    if (begin < 0 || begin > end || end > cells)
        throw SettingError("shard", "expected cells 0 <= begin <= end <= " + std::to_string(cells) + ", got " +
                                        std::to_string(begin) + " ... " + std::to_string(end));
    if (progress) progress->cellsInShard = uint64_t(end - begin);
    const ViewpointClassifier classifier(tracer_);
    const Bounds3 region = lightRegion();
    const int fpr = layout_.floatsPerRecord();
    const uint64_t rs = recordSeed(settings_.seed);

    if (const std::string why = memoryShortfall(memoryEstimate(uint64_t(end - begin)), availableMemoryBytes(),
                                                std::to_string(end - begin) + " cells x " + std::to_string(settings_.directions) +
                                                    " directions x " + std::to_string(fpr) +
                                                    " floats per record, if every ray makes a record");
        !why.empty())
        throw SettingError("grid and directions", "the run " + why + "; choose a smaller grid (1 ... " +
                                                      std::to_string(kMaxGridCells) + " per axis) or fewer directions (1 ... " +
                                                      std::to_string(kMaxDirections) + "), or generate in shards");
    std::vector<CellOutput> out(size_t(end - begin));
    std::atomic<uint64_t> rays{0}, shadowRays{0};
    auto cancelled = [cancel] { return cancel && cancel->load(std::memory_order_relaxed); };
    tbb::parallel_for(begin, end, [&](int cell) {
        if (cancelled()) return;
        CellOutput& co = out[size_t(cell - begin)];
        const Vec3 vp = grid.viewpoint(cell, settings_.seed);
        const ViewpointStatus status = classifier.classify(vp);
        co.status = uint8_t(status);
        if (status == ViewpointStatus::Kept) {
            TraceCounters counters;
            std::vector<float> rec(static_cast<size_t>(fpr));
            // Cancel is checked per record, not per cell: one cell may hold millions of directions.
            for (int j = 0; j < settings_.directions && !cancelled(); ++j) {
                const uint64_t r = uint64_t(cell) * uint64_t(settings_.directions) + uint64_t(j);
                Vec3 dir, lp;
                recordRay(rs, r, region, dir, lp);
                int objectId = -1, paths = 0;
                bool capped = false;
                RecordOutcome outcome;
                const bool stored =
                    estimateRecord(vp, dir, lp, r, rec.data(), objectId, counters, co.nonFinite, &outcome, &paths, &capped);
                co.paths += uint64_t(paths);
                if (stored) {
                    co.records.insert(co.records.end(), rec.begin(), rec.end());
                    co.objects.push_back(objectId);
                    co.atCap += capped;
                } else if (outcome == RecordOutcome::Escaped) {
                    ++co.escaped;
                } else if (outcome == RecordOutcome::HitEmitter) {
                    ++co.emitterHits;
                } else {
                    ++co.emptyRecords;
                }
            }
            rays += counters.rays;
            shadowRays += counters.shadowRays;
            if (progress) {
                progress->records += co.objects.size();
                progress->paths += co.paths;
            }
        }
        if (progress) ++progress->cellsDone;
    });

    GeneratedData data;
    data.cancelled = cancelled();
    data.sceneHash = scene_.contentHash();
    // A cancelled run is never written: free the cells at once instead of regrouping them.
    if (data.cancelled) return data;
    data.perObject.resize(scene_.objects.size());
    GeneratorStats& st = data.stats;
    st.recordsPerCell.reserve(out.size());
    // Regroup by object in cell order. Exact reservations and freeing each cell once copied keep the
    // peak near one payload instead of two or three (the default Cornell run is ~250 MiB).
    std::vector<size_t> perObjectCount(scene_.objects.size(), 0);
    for (const CellOutput& co : out)
        for (int32_t id : co.objects) ++perObjectCount[size_t(id)];
    for (size_t i = 0; i < perObjectCount.size(); ++i) data.perObject[i].reserve(perObjectCount[i] * size_t(fpr));
    for (CellOutput& co : out) {
        for (size_t i = 0; i < co.objects.size(); ++i) {
            auto& dst = data.perObject[size_t(co.objects[i])];
            dst.insert(dst.end(), co.records.begin() + long(i * size_t(fpr)), co.records.begin() + long((i + 1) * size_t(fpr)));
        }
        std::vector<float>().swap(co.records);
        st.raysEscaped += co.escaped;
        st.raysHitEmitter += co.emitterHits;
        st.nonFiniteSamplesDropped += co.nonFinite;
        st.recordsWithoutFiniteSample += co.emptyRecords;
        st.records += co.objects.size();
        st.cellsDroppedInsideObject += co.status == uint8_t(ViewpointStatus::InsideObject);
        st.cellsDroppedOutsideScene += co.status == uint8_t(ViewpointStatus::OutsideScene);
        st.cellsDroppedBehindSurface += co.status == uint8_t(ViewpointStatus::BehindSurface);
        st.recordsAtSppCap += co.atCap;
        st.paths += co.paths;
        st.recordsPerCell.push_back(uint64_t(co.objects.size()));
    }
    for (const std::vector<float>& records : data.perObject) {
        st.recordsPerObject.push_back(records.size() / size_t(fpr));
        st.noisePerObject.push_back(summarizeNoise(records.data(), records.size() / size_t(fpr), fpr,
                                                   layout_.inputCount(), layout_.inputCount() + layout_.targetCount()));
    }
    if (st.records == 0 && st.recordsWithoutFiniteSample > 0)
        throw InputError(scene_.sourcePath, "",
                         "every sample of every record was NaN or infinite (" + std::to_string(st.nonFiniteSamplesDropped) +
                             " samples dropped, no record stored): the scene's radiance must stay finite in single "
                             "precision (check light radiance/intensity, light size and material values)");
    data.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    st.rays = rays;
    st.shadowRays = shadowRays;

    data.description = datasetDescription(scene_, data.sceneHash, settings_, region, grid.bounds(), tracer_.effects(), choice_);
    data.layout = layout_;
    data.shard = {shardIndex, shardCount, begin, end, cells};
    return data;
}

}  // namespace rrf
