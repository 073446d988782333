#include "core/render/renderer.h"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range2d.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

namespace rrf {

RenderOptions renderOptionsFor(const Scene& scene, const RenderSettings& s, int passes) {
    RenderOptions o;
    o.width = s.width > 0 ? s.width : scene.camera.width;
    o.height = s.height > 0 ? s.height : scene.camera.height;
    o.spp = std::max(1, s.spp);
    o.seed = s.seed;
    o.maxDepth = s.maxDepth;
    o.estimator = s.estimator;
    o.samplesPerPass = std::max(1, o.spp / std::max(1, passes));
    return o;
}

Renderer::Renderer(const Scene& scene, const Accel& accel, const RenderOptions& options)
    : scene_(scene),
      options_(options),
      choice_(chooseEstimator(options.estimator, Effects::derive(scene))),
      // BDPT borrows the NEE tracer's intersection, occlusion, BRDFs and lights.
      tracer_(scene, accel, choice_.estimator == Estimator::BDPT ? Estimator::NEE : choice_.estimator, options.maxDepth),
      camera_(scene.camera, options.width, options.height),
      pixels_((requireRenderMemory(options.width, options.height), size_t(options.width) * size_t(options.height))) {
    // An offset outside [0, stride) would select no row at all: a part that renders nothing and
    // still counts its passes, which joinRenderRows could not tell from a finished one.
    if (options.rowStride < 1 || options.rowOffset < 0 || options.rowOffset >= options.rowStride)
        throw std::invalid_argument("Renderer: rowOffset " + std::to_string(options.rowOffset) + " must be in [0, rowStride " +
                                    std::to_string(options.rowStride) + ")");
    options_.estimator = choice_.estimator;
    if (choice_.estimator == Estimator::BDPT) {
        bdpt_ = std::make_unique<BidirectionalTracer>(tracer_, options.maxDepth);
        importance_ = std::make_unique<PinholeImportance>(scene.camera, options.width, options.height);
    }
}

void Renderer::run(const std::function<void(int)>& onPass) {
    while (sppDone_ < options_.spp && !cancelled_) {
        if (!runPass()) break;
        if (onPass) onPass(sppDone_);
    }
}

bool Renderer::runPass() {
    const int samples = std::min(std::max(1, options_.samplesPerPass), options_.spp - sppDone_);
    if (samples <= 0) return true;
    const auto start = std::chrono::steady_clock::now();
    struct Local {
        TraceCounters counters;
        uint64_t nonFinite = 0, accepted = 0;
    };
    tbb::combinable<Local> locals;
    const int ts = std::max(1, options_.tileSize);
    // Only this thread writes pixels_, so it may be read here without the lock.
    pass_ = pixels_;
    if (bdpt_) {
        Local& l = locals.local();
        runBidirectionalPass(samples, l.counters, l.nonFinite, l.accepted);
    } else {
        tbb::parallel_for(tbb::blocked_range2d<int>(0, options_.height, ts, 0, options_.width, ts),
                          [&](const tbb::blocked_range2d<int>& r) {
                              if (cancelled_) return;
                              Local& l = locals.local();
                              renderTile(r.cols().begin(), r.rows().begin(), r.cols().end(), r.rows().end(),
                                         samples, l.counters, l.nonFinite, l.accepted);
                          });
    }
    Local total;
    locals.combine_each([&](const Local& l) {
        total.counters.rays += l.counters.rays;
        total.counters.shadowRays += l.counters.shadowRays;
        total.nonFinite += l.nonFinite;
        total.accepted += l.accepted;
    });
    // A cancelled pass is merged too unless the options say otherwise: each pixel carries its own
    // sample count, so the tiles that did finish stay unbiased.
    const bool merge = !cancelled_ || options_.keepCancelledPass;
    if (merge) {
        mergePass();
        samples_ += total.accepted;
        nonFinite_ += total.nonFinite;
    }
    rays_ += total.counters.rays;
    shadowRays_ += total.counters.shadowRays;
    seconds_ = seconds_ + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (cancelled_) return false;
    sppDone_ += samples;
    ++passes_;
    return true;
}

void Renderer::addSample(Pixel& px, const Radiance& L) {
    const Vec3 g = L.global();
    for (int c = 0; c < 3; ++c) {
        const double d = L.direct[c], ind = L.indirect[c], glob = g[c];
        px.direct[c] += d;
        px.indirect[c] += ind;
        px.sq[int(Term::Direct)][c] += d * d;
        px.sq[int(Term::Indirect)][c] += ind * ind;
        px.sq[int(Term::Global)][c] += glob * glob;
    }
    ++px.accepted;
}

void Renderer::renderTile(int x0, int y0, int x1, int y1, int samples, TraceCounters& counters, uint64_t& nonFinite,
                          uint64_t& accepted) {
    // Samples go to the tracer in batches of Accel::kPacket in the tile's pixel and sample order (a
    // row of pixels, or one pixel's samples), so their camera rays and first shadow rays are coherent
    // packets; each pixel still adds its samples in sample order.
    constexpr int K = Accel::kPacket;
    Ray rays[K];
    Rng rngs[K] = {Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0),
                   Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0), Rng(0, 0)};
    Pixel* owners[K];
    Radiance out[K];
    int n = 0;
    auto flush = [&] {
        tracer_.traceBatch(rays, rngs, n, counters, out);
        for (int j = 0; j < n; ++j) {
            const Radiance& L = out[j];
            if (!L.direct.isFinite() || !L.indirect.isFinite()) {
                ++nonFinite;
                continue;
            }
            addSample(*owners[j], L);
            ++accepted;
        }
        n = 0;
    };
    for (int y = y0; y < y1; ++y) {
        if (y % options_.rowStride != options_.rowOffset) continue;
        for (int x = x0; x < x1; ++x) {
            const uint64_t index = uint64_t(y) * uint64_t(options_.width) + uint64_t(x);
            Pixel& px = pass_[index];
            const uint64_t key = Rng::streamKey(options_.seed, index);
            for (int s = 0; s < samples; ++s) {
                Rng& rng = rngs[n] = Rng::ofStream(key, px.next++);
                const float jx = rng.uniform(), jy = rng.uniform();
                rays[n] = camera_.generate(x, y, jx, jy);
                owners[n] = &px;
                if (++n == K) flush();
            }
        }
    }
    if (n > 0) flush();
}

