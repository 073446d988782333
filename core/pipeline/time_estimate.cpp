#include "core/pipeline/time_estimate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/nn/encoding_presets.h"
#include "core/nn/mlp.h"
#include "core/render/renderer.h"
#include "core/util/error.h"
#include "core/scene/scene.h"

namespace rrf {

namespace {
std::string format(const char* fmt, double a, double b = 0, double c = 0, double d = 0) {
    char buf[256];
    std::snprintf(buf, sizeof buf, fmt, a, b, c, d);
    return buf;
}

/// Wall seconds of one pass over `records` pixels-or-records × `paths` at `rate`.
double pathSeconds(double samples, const PathRate& rate) {
    return rate.samplesPerSecond > 0 ? samples / rate.samplesPerSecond : 0.0;
}

/// kd-tree levels a partition can grow (1 without one): ⌈log2 max_leaves⌉ + 1, at most max_depth + 1.
int treeLevels(const PartitionSettings& p) {
    if (p.maxLeaves <= 1 || p.maxDepth <= 0) return 1;
    const int depth = int(std::ceil(std::log2(double(p.maxLeaves))));
    return std::min(depth, p.maxDepth) + 1;
}
}  // namespace

PathRate PathRate::of(double measured, int threads) {
    PathRate r;
    r.measured = measured > 0;
    r.samplesPerSecond = r.measured ? measured : kReferencePathRate * std::max(1, threads);
    return r;
}

std::string PathRate::describe() const {
    if (measured) return format("%.3g M samples/s (the last render's)", samplesPerSecond / 1e6);
    return format("%.3g M samples/s (the reference machine's %.3g M per thread x %.0f threads)", samplesPerSecond / 1e6,
                  kReferencePathRate / 1e6, std::round(samplesPerSecond / kReferencePathRate));
}

double expectedRecords(const SamplingSettings& s, double recordsPerRay) {
    return double(s.cellCount()) * double(s.directions) * std::clamp(recordsPerRay, 0.0, 1.0);
}

StageEstimate estimateGenerate(const SamplingSettings& s, const PathRate& rate, double recordsPerRay) {
    const double records = expectedRecords(s, recordsPerRay);
    const int maxPaths = s.adaptive() ? s.maxSpp : s.spp;
    StageEstimate e;
    e.low = pathSeconds(records * s.spp, rate);
    e.high = pathSeconds(records * maxPaths, rate);
    e.basis = format("<= %.4g records x %.0f", records, s.spp) + (s.adaptive() ? format("..%.0f", maxPaths) : "") +
              " paths at " + rate.describe();
    return e;
}

StageEstimate estimateTraining(const ObjectTrainingOptions& o, double records, int objects, int inputs, int threads) {
    MlpArch arch;
    arch.inputs = std::max(1, inputs);
    try {
        // An input encoding widens the first layer (its own cost per record is not modelled).
        // (the section's networks; "objects" entries are not modelled)
        const InputEncoding encoding = networkEncoding(o.encoding, arch.inputs, o.inputs);
        arch.inputs = encoding.outputs();
    } catch (const InputError&) {
        // An encoding these records cannot take: training will say so; estimate the raw network.
    }
    arch.hidden = o.hidden;
    arch.activation = o.activation;
    arch.outputs = o.targets == TargetMode::Joint ? 6 : 3;
    const double P = double(arch.numParams());
    const int perObject = o.targets == TargetMode::Separate ? 2 : 1;
    // An ensemble trains each network's members one after another (nn/ensemble.h).
    const int networks = std::max(1, objects) * perObject;
    const double members = double(std::max(1, o.ensemble));
    // Records spread over the objects; every network of an object sees all of its records.
    const double perNetwork = records / double(std::max(1, objects));
    const TrainerConfig& t = o.trainer;
    double epochSeconds = 0;
    std::string cost;
    double n = perNetwork;
    if (t.common().maxSamples > 0) n = std::min(n, double(t.common().maxSamples));
    if (t.type == TrainerType::LevenbergMarquardt) {
        if (t.lm.maxEpochGflop > 0) n = std::min(n, std::floor(t.lm.maxEpochGflop * 1e9 / (3 * P * P)));
        epochSeconds = 3 * n * P * P / kLmFlopsPerThread;
        cost = format("LM 3 N P^2 with N = %.4g, P = %.0f at %.0f GFLOP/s per thread", n, P, kLmFlopsPerThread / 1e9);
    } else {
        epochSeconds = n * P / kAdamWeightSamplesPerThread;
        cost = format("Adam N P with N = %.4g, P = %.0f at %.3g M samples/s per thread for P = 583", n, P,
                      kAdamWeightSamplesPerThread / 583 / 1e6);
    }
    const double parallel = double(std::min(std::max(1, threads), networks));
    const int levels = treeLevels(o.partition);
    StageEstimate e;
    e.low = double(t.maxEpochs()) * epochSeconds * double(networks) * members / parallel;
    e.high = e.low * levels;
    e.basis = format("%.0f networks x ", networks) + (members > 1 ? format("%.0f members x ", members) : std::string()) +
              format("<= %.0f epochs of ", t.maxEpochs()) + cost +
              format(", %.0f in parallel", parallel) +
              (levels > 1 ? format("; up to %.0f kd-tree levels", levels) : std::string());
    return e;
}

StageEstimate estimateRender(const RenderSettings& r, const Scene& scene, const PathRate& rate) {
    const RenderOptions o = renderOptionsFor(scene, r, 1);
    StageEstimate e;
    e.low = e.high = pathSeconds(double(o.width) * o.height * r.spp, rate);
    e.basis = format("%.0f x %.0f pixels x %.0f spp at ", o.width, o.height, r.spp) + rate.describe();
    return e;
}

StageEstimate estimateEvaluate(const RenderSettings& r, const Scene& scene, const PathRate& rate) {
    const RenderOptions o = renderOptionsFor(scene, r, 1);
    StageEstimate e;
    e.low = e.high = pathSeconds(double(o.width) * o.height * kEvaluateSppEquivalent, rate);
    e.basis = format("one CPU prediction of %.0f x %.0f pixels, about %.0f path samples per pixel", o.width, o.height,
                     kEvaluateSppEquivalent);
    return e;
}

std::string durationText(double seconds) {
    if (seconds < 1) return "< 1 s";
    if (seconds < 90) return format("%.0f s", std::round(seconds));
    if (seconds < 5400) return format("%.1f min", seconds / 60);
    if (seconds < 172800) return format("%.1f h", seconds / 3600);
    return format("%.1f days", seconds / 86400);
}

std::string rangeText(const StageEstimate& e) {
    const std::string lo = durationText(e.low), hi = durationText(e.high);
    return lo == hi ? lo : lo + " to " + hi;
}

}  // namespace rrf
