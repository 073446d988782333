// Path-tracer benchmark: plain Embree rtcIntersect1 / rtcOccluded1 on the tracer's own rays versus
// the tracer itself, for 1 and 2 threads, in one run (ratios are only meaningful within a run on
// a shared machine). The baseline stays one ray per call on purpose: it is what the tracer's rays
// cost without the tracer, whereas the tracer may trace its coherent rays (camera rays, their
// shadow rays) as packets, which is part of what is measured. Each ratio is given by wall time and
// by CPU time: on a machine shared with other work only the second counts just the time this
// process ran.
//
// What the ratio compares, exactly:
// - "The same rays" means the same distribution, not the same samples: the baseline replays the
//   rays PathTracer::trace() shoots for 2 samples per pixel (seed 99), split into the closest-hit
//   and the shadow queries, each list in the order the paths shot them; the tracer is then timed
//   rendering --spp samples per pixel (the renderer's seed) with traceBatch().
// - The baseline's rate is the harmonic mix of the two query kinds weighted by the logged shadow
//   fraction, each timed one ray per call, over 4096-ray chunks on the same thread count.
// - The tracer's time is the Renderer's pass: camera rays, its own math (BSDF and light sampling,
//   hit records, ray offsets), the analytic test of the movable light against every query (that
//   light is not in the BVH, so the baseline never pays for it), and the per-pixel sums. Its ray
//   count is the same two kinds of query as the log's.
// - The tracer runs as it would for a user: its lockstep vertices as the widest SIMD lanes the build
//   and the CPU have (render/path_lanes.h); further rows have the narrower lanes and the portable
//   lockstep on the same machine, for the same thread count in the same run.
//
//   bench_render [project-or-scene.json] [--spp N] [--width W --height H]
//
// Default: the bundled Cornell box at 256x256, NEE.
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <string>
#include <vector>

#include <embree3/rtcore.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "bench/bench_args.h"
#include "core/project/project_file.h"
#include "core/scene/accel.h"
#include "core/scene/camera_rays.h"
#include "core/project/project.h"
#include "core/render/renderer.h"

using namespace rrf;
using Clock = std::chrono::steady_clock;

namespace bench_render {

double seconds(Clock::time_point a) { return std::chrono::duration<double>(Clock::now() - a).count(); }

/// CPU seconds of the whole process: on a machine shared with other work, the time this process
/// actually ran, which wall time is not.
double cpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

/// A rate in rays per second, by wall time and by CPU time.
struct Rate {
    double wall = 0, cpu = 0;
};

/// Replays the logged rays through rtcIntersect1 (or rtcOccluded1); returns rays per second.
Rate plainEmbree(const Accel& accel, const std::vector<Ray>& rays, bool occluded, int repeats) {
    std::atomic<uint64_t> hits{0};
    const auto start = Clock::now();
    const double cpuStart = cpuSeconds();
    for (int rep = 0; rep < repeats; ++rep) {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
            RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            uint64_t local = 0;
            for (size_t i = r.begin(); i < r.end(); ++i) {
                const Ray& ray = rays[i];
                RTCRayHit rh;
                rh.ray.org_x = ray.origin.x; rh.ray.org_y = ray.origin.y; rh.ray.org_z = ray.origin.z;
                rh.ray.dir_x = ray.dir.x; rh.ray.dir_y = ray.dir.y; rh.ray.dir_z = ray.dir.z;
                rh.ray.tnear = ray.tmin; rh.ray.tfar = ray.tmax;
                rh.ray.time = 0.f; rh.ray.mask = 0xFFFFFFFFu; rh.ray.id = 0; rh.ray.flags = 0;
                if (occluded) {
                    rtcOccluded1(accel.handle(), &ctx, &rh.ray);
                    local += rh.ray.tfar < 0.f;
                } else {
                    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                    rtcIntersect1(accel.handle(), &ctx, &rh);
                    local += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
                }
            }
            hits += local;
        });
    }
    const double s = seconds(start), cpu = cpuSeconds() - cpuStart;
    if (hits == 0) std::printf("(no hits?)\n");
    return {double(rays.size()) * repeats / s, double(rays.size()) * repeats / cpu};
}