bool Renderer::runBidirectionalPass(int samples, TraceCounters& counters, uint64_t& nonFinite, uint64_t& accepted) {
    const int w = options_.width, h = options_.height, ts = std::max(1, options_.tileSize);
    const int tilesX = (w + ts - 1) / ts, tilesY = (h + ts - 1) / ts;
    const Light movable = scene_.movableLight >= 0 && scene_.movableLight < int(scene_.lights.size())
                              ? scene_.lights[size_t(scene_.movableLight)]
                              : Light{};
    std::vector<Radiance> own(size_t(w) * size_t(h));
    std::vector<std::vector<Splat>> splats(size_t(tilesX) * size_t(tilesY));
    tbb::combinable<TraceCounters> tileCounters;
    for (int s = 0; s < samples; ++s) {
        if (cancelled_) return false;
        // Every pixel is at the same sample index: iterations run in lockstep.
        // (a part may own no row at all: then its iterations count from the spp done).
        const uint64_t sample = options_.rowOffset < h ? pass_[size_t(options_.rowOffset) * size_t(w)].next
                                                       : uint64_t(sppDone_) + uint64_t(s);
        tbb::parallel_for(tbb::blocked_range<int>(0, tilesX * tilesY, 1), [&](const tbb::blocked_range<int>& r) {
            TraceCounters& c = tileCounters.local();
            for (int tile = r.begin(); tile < r.end(); ++tile) {
                std::vector<Splat>& out = splats[size_t(tile)];
                out.clear();
                const int x0 = (tile % tilesX) * ts, y0 = (tile / tilesX) * ts;
                for (int y = y0; y < std::min(h, y0 + ts); ++y) {
                    // A part of an image split by rows still traces every pixel's light path (its
                    // splats land anywhere) and the camera paths of its own rows only.
                    const bool mine = y % options_.rowStride == options_.rowOffset;
                    for (int x = x0; x < std::min(w, x0 + ts); ++x) {
                        const uint64_t index = uint64_t(y) * uint64_t(w) + uint64_t(x);
                        Rng rng(options_.seed, index, sample);
                        Rng lightRng = bdptLightRng(options_.seed, index, sample);
                        const Radiance L =
                            bdpt_->tracePixel(camera_, *importance_, x, y, movable, rng, lightRng, c, out, mine);
                        if (mine) own[index] = L;
                    }
                }
            }
        });
        // Splats in tile order, each tile's in pixel order: the same sums for any thread count.
        for (const std::vector<Splat>& tile : splats)
            for (const Splat& sp : tile) {
                own[sp.pixel].direct += sp.L.direct;
                own[sp.pixel].indirect += sp.L.indirect;
            }
        for (int y = options_.rowOffset; y < h; y += options_.rowStride) {
            for (int x = 0; x < w; ++x) {
                const size_t index = size_t(y) * size_t(w) + size_t(x);
                Pixel& px = pass_[index];
                ++px.next;
                const Radiance L = own[index];
                own[index] = Radiance{};
                if (!L.direct.isFinite() || !L.indirect.isFinite()) {
                    ++nonFinite;
                    continue;
                }
                addSample(px, L);
                ++accepted;
            }
        }
    }
    tileCounters.combine_each([&](const TraceCounters& c) {
        counters.rays += c.rays;
        counters.shadowRays += c.shadowRays;
    });
    return true;
}

