#pragma once
/// Time estimates of the pipeline's stages from their settings, before anything runs: what the
/// Sampling and Network panels show next to a preset, what the one-click pipeline weighs its
/// stages by (overall fraction and ETA), and what `rrf pipeline` prints. Every estimate is a range
/// with the figures it was computed from (`basis`), so the user can judge it:
///
///  - data: records × paths per record ÷ the path-sample rate. Records are at most grid cells ×
///    directions (cells inside objects and escaping rays make none; a measured records-per-ray
///    fraction narrows it); paths per record are the first round (low) to max_spp (high, when
///    adaptive). The rate is the last ground-truth render's samples/s when known (the generator
///    traces at the renderer's speed, bench_generate), else kReferencePathRate per thread.
///  - training: per network, max_epochs × the cost of one epoch (an upper bound: the error goal and
///    patience stop earlier). Levenberg–Marquardt: 3·N·P² flops (N its records after max_samples and
///    max_epoch_gflop, P the weights) at kLmFlopsPerThread; Adam: N·P multiply–adds per epoch for
///    forward and backward at kAdamWeightSamplesPerThread. Objects train in parallel, so the wall
///    time is the networks' sum over min(threads, networks). Low: the root networks only; high: every
///    kd-tree level splits (each level sees an object's records once more).
///  - render: width × height × spp ÷ the rate; evaluate: one CPU prediction of the image, counted as
///    a render at kEvaluateSppEquivalent samples per pixel.

#include <string>

#include "core/data/sampling_settings.h"
#include "core/nn/object_training.h"
#include "core/render/render_settings.h"

namespace rrf {

struct Scene;

/// Path samples per second per thread when no render was measured: the path tracer's per-thread speed
/// on the 2-core reference machine (docs/results.md, "tracer": bench_render's tracer rate).
constexpr double kReferencePathRate = 1.85e6;
/// Levenberg–Marquardt flops per second per thread (docs/results.md, "kernels": bench_nn's LM epoch
/// of 16-20-10-3 against its 3·N·P² flop count, on 1 thread).
constexpr double kLmFlopsPerThread = 20.0e9;
/// Adam training throughput per thread in samples × weights per second (docs/results.md, "kernels":
/// bench_nn's Adam rate for 16-20-10-3 on one thread, times its P = 583 weights).
constexpr double kAdamWeightSamplesPerThread = 6.30e6 * 583;
/// The evaluation's CPU prediction (exact direct light's shadow rays and the networks) counted as
/// this many path samples per pixel: a rough allowance that only weighs the pipeline's last stage
/// against the others, not a measurement.
constexpr double kEvaluateSppEquivalent = 4.0;

/// The range of a stage's wall time in seconds and what it was computed from.
struct StageEstimate {
    double low = 0, high = 0;
    std::string basis;  ///< e.g. "<= 153600 records x 64..1024 paths at 3.7 M samples/s (last render)"
};

/// How fast this machine traces paths: `measured` (the last render's samples/s, all threads) when
/// positive, else kReferencePathRate × `threads`.
struct PathRate {
    double samplesPerSecond = 0;
    bool measured = false;
    static PathRate of(double measured, int threads);
    /// "3.7 M samples/s (the last render's)" or "... (the reference machine's 1.85 M per thread x 2 threads)".
    std::string describe() const;
};

/// Records a generation makes at most: cells × directions × `recordsPerRay` (1 when unknown).
double expectedRecords(const SamplingSettings& s, double recordsPerRay = 1.0);
StageEstimate estimateGenerate(const SamplingSettings& s, const PathRate& rate, double recordsPerRay = 1.0);
/// `records`: what the dataset holds (expectedRecords() before it exists); `inputs`: network inputs
/// per record (RecordLayout::forScene(scene).inputCount()).
StageEstimate estimateTraining(const ObjectTrainingOptions& o, double records, int objects, int inputs, int threads);
StageEstimate estimateRender(const RenderSettings& r, const Scene& scene, const PathRate& rate);
StageEstimate estimateEvaluate(const RenderSettings& r, const Scene& scene, const PathRate& rate);

/// "< 1 s", "12 s", "4.5 min", "2.3 h": a duration for estimates.
std::string durationText(double seconds);
/// "12 s" or "12 s to 3.2 min": a range.
std::string rangeText(const StageEstimate& e);

}  // namespace rrf
