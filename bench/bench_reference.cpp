// Reference cost benchmark (issue 10): how long the reference store takes to render a reference of
// the Cornell box to a relative RMSE noise of 0.01 (global term, over the footprint mask, the noise
// figure of core/eval/reference_noise.h), and the noise on the way at 64, 256 and 1024 spp.
//
//   bench_reference [project.json] [--size 256] [--noise 0.01] [--spp-cap 65536] [--max-seconds S]
//                   [--threads N] [--estimators nee,bdpt]
//
// --estimators renders the same reference once per estimator (default: the project's setting), so the
// noise-against-time figures of the path tracer and the bidirectional tracer come from one run.
//
// It renders into a fresh temporary store (removed afterwards), so every run measures the whole cost.
// With --max-seconds the render is cancelled after S seconds and the spp and seconds to reach the
// target are extrapolated from the last noise with noise ∝ 1/√spp (printed as "extrapolated").
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <map>
#include <memory>
#include <thread>
#include <mutex>
#include <string>
#include <vector>

#include <unistd.h>

#include <tbb/global_control.h>

#include "bench/bench_args.h"
#include "core/eval/reference_store.h"
#include "core/pipeline/sweep.h"
#include "core/project/project.h"
#include "core/project/project_file.h"

using namespace rrf;
namespace fs = std::filesystem;

namespace bench_reference {

int main(int argc, char** argv) {
    CLI::App app{"Reference store: seconds and spp to reach a relative noise target"};
    std::string project;
    int size = 256, cap = 65536, threads = 0;
    double noise = 0.01, maxSeconds = 0;
    app.add_option("project", project, bench::kProjectHelp);
    app.add_option("--size", size, "image width and height")->check(bench::kPositive);
    app.add_option("--noise", noise, "relative RMSE noise to reach (global term)")->check(CLI::Range(1e-6, 10.0));
    app.add_option("--spp-cap", cap, "most samples per pixel")->check(CLI::Range(2, 1 << 24));
    app.add_option("--max-seconds", maxSeconds, "cancel after this many seconds and extrapolate (0 = never)")
        ->check(CLI::Range(0.0, 1e9));
    app.add_option("--threads", threads, "worker threads (0 = all cores)")->check(CLI::Range(0, 1024));
    std::vector<std::string> estimatorList;
    app.add_option("--estimators", estimatorList, "estimators to measure one after the other (default: the project's)")
        ->delimiter(',');
    bench::parseArgs(app, argc, argv);
    project = bench::projectOrDefault(project, "bench_reference");

    std::unique_ptr<tbb::global_control> limit;
    if (threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
    const Project p = loadProjectOrScene(project);
    std::vector<Estimator> estimators;
    for (const std::string& name : estimatorList) {
        const std::optional<Estimator> e = parseEstimator(name);
        if (!e) {
            std::fprintf(stderr, "bench_reference: --estimators: unknown estimator '%s' (known: %s)\n", name.c_str(),
                         estimatorNames());
            return 2;
        }
        estimators.push_back(*e);
    }
    if (estimators.empty()) estimators.push_back(p.render.estimator);
    auto measure = [&](Estimator estimator) -> bool {
        const fs::path dir = fs::temp_directory_path() / ("rrf_bench_reference_" + std::to_string(::getpid()));
        fs::remove_all(dir);
        ReferenceStore store(dir.string());
        RenderSettings render = p.render;
        render.estimator = estimator;
        const ReferenceKey key = ReferenceKey::of(p.scene, p.scene.lightPosition(), size, size, render);
        NoiseTarget target;
        target.relativeRmse = noise;
        target.sppCap = cap;
        target.sppPerPass = 16;
        std::printf("bench_reference: %s at %dx%d, %s, target relative noise %g (global term, footprint mask), cap %d spp, "
                    "%d spp per pass, %d hardware threads\n",
                    project.c_str(), size, size, estimatorName(key.estimator), noise, cap, target.sppPerPass,
                    int(std::thread::hardware_concurrency()));

        std::atomic<bool> cancel{false};
        std::mutex m;
        std::map<int, std::pair<double, double>> marks;  // spp -> (noise, seconds)
        std::vector<double> sppSeen, noiseSeen;
        ReferenceProgress last;
        const auto wallStart = std::chrono::steady_clock::now();
        // Process CPU time too: on a shared machine the wall time depends on the other load, CPU time / threads
        // is what the render costs on idle cores.
        const std::clock_t cpuStart = std::clock();
        const Reference r = store.obtain(
            p.scene, key, target, &cancel,
            [&](const ReferenceProgress& pr) {
                std::lock_guard<std::mutex> lock(m);
                last = pr;
                if (std::isfinite(pr.noise)) {
                    sppSeen.push_back(pr.spp);
                    noiseSeen.push_back(pr.noise);
                }
                for (int mark : {64, 256, 1024, 4096, 16384})
                    if (pr.spp == mark) {
                        marks[mark] = {pr.noise, pr.seconds};
                        std::printf("  %6d spp: relative noise %.4f after %.1f s (ETA to %g: %.0f s)\n", mark, pr.noise, pr.seconds,
                                    noise, pr.etaSeconds);
                        std::fflush(stdout);
                    }
                if (maxSeconds > 0 && pr.seconds >= maxSeconds) cancel = true;
            },
            {}, [](const std::string& line) { std::printf("  %s\n", line.c_str()); });
        // Wall time includes what the render time does not: the G-buffer, the noise checks and the save.
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
        const double cpu = double(std::clock() - cpuStart) / CLOCKS_PER_SEC;
        const int cores = threads > 0 ? threads : int(std::thread::hardware_concurrency());
        std::printf("\nwall %.1f s, process CPU %.1f s = %.1f s on %d idle cores (load average decides which one applies)\n", wall,
                    cpu, cpu / cores, cores);
        const std::optional<StoredReference> e = store.find(key);
        fs::remove_all(dir);
        if (!e) {
            std::printf("nothing rendered\n");
            return false;
        }
        const double reached = e->noise.relativeRmse[int(Term::Global)];
        const double slope = logLogSlope(sppSeen, noiseSeen);
        std::printf("\nlog-log slope of noise vs spp over the passes: %.3f (noise ∝ 1/√spp: -0.5)\n", slope);
        if (!r.cancelled && reached <= noise) {
            std::printf("RESULT: relative noise %.4f (target %g) reached at %d spp in %.1f s wall (%.1f s on %d idle cores), %dx%d, "
                        "measured\n",
                        reached, noise, e->spp, wall, cpu / cores, cores, size, size);
        } else {
            // noise ∝ 1/√spp: spp_needed = spp · (noise / target)², time in proportion.
            const double need = e->spp * (reached / noise) * (reached / noise);
            std::printf("RESULT: stopped at %d spp, %.1f s, relative noise %.4f; EXTRAPOLATED with noise ∝ 1/√spp: %.0f spp and "
                        "%.0f s wall (%.0f s on %d idle cores) to reach %g (%dx%d)\n",
                        e->spp, e->seconds, reached, need, wall * need / e->spp, cpu / cores * need / e->spp, cores, noise, size, size);
        }
        return true;
    };
    for (Estimator e : estimators) {
        if (!measure(e)) return 1;
        std::printf("\n");
    }
    return 0;
}

}  // namespace bench_reference
