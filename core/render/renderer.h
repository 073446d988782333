#pragma once
/// Progressive, tiled, multi-threaded (oneTBB) ground-truth renderer.
///
/// Each pass adds `samplesPerPass` samples to every pixel. Sums are kept in double per pixel, together
/// with the sums of squares of the direct, indirect and global radiance (each term's per-pixel variance
/// of the mean: the noise floor of every error measured against this render). Sample k of pixel
/// i always uses Rng(seed, i, k) and a pass adds its samples onto the pixel's running sums in sample
/// order, so the image is bit-identical for any thread count and any pass split — and for a render
/// resumed from an exported RenderState (the reference store continues references this way). A sample whose direct or indirect radiance is NaN/Inf is dropped and counted; the pixel
/// keeps its own sample count so the mean stays unbiased.
///
/// Thread safety: run()/runPass() on one worker thread; snapshot(), cancel(), progress() and stats()
/// may be called from any other thread at any time (the UI thread polls them); snapshot() shows the
/// passes completed so far and does not block for the duration of a pass.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "core/scene/camera_rays.h"
#include "core/util/image.h"
#include "core/render/bdpt.h"
#include "core/render/path_tracer.h"
#include "core/render/term.h"

namespace rrf {

struct RenderOptions {
    int width = 256, height = 256;
    int spp = 64;
    /// Auto: the renderer resolves it from the scene's effects (chooseEstimator), as the project does.
    Estimator estimator = Estimator::Auto;
    uint64_t seed = 1;
    int maxDepth = 64;
    int samplesPerPass = 1;
    /// Tiles of the image; with BDPT also the unit in which light-tracing splats are ordered, so it
    /// is part of what makes a BDPT render (not of what makes a path-traced one).
    int tileSize = 16;
    /// What happens to a pass cut short by cancel(): true keeps the samples of the tiles it finished
    /// (each pixel carries its own count, so the image stays unbiased); false drops the whole pass,
    /// so the sums end on a pass boundary and an exported state resumes bit-identically.
    bool keepCancelledPass = true;
    /// Renders only the rows y with y mod rowStride = rowOffset (the others keep no samples): one
    /// process's share of an image split across processes (core/render/render_rows.h). Each pixel's
    /// samples are those of the whole render, so the joined rows are the whole render's bits.
    /// Requires 1 ≤ rowStride and 0 ≤ rowOffset < rowStride (the Renderer throws otherwise).
    int rowOffset = 0, rowStride = 1;
};

/// Per-pixel sums of a render, in double: radiance per term and channel, squares for the variances.
struct PixelSums {
    double direct[3] = {0, 0, 0};
    double indirect[3] = {0, 0, 0};
    /// Sums of squares per term (index int(Term)) and channel, for the variances of the means.
    double sq[kTermCount][3] = {};
    uint32_t accepted = 0;     ///< finite samples accumulated
    uint32_t next = 0;         ///< next sample index (counts dropped samples too)
};

/// Everything a render has accumulated after its last completed pass: restoring it into a renderer
/// of the same scene, size, estimator, depth and seed continues exactly where it stopped.
struct RenderState {
    int width = 0, height = 0;
    int sppDone = 0, passes = 0;
    uint64_t samples = 0, rays = 0, shadowRays = 0, nonFinite = 0;
    double seconds = 0.0;
    std::vector<PixelSums> pixels;  ///< i = y·width + x
};

/// Options for rendering `scene` with a project's render settings: a size of 0 means the camera's,
/// and the spp are split into about `passes` passes (each pass refreshes snapshots and progress).
RenderOptions renderOptionsFor(const Scene& scene, const RenderSettings& settings, int passes);

/// A consistent copy of the current estimate.
struct RenderSnapshot {
    Image direct, indirect, global;
    /// Per-pixel, per-channel variance of the mean of each term, Var(mean) = max(0, E[x²] − E[x]²) / (n − 1)
    /// over the pixel's n accepted samples (0 where n < 2). The global one is not the sum of the other
    /// two: direct and indirect radiance of one path are correlated.
    Image variance;            ///< of the global mean
    Image directVariance;      ///< of the direct mean
    Image indirectVariance;    ///< of the indirect mean
    int passes = 0;
    uint64_t samples = 0;      ///< samples accepted so far (all pixels)
    uint64_t nonFinite = 0;    ///< samples dropped because they were NaN/Inf
    int sppCompleted = 0;      ///< samples per pixel of completed passes
    double seconds = 0.0;      ///< render time so far
    /// Relative standard error of the image mean of the global image, a convergence estimate.
    double relativeError = 0.0;