/// The same rays as incoherent packets of 16 consecutive logged rays (rtcIntersect16 /
/// rtcOccluded16), single-threaded: what packets buy on rays that do not share an origin. Not the
/// baseline of the ratio, which stays one ray per call.
double packetEmbree(const Accel& accel, const std::vector<Ray>& rays, bool occluded, int repeats) {
    uint64_t hits = 0;
    const auto start = Clock::now();
    for (int rep = 0; rep < repeats; ++rep)
        for (size_t b = 0; b < rays.size(); b += 16) {
            const int n = int(std::min<size_t>(16, rays.size() - b));
            RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
            alignas(64) RTCRayHit16 rh;
            alignas(64) int valid[16];
            for (int i = 0; i < 16; ++i) {
                const Ray& ray = rays[b + size_t(i < n ? i : 0)];
                valid[i] = i < n ? -1 : 0;
                rh.ray.org_x[i] = ray.origin.x; rh.ray.org_y[i] = ray.origin.y; rh.ray.org_z[i] = ray.origin.z;
                rh.ray.dir_x[i] = ray.dir.x; rh.ray.dir_y[i] = ray.dir.y; rh.ray.dir_z[i] = ray.dir.z;
                rh.ray.tnear[i] = ray.tmin; rh.ray.tfar[i] = ray.tmax;
                rh.ray.time[i] = 0.f; rh.ray.mask[i] = 0xFFFFFFFFu; rh.ray.id[i] = unsigned(i); rh.ray.flags[i] = 0;
                rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
                rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
            }
            if (occluded) rtcOccluded16(valid, accel.handle(), &ctx, &rh.ray);
            else rtcIntersect16(valid, accel.handle(), &ctx, &rh);
            for (int i = 0; i < n; ++i)
                hits += occluded ? rh.ray.tfar[i] < 0.f : rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
        }
    const double s = seconds(start);
    if (hits == 0) std::printf("(no hits?)\n");
    return double(rays.size()) * repeats / s;
}