void Renderer::mergePass() {
    std::lock_guard<std::mutex> lock(mutex_);
    pixels_.swap(pass_);
}

double Renderer::progress() const {
    return options_.spp > 0 ? std::min(1.0, double(sppDone_) / double(options_.spp)) : 1.0;
}

RenderSnapshot Renderer::snapshotOfPixels(const std::vector<Pixel>& pixels, int w, int h) {
    RenderSnapshot s;
    s.direct = Image(w, h);
    s.indirect = Image(w, h);
    s.global = Image(w, h);
    s.variance = Image(w, h);
    s.directVariance = Image(w, h);
    s.indirectVariance = Image(w, h);
    double sumMean = 0, sumVar = 0;
    for (size_t i = 0; i < pixels.size(); ++i) {
        const Pixel& p = pixels[i];
        if (p.accepted == 0) continue;
        const double inv = 1.0 / p.accepted;
        // Variance of the mean: (E[x²] − E[x]²) / (n − 1), clamped against rounding.
        auto varianceOfMean = [&](const double* sq, int c, double mean) {
            return p.accepted > 1 ? std::max(0.0, sq[c] * inv - mean * mean) / (p.accepted - 1) : 0.0;
        };
        for (int c = 0; c < 3; ++c) {
            const double d = p.direct[c] * inv, ind = p.indirect[c] * inv, g = d + ind;
            s.direct.data[3 * i + size_t(c)] = float(d);
            s.indirect.data[3 * i + size_t(c)] = float(ind);
            // Sum the stored floats so that global == direct + indirect holds exactly in the images.
            s.global.data[3 * i + size_t(c)] = float(d) + float(ind);
            const double var = varianceOfMean(p.sq[int(Term::Global)], c, g);
            s.variance.data[3 * i + size_t(c)] = float(var);
            s.directVariance.data[3 * i + size_t(c)] = float(varianceOfMean(p.sq[int(Term::Direct)], c, d));
            s.indirectVariance.data[3 * i + size_t(c)] = float(varianceOfMean(p.sq[int(Term::Indirect)], c, ind));
            sumMean += g;
            sumVar += var;
        }
    }
    // Pixel errors are independent, so the variance of the image mean is Σvar / (3wh)².
    const double count = 3.0 * w * h;
    s.relativeError = sumMean > 0 ? std::sqrt(sumVar) / count / (sumMean / count) : 0.0;
    return s;
}

RenderSnapshot Renderer::snapshot() const {
    RenderSnapshot s;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        s = snapshotOfPixels(pixels_, options_.width, options_.height);
    }
    s.passes = passes_;
    s.samples = samples_;
    s.nonFinite = nonFinite_;
    s.sppCompleted = sppDone_;
    s.seconds = seconds_;
    return s;
}

RenderSnapshot Renderer::snapshotOf(const RenderState& state) {
    if (state.pixels.size() != size_t(state.width) * size_t(state.height))
        throw std::invalid_argument("Renderer::snapshotOf: the state's pixel count is not width x height");
    RenderSnapshot s = snapshotOfPixels(state.pixels, state.width, state.height);
    s.passes = state.passes;
    s.samples = state.samples;
    s.nonFinite = state.nonFinite;
    s.sppCompleted = state.sppDone;
    s.seconds = state.seconds;
    return s;
}

RenderState Renderer::exportState() const {
    RenderState st;
    st.width = options_.width;
    st.height = options_.height;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        st.pixels = pixels_;
    }
    st.sppDone = sppDone_;
    st.passes = passes_;
    st.samples = samples_;
    st.rays = rays_;
    st.shadowRays = shadowRays_;
    st.nonFinite = nonFinite_;
    st.seconds = seconds_;
    return st;
}

void Renderer::restoreState(const RenderState& st) {
    if (st.width != options_.width || st.height != options_.height ||
        st.pixels.size() != size_t(st.width) * size_t(st.height))
        throw std::invalid_argument("Renderer::restoreState: the state is " + std::to_string(st.width) + "x" +
                                    std::to_string(st.height) + ", the renderer " + std::to_string(options_.width) + "x" +
                                    std::to_string(options_.height));
    {
        std::lock_guard<std::mutex> lock(mutex_);
        pixels_ = st.pixels;
    }
    sppDone_ = st.sppDone;
    passes_ = st.passes;
    samples_ = st.samples;
    rays_ = st.rays;
    shadowRays_ = st.shadowRays;
    nonFinite_ = st.nonFinite;
    seconds_ = st.seconds;
}

RenderStats Renderer::stats() const {
    RenderStats s;
    s.samples = samples_;
    s.rays = rays_;
    s.shadowRays = shadowRays_;
    s.nonFinite = nonFinite_;
    s.seconds = seconds_;
    return s;
}

}  // namespace rrf