    const Image& image(Term t) const { return t == Term::Direct ? direct : t == Term::Indirect ? indirect : global; }
    /// The variance of the mean of term `t` (variance, directVariance or indirectVariance).
    const Image& varianceOf(Term t) const {
        return t == Term::Direct ? directVariance : t == Term::Indirect ? indirectVariance : variance;
    }
    /// True once every pixel may have 2 samples: below that the variance images hold 0, which is not
    /// an estimate, so every reader treats the noise as unknown (never as a floor of 0).
    bool varianceKnown() const { return sppCompleted >= 2; }
};

struct RenderStats {
    uint64_t samples = 0, rays = 0, shadowRays = 0, nonFinite = 0;
    double seconds = 0.0;
    double samplesPerSecond() const { return seconds > 0 ? double(samples) / seconds : 0.0; }
    double raysPerSecond() const { return seconds > 0 ? double(rays + shadowRays) / seconds : 0.0; }
};

class Renderer {
public:
    /// `scene` and `accel` must outlive the renderer. Throws std::invalid_argument when the rows
    /// are out of range (RenderOptions::rowOffset, rowStride).
    Renderer(const Scene& scene, const Accel& accel, const RenderOptions& options);

    /// Runs passes until options.spp samples per pixel are done or cancel() is called.
    /// `onPass` (optional) is called on the calling thread after each pass with the spp done so far.
    void run(const std::function<void(int sppDone)>& onPass = {});
    /// One pass of `samplesPerPass` samples per pixel; returns false if it was cancelled midway.
    bool runPass();

    void cancel() { cancelled_ = true; }
    bool cancelled() const { return cancelled_; }
    /// Fraction of the requested samples done, in [0,1].
    double progress() const;
    RenderSnapshot snapshot() const;
    RenderStats stats() const;

    /// The committed sums and counters (what snapshot() shows), for saving a resumable render.
    RenderState exportState() const;
    /// Replaces the sums and counters by `state`, e.g. one exported by an earlier session; options
    /// keep this renderer's (a larger spp continues further). Throws std::invalid_argument if the
    /// size differs. Call between passes only.
    void restoreState(const RenderState& state);
    /// The images and variances of `state` (what snapshot() would show after restoreState(state)).
    static RenderSnapshot snapshotOf(const RenderState& state);

    const PathTracer& tracer() const { return tracer_; }
    /// PathTracer::setLanes() for this renderer's tracer (bench_render's portable row). Before run().
    void setLanes(path_lanes::Isa isa) { tracer_.setLanes(isa); }
    const RenderOptions& options() const { return options_; }
    /// The estimator that runs (options.estimator with Auto resolved) and why.
    const EstimatorChoice& estimatorChoice() const { return choice_; }

private:
    using Pixel = PixelSums;
    void renderTile(int x0, int y0, int x1, int y1, int samples, TraceCounters& counters, uint64_t& nonFinite,
                    uint64_t& accepted);
    /// BDPT passes: one iteration (a sample of every pixel and width × height light paths) at a
    /// time, so each pixel's sample includes the light-tracing splats it received in its iteration
    /// and the variance of the mean stays an estimate over independent iterations.
    bool runBidirectionalPass(int samples, TraceCounters& counters, uint64_t& nonFinite, uint64_t& accepted);
    static void addSample(PixelSums& px, const Radiance& L);
    void mergePass();
    static RenderSnapshot snapshotOfPixels(const std::vector<Pixel>& pixels, int width, int height);

    const Scene& scene_;
    RenderOptions options_;
    EstimatorChoice choice_;
    PathTracer tracer_;
    std::unique_ptr<BidirectionalTracer> bdpt_;  ///< set when choice_ is BDPT
    std::unique_ptr<PinholeImportance> importance_;
    CameraRays camera_;
    std::vector<Pixel> pixels_;  ///< committed sums: what snapshot() shows
    /// The sums with the pass in progress: a copy of pixels_ that the pass adds its samples to (each
    /// pixel from one thread, without a lock), swapped into pixels_ under the mutex at its end, so
    /// snapshot() never waits for a pass and every pixel's sums run in sample order.
    std::vector<Pixel> pass_;
    mutable std::mutex mutex_;  ///< guards pixels_ between mergePass() and snapshot()
    std::atomic<bool> cancelled_{false};
    std::atomic<int> passes_{0};
    std::atomic<int> sppDone_{0};
    std::atomic<uint64_t> samples_{0}, rays_{0}, shadowRays_{0}, nonFinite_{0};
    std::atomic<double> seconds_{0.0};
};

}  // namespace rrf
