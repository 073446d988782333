// bench_direct: exact direct light (core/predict/exact_direct.h) per 256x256 frame, the estimator
// this session replaced against the one that replaced it, with the error of each measured against a
// converged exact direct image, in one run:
//
//   bench_direct [--quick] [--project P ...] [--samples 256] [--reference-samples 4096] [--frames 10]
//
// Per project (default: the bundled cornell-box and cornell-glossy, and cornell-glossy with its back
// wall sharpened to exponent 300 so that the lamp's highlight near its top is a narrow lobe):
//  - two references: the estimator before at --reference-samples (4096; --quick 1024) with two
//    seeds (its glossy estimate is independent of the lobe quadrature); their difference gives the
//    references' own noise;
//  - rows "before" (the replaced estimator, bench/exact_direct_before.h: every sample's shadow ray
//    traced one by one through Embree, glossy light by next-event estimation over the same samples),
//    "now, casters off" (every ray to Embree, in packets), and "now" (shadow casters, packets,
//    glossy lobe by quadrature), at --samples (256) and, for "now", also 64 (the default preset's);
//  - per row: wall-clock ms per frame (best of --frames; "before" best of 2) on all cores and the
//    process CPU ms of that frame (the machine may be shared: CPU time is the steadier figure), the
//    relative RMSE of the direct image against the first reference over the footprint-kept pixels
//    (core/predict/footprint_mask.h), the same with the reference's noise taken out (mean squared
//    error minus half the mean squared difference of the two references), and how the
//    (receiver, light) pairs were settled.
// The light sits where the project puts it. The G-buffer is made once per project and not timed
// (bench_predict times it with the networks).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <string>
#include <type_traits>
#include <vector>

#include "bench/bench_args.h"
#include "bench/exact_direct_before.h"
#include "core/eval/error_metrics.h"
#include "core/predict/exact_direct.h"
#include "core/predict/footprint_mask.h"
#include "core/predict/predictor.h"
#include "core/project/project.h"
#include "core/project/project_file.h"
#include "core/util/stopwatch.h"

using namespace rrf;

