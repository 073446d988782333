// Path-tracer benchmark: plain Embree rtcIntersect1 / rtcOccluded1 on the tracer's own rays versus
// the tracer itself, for 1 and 2 threads, in one run (ratios are only meaningful within a run on
// a shared machine).
//
//   bench_render [project-or-scene.json] [--spp N] [--width W --height H]
//
// Default: the bundled Cornell box at 256x256, NEE.
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <embree3/rtcore.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "bench/bench_args.h"
#include "core/scene/accel.h"
#include "core/scene/camera_rays.h"
#include "core/project/project.h"
#include "core/render/renderer.h"

using namespace rrf;
using Clock = std::chrono::steady_clock;

namespace bench_render {

double seconds(Clock::time_point a) { return std::chrono::duration<double>(Clock::now() - a).count(); }

/// Replays the logged rays through rtcIntersect1 (or rtcOccluded1); returns rays per second.
double plainEmbree(const Accel& accel, const std::vector<Ray>& rays, bool occluded, int repeats) {
    std::atomic<uint64_t> hits{0};
    const auto start = Clock::now();
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

    std::printf("| threads | rtcIntersect1 Mrays/s | rtcOccluded1 Mrays/s | Embree mix Mrays/s | tracer Msamples/s | tracer Mrays/s | tracer/Embree |\n");
    std::printf("|---:|---:|---:|---:|---:|---:|---:|\n");
    for (int threads : {1, 2}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
        const double ri = plainEmbree(accel, rays, false, 2);
        const double ro = plainEmbree(accel, shadowRays, true, 2);
        // Rate of plain Embree on the tracer's mix of closest-hit and shadow rays.
        const double mix = 1.0 / ((1.0 - shadowFraction) / ri + shadowFraction / ro);

        RenderOptions o;
        o.width = width;
        o.height = height;
        o.spp = spp;
        o.samplesPerPass = spp;
        Renderer renderer(scene, accel, o);
        renderer.run();
        const RenderStats st = renderer.stats();
        std::printf("| %d | %.2f | %.2f | %.2f | %.3f | %.2f | %.2f |\n", threads, ri / 1e6, ro / 1e6, mix / 1e6,
                    st.samplesPerSecond() / 1e6, st.raysPerSecond() / 1e6, st.raysPerSecond() / mix);
        std::fflush(stdout);
    }
    return 0;
}

}  // namespace bench_render