int main(int argc, char** argv) {
    std::string input;
    int spp = 16, width = 256, height = 256;
    CLI::App app{"Path-tracer benchmark: plain Embree rays versus the tracer, 1 and 2 threads", "bench_render"};
    app.add_option("project", input, bench::kProjectHelp);
    app.add_option("--spp", spp, "samples per pixel of the tracer run")->check(bench::kPositive)->capture_default_str();
    app.add_option("--width", width, "image width")->check(bench::kPositive)->capture_default_str();
    app.add_option("--height", height, "image height")->check(bench::kPositive)->capture_default_str();
    bench::parseArgs(app, argc, argv);
    input = bench::projectOrDefault(input, "bench_render");
    const Project project = loadProjectOrScene(input);
    const Scene& scene = project.scene;
    const Accel accel(scene);

    // 1. The tracer's own ray distribution: 2 spp over the whole image, logged.
    std::vector<Ray> rays, shadowRays;
    {
        PathTracer tracer(scene, accel, Estimator::NEE, 64);
        CameraRays cam(scene.camera, width, height);
        TraceCounters c;
        c.rayLog = &rays;
        c.shadowRayLog = &shadowRays;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                for (int s = 0; s < 2; ++s) {
                    Rng rng(99, uint64_t(y * width + x), uint64_t(s));
                    const float jx = rng.uniform(), jy = rng.uniform();
                    tracer.trace(cam.generate(x, y, jx, jy), rng, c);
                }
    }
    const double shadowFraction = double(shadowRays.size()) / double(rays.size() + shadowRays.size());
    std::printf("scene: %s, %dx%d, NEE; logged %zu closest-hit rays and %zu shadow rays (%.2f rays per sample)\n\n",
                input.c_str(), width, height, rays.size(), shadowRays.size(),
                double(rays.size() + shadowRays.size()) / (2.0 * width * height));

    std::printf("| threads | path loop | rtcIntersect1 Mrays/s | rtcOccluded1 Mrays/s | Embree mix Mrays/s | tracer Msamples/s | tracer Mrays/s "
                "| tracer/Embree | tracer/Embree by CPU time |\n");
    std::printf("|---:|---|---:|---:|---:|---:|---:|---:|---:|\n");
    double ratio[3] = {0, 0, 0}, cpuRatio[3] = {0, 0, 0}, portable[3] = {0, 0, 0}, narrower[3] = {0, 0, 0};
    path_lanes::Isa used = path_lanes::Isa::None;
    for (int threads : {1, 2}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
        const Rate ri = plainEmbree(accel, rays, false, 2);
        const Rate ro = plainEmbree(accel, shadowRays, true, 2);
        // Rate of plain Embree on the tracer's mix of closest-hit and shadow rays.
        auto mixOf = [&](double i, double o) { return 1.0 / ((1.0 - shadowFraction) / i + shadowFraction / o); };
        const double mix = mixOf(ri.wall, ro.wall), cpuMix = mixOf(ri.cpu, ro.cpu);

        // The tracer as it runs (its lanes where the CPU has them), then, where that was the lanes,
        // the portable lockstep on the same machine in the same run.
        std::vector<path_lanes::Isa> loops;
        for (path_lanes::Isa isa : {path_lanes::Isa::Avx512, path_lanes::Isa::Avx2, path_lanes::Isa::None})
            if (path_lanes::isaSupported(isa)) loops.push_back(isa);
        for (path_lanes::Isa isa : loops) {
            const bool lanes = isa == loops.front();
            RenderOptions o;
            o.width = width;
            o.height = height;
            o.spp = spp;
            o.samplesPerPass = spp;
            Renderer renderer(scene, accel, o);
            if (!lanes) {
                if (renderer.tracer().lanes() == path_lanes::Isa::None) break;
                renderer.setLanes(isa);
            }
            const double cpuStart = cpuSeconds();
            renderer.run();
            const double cpu = cpuSeconds() - cpuStart;
            const RenderStats st = renderer.stats();
            const double r = st.raysPerSecond() / mix, cr = double(st.rays + st.shadowRays) / cpu / cpuMix;
            if (lanes) {
                ratio[threads] = r;
                cpuRatio[threads] = cr;
                used = renderer.tracer().lanes();
            } else if (isa == path_lanes::Isa::None) {
                portable[threads] = r;
            } else {
                narrower[threads] = r;
            }
            std::printf("| %d | %s | %.2f | %.2f | %.2f | %.3f | %.2f | %.2f | %.2f |\n", threads,
                        path_lanes::isaName(renderer.tracer().lanes()), ri.wall / 1e6, ro.wall / 1e6,
                        mix / 1e6, st.samplesPerSecond() / 1e6, st.raysPerSecond() / 1e6, r, cr);
            std::fflush(stdout);
        }
    }
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        std::printf("\nthe same rays as incoherent packets of 16, 1 thread: rtcIntersect16 %.2f Mrays/s, rtcOccluded16 %.2f "
                    "Mrays/s\n",
                    packetEmbree(accel, rays, false, 2) / 1e6, packetEmbree(accel, shadowRays, true, 2) / 1e6);
    }
    // The metric (issue 28 item 4): the tracer's ray rate over plain Embree's on the same rays.
    std::printf("\ntracer/Embree on the same rays (target >= 0.8): %.2f at 1 thread, %.2f at 2 threads; by CPU time "
                "%.2f and %.2f\n",
                ratio[1], ratio[2], cpuRatio[1], cpuRatio[2]);
    std::printf("with the %s", path_lanes::isaName(used));
    if (used == path_lanes::Isa::Avx512)
        std::printf("; the AVX2 lanes (CPUs without AVX-512): %.2f at 1 thread, %.2f at 2 threads", narrower[1], narrower[2]);
    if (used != path_lanes::Isa::None)
        std::printf("; the portable lockstep (builds without the lanes): %.2f at 1 thread, %.2f at 2 threads", portable[1],
                    portable[2]);
    else
        std::printf(" lockstep: this build or CPU has no lanes");
    std::printf("\n");
    return 0;
}

}  // namespace bench_render