namespace bench_direct {

double cpuSeconds() {
    timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

struct Timed {
    Image image;
    double wall = 1e30, cpu = 0;  ///< best wall-clock seconds and the CPU seconds of that frame
    ShadowCasters::Counts settled;
    uint64_t shadowRays = 0;
};

/// The fastest of `frames` frames of `direct` (ExactDirect or bench::ExactDirectBefore).
template <class Direct>
Timed render(const Direct& direct, const GBuffer& gb, const Light& movable, int frames) {
    Timed f;
    for (int k = 0; k < frames; ++k) {
        ShadowCasters::Counts settled;
        uint64_t rays = 0;
        const double c0 = cpuSeconds();
        Stopwatch sw;
        Image im;
        if constexpr (std::is_same_v<Direct, ExactDirect>) {
            uint64_t nonFinite = 0;
            TraceCounters counters;
            im = direct.image(gb, movable, nonFinite, &settled, &counters);
            rays = counters.shadowRays;
            if (nonFinite) std::printf("  (%llu non-finite pixels)\n", (unsigned long long)nonFinite);
        } else {
            im = direct.image(gb, movable, rays);
        }
        const double wall = sw.seconds(), cpu = cpuSeconds() - c0;
        if (wall < f.wall) {
            f.wall = wall;
            f.cpu = cpu;
        }
        f.image = std::move(im);
        f.settled = settled;
        f.shadowRays = rays;
    }
    return f;
}

/// Relative RMSE of `p` against `r1` over `mask`, and the same with the references' noise removed:
/// E[(p − r1)²] = (p − t)² + Var(r1) and E[(r1 − r2)²] = 2 Var(r), per channel, weights 1/(|r1| + 0.01)².
void errors(const Image& p, const Image& r1, const Image& r2, const std::vector<uint32_t>& mask, double& raw,
            double& corrected, double& noise) {
    double se = 0, sn = 0;
    size_t count = 0;
    for (uint32_t i : mask) {
        const int x = int(i % uint32_t(p.width)), y = int(i / uint32_t(p.width));
        const Vec3 a = p.at(x, y), b = r1.at(x, y), c = r2.at(x, y);
        for (int k = 0; k < 3; ++k) {
            const double w = 1.0 / std::pow(std::fabs(double(b[k])) + kRelativeEpsilon, 2.0);
            se += w * std::pow(double(a[k]) - double(b[k]), 2.0);
            sn += w * 0.5 * std::pow(double(b[k]) - double(c[k]), 2.0);
            ++count;
        }
    }
    raw = std::sqrt(se / double(count));
    noise = std::sqrt(sn / double(count));
    corrected = std::sqrt(std::max(0.0, se - sn) / double(count));
}

struct Case {
    std::string name, project;
    float backWallExponent = 0.f;  ///< > 0: the glossy back wall's exponent replaced
};


int main(int argc, char** argv) {
    bool quick = false;
    std::vector<std::string> projects;
    int samples = 256, referenceSamples = 4096, frames = 10;
    CLI::App app{"exact direct light per 256x256 frame: the estimator before and now, time and error", "bench_direct"};
    app.add_flag("--quick", quick, "1024-sample references, 3 frames");
    app.add_option("--project", projects, "project or scene files (default: the bundled Cornell boxes)")
        ->type_name("FILE ...");
    app.add_option("--samples", samples, "light samples per pixel of the compared rows")->check(bench::kPositive);
    app.add_option("--reference-samples", referenceSamples, "light samples of the references")->check(bench::kPositive);
    app.add_option("--frames", frames, "frames per row; the fastest counts")->check(bench::kPositive);
    bench::parseArgs(app, argc, argv);
    if (quick) {
        referenceSamples = std::min(referenceSamples, 1024);
        frames = std::min(frames, 3);
    }
    std::vector<Case> cases;
    if (projects.empty()) {
        const std::string box = bench::projectOrDefault("", "bench_direct");
        const std::string glossy = bundledProject("cornell-glossy").string();
        cases = {{"cornell-box", box}, {"cornell-glossy", glossy}, {"cornell-glossy, back wall e = 300", glossy, 300.f}};
    } else {
        for (const std::string& p : projects) cases.push_back({p, p});
    }

    std::printf("bench_direct: 256x256, references at %d samples (the estimator before, two seeds)\n\n",
                referenceSamples);
    std::printf("| scene | estimator | samples | ms/frame | CPU ms | relative RMSE | noise-corrected | "
                "reference noise | unoccluded / occluded / clipped / traced | shadow rays/pixel |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
    for (const Case& c : cases) {
        Project proj = loadProjectOrScene(c.project);
        Scene& scene = proj.scene;
        if (c.backWallExponent > 0.f)
            for (Material& m : scene.materials)
                if (m.name == "glossy-back") m.exponent = c.backWallExponent;
        ModelSet none;
        const Predictor pred(scene, none, PredictionSettings{});
        const GBuffer gb = pred.gbuffer(scene.lightPosition(), 256, 256);
        const FootprintMask mask = footprintMask(gb);
        const Light movable = pred.tracer().movableLightAt(gb.lightPosition);
        size_t covered = 0;
        for (int32_t id : gb.object) covered += id >= 0;
        const Timed ref1 = render(bench::ExactDirectBefore(pred.tracer(), referenceSamples, 1001), gb, movable, 1);
        const Timed ref2 = render(bench::ExactDirectBefore(pred.tracer(), referenceSamples, 1002), gb, movable, 1);
        ExactDirect::Options noCasters;
        noCasters.proofs = false;
        struct Row {
            const char* what;
            int samples;
            int kind;  // 0: before, 1: now, 2: now without the casters
            int frames;
        };
        const Row rows[] = {{"before", samples, 0, 2},
                            {"now, casters off", samples, 2, std::min(frames, 3)},
                            {"now", samples, 1, frames},
                            {"now", 64, 1, frames}};
        for (const Row& r : rows) {
            const Timed f = r.kind == 0 ? render(bench::ExactDirectBefore(pred.tracer(), r.samples, 1), gb, movable, r.frames)
                                        : render(ExactDirect(pred.tracer(), r.samples, 1, r.kind == 2 ? noCasters : ExactDirect::Options{}),
                                                 gb, movable, r.frames);
            double raw, corrected, noise;
            errors(f.image, ref1.image, ref2.image, mask.kept, raw, corrected, noise);
            const ShadowCasters::Counts& s = f.settled;
            std::printf("| %s | %s | %d | %.1f | %.1f | %.5f | %.5f | %.5f | %llu / %llu / %llu / %llu | %.1f |\n",
                        c.name.c_str(), r.what, r.samples, 1e3 * f.wall, 1e3 * f.cpu, raw, corrected, noise,
                        (unsigned long long)s.unoccluded, (unsigned long long)s.occluded,
                        (unsigned long long)s.segments, (unsigned long long)s.rays,
                        double(f.shadowRays) / double(covered));
            std::fflush(stdout);
        }
    }
    std::printf("\nshadow rays/pixel: per object pixel, the proofs' rays and the clipped ones included.\n");
    std::printf("ms/frame: fastest of the frames, wall clock, all cores; CPU ms: that frame's process CPU time.\n"
                "relative RMSE: per channel, |d| / (|ref| + 0.01), over the footprint-kept pixels.\n"
                "before: the replaced estimator (every shadow ray to Embree one by one, glossy by NEE);\n"
                "now: shadow casters (proofs, clipped rays), 16-ray packets, glossy lobe by quadrature;\n"
                "casters off: every ray to Embree in 16-ray packets.\n");
    return 0;
}

}  // namespace bench_direct
