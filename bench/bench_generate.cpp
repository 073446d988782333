// Data-generator benchmark, in one run (ratios are only meaningful within a run on a shared machine):
//
//  1. throughput: records/s, path samples/s and rays/s of DataGenerator::run on a small grid versus
//     the plain Renderer's samples/s and rays/s. A generator path sample is one PathTracer::shade()
//     call (the record's first ray is shot once and shared by its spp paths), a renderer sample is
//     a camera ray plus shade(), so rays/s is the like-for-like measure of bookkeeping overhead;
//  2. memory: the paper preset's Cornell-box data (15³ grid, 1200 directions, about 4 million records) with
//     1 path per record (memory does not depend on spp): time, peak resident memory (getrusage
//     max RSS) after generation and after writing, and the dataset file size.
//
//   bench_generate [project-or-scene.json] [--grid nx,ny,nz] [--dirs N] [--spp N]
//                  [--render-spp N] [--width W --height H]
//                  [--mem-grid nx,ny,nz] [--mem-dirs N] [--no-memory] [--out file.rrfd]
//
// Defaults: the bundled Cornell box; throughput grid 6,6,6 × 200 directions × 16 spp; render 256×256
// at 4 spp; memory run 15,15,15 × 1200 × 1 spp written to a temporary file (removed afterwards).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <unistd.h>

#include "bench/bench_args.h"
#include "core/project/project_file.h"
#include "core/data/dataset_header_json.h"
#include "core/scene/accel.h"
#include "core/data/data_generator.h"
#include "core/util/text_format.h"
#include "core/data/dataset_file.h"
#include "core/project/project.h"
#include "core/render/renderer.h"

using namespace rrf;
using Clock = std::chrono::steady_clock;

namespace bench_generate {

double seconds(Clock::time_point a) { return std::chrono::duration<double>(Clock::now() - a).count(); }

/// Peak resident set size of this process so far, in MiB (Linux reports ru_maxrss in KiB).
double maxRssMiB() {
    rusage u{};
    ::getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) / 1024.0;
}

/// Binds `--<name> nx,ny,nz` to the grid of `s` (three positive integers).
void addGridOption(CLI::App& app, const std::string& name, SamplingSettings& s, std::vector<int>& grid, const char* help) {
    grid = {s.nx, s.ny, s.nz};
    app.add_option(name, grid, help)
        ->delimiter(',')
        ->expected(3)
        ->type_name("NX,NY,NZ")
        ->check(bench::kPositive)
        ->default_str(std::to_string(s.nx) + "," + std::to_string(s.ny) + "," + std::to_string(s.nz));
}


int main(int argc, char** argv) {
    std::string input, out;
    SamplingSettings gen;
    gen.nx = gen.ny = gen.nz = 6;
    gen.directions = 200;
    gen.spp = 16;
    SamplingSettings mem;  // the report's run (the paper preset's data): 15³ grid, 1200 directions
    mem.nx = mem.ny = mem.nz = 15;
    mem.directions = 1200;
    mem.spp = 1;
    int renderSpp = 4, width = 256, height = 256;
    bool noMemory = false;
    std::vector<int> genGrid, memGrid;

    CLI::App app{"Data-generator benchmark: generator versus renderer throughput, and the memory of the paper preset's data",
                 "bench_generate"};
    app.add_option("project", input, bench::kProjectHelp);
    addGridOption(app, "--grid", gen, genGrid, "jitter grid of the throughput run");
    app.add_option("--dirs", gen.directions, "directions per cell of the throughput run")->check(bench::kPositive)->capture_default_str();
    app.add_option("--spp", gen.spp, "paths per record of the throughput run")->check(bench::kPositive)->capture_default_str();
    app.add_option("--render-spp", renderSpp, "samples per pixel of the renderer run")->check(bench::kPositive)->capture_default_str();
    app.add_option("--width", width, "renderer image width")->check(bench::kPositive)->capture_default_str();
    app.add_option("--height", height, "renderer image height")->check(bench::kPositive)->capture_default_str();
    addGridOption(app, "--mem-grid", mem, memGrid, "jitter grid of the memory run");
    app.add_option("--mem-dirs", mem.directions, "directions per cell of the memory run")->check(bench::kPositive)->capture_default_str();
    app.add_flag("--no-memory", noMemory, "skip the memory run");
    app.add_option("--out", out, "dataset file of the memory run (default: a temporary file, removed afterwards)");
    bench::parseArgs(app, argc, argv);
    input = bench::projectOrDefault(input, "bench_generate");
    gen.nx = genGrid[0], gen.ny = genGrid[1], gen.nz = genGrid[2];
    mem.nx = memGrid[0], mem.ny = memGrid[1], mem.nz = memGrid[2];
    // Fixed paths per record (no adaptive sampling), so records/s is measured at exactly --spp paths
    // and the memory run's 1 path stays 1.
    gen.maxSpp = gen.spp;
    mem.maxSpp = mem.spp;
    const bool memory = !noMemory;

    const Project project = loadProjectOrScene(input);
    const Scene& scene = project.scene;
    std::printf("bench_generate: %s, %ld hardware threads\n\n", input.c_str(), ::sysconf(_SC_NPROCESSORS_ONLN));

    // 1. Renderer: samples/s and rays/s at width × height.
    const Accel accel(scene);
    RenderOptions ro;
    ro.width = width;
    ro.height = height;
    ro.spp = renderSpp;
    Renderer renderer(scene, accel, ro);
    renderer.run();
    const RenderStats rs = renderer.stats();

    // 2. Generator throughput.
    const DataGenerator generator(scene, gen);
    const GeneratedData g = generator.run();
    const uint64_t records = datasetHeader(g).at("stats").at("records").get<uint64_t>();
    const double genRaysPerS = double(g.stats.rays + g.stats.shadowRays) / g.seconds;

    std::printf("| measurement | work | time (s) | records/s | path samples/s | rays/s (incl. shadow) |\n");
    std::printf("|---|---|---:|---:|---:|---:|\n");
    std::printf("| renderer %dx%d, %d spp | %s samples | %.2f | - | %s | %s |\n", width, height, renderSpp,
                humanCount(double(rs.samples)).c_str(), rs.seconds, humanCount(rs.samplesPerSecond()).c_str(),
                humanCount(rs.raysPerSecond()).c_str());
    std::printf("| generator grid %dx%dx%d, %d dirs, %d spp | %s records, %s paths | %.2f | %s | %s | %s |\n", gen.nx,
                gen.ny, gen.nz, gen.directions, gen.spp, humanCount(double(records)).c_str(), humanCount(double(g.stats.paths)).c_str(),
                g.seconds, humanCount(double(records) / g.seconds).c_str(), humanCount(double(g.stats.paths) / g.seconds).c_str(),
                humanCount(genRaysPerS).c_str());
    std::printf("| generator / renderer | | | | %.2fx | %.2fx |\n",
                (double(g.stats.paths) / g.seconds) / rs.samplesPerSecond(), genRaysPerS / rs.raysPerSecond());

    if (!memory) return 0;
    // 3. Memory of the paper preset's data (spp 1), then the written file.
    const bool tempOut = out.empty();
    if (tempOut) out = (std::filesystem::temp_directory_path() / ("bench_generate_" + std::to_string(::getpid()) + ".rrfd")).string();
    const double rssBefore = maxRssMiB();
    const DataGenerator big(scene, mem);
    const auto start = Clock::now();
    GeneratedData d = big.run();
    const double genSeconds = seconds(start);
    const double rssGenerated = maxRssMiB();
    const auto writeStart = Clock::now();
    writeDataset(out, datasetHeader(d), d.sceneHash, d.perObject);
    const double writeSeconds = seconds(writeStart);
    const double rssWritten = maxRssMiB();
    const uint64_t bigRecords = datasetHeader(d).at("stats").at("records").get<uint64_t>();
    const double fileMiB = double(std::filesystem::file_size(out)) / (1024.0 * 1024.0);
    const double payloadMiB = double(bigRecords) * big.layout().floatsPerRecord() * 4.0 / (1024.0 * 1024.0);
    std::printf("\n| paper preset's data (grid %dx%dx%d, %d dirs, spp %d) | value |\n|---|---:|\n", mem.nx, mem.ny, mem.nz,
                mem.directions, mem.spp);
    std::printf("| records | %llu (%s) |\n", (unsigned long long)bigRecords, humanCount(double(bigRecords)).c_str());
    std::printf("| cells kept / dropped inside / dropped outside | %llu / %llu / %llu |\n",
                (unsigned long long)(mem.cellCount() - datasetHeader(d).at("stats").at("cells_dropped_inside_object").get<uint64_t>() -
                                     datasetHeader(d).at("stats").at("cells_dropped_outside_scene").get<uint64_t>()),
                (unsigned long long)datasetHeader(d).at("stats").at("cells_dropped_inside_object").get<uint64_t>(),
                (unsigned long long)datasetHeader(d).at("stats").at("cells_dropped_outside_scene").get<uint64_t>());
    std::printf("| generation time | %.2f s (%s records/s) |\n", genSeconds, humanCount(double(bigRecords) / genSeconds).c_str());
    std::printf("| write time | %.2f s |\n", writeSeconds);
    std::printf("| payload (records x %d floats x 4 B) | %.1f MiB |\n", big.layout().floatsPerRecord(), payloadMiB);
    std::printf("| dataset file size | %.1f MiB |\n", fileMiB);
    std::printf("| max RSS before the run | %.1f MiB |\n", rssBefore);
    std::printf("| max RSS after generation | %.1f MiB (%.2fx payload) |\n", rssGenerated, rssGenerated / payloadMiB);
    std::printf("| max RSS after writing | %.1f MiB (%.2fx payload) |\n", rssWritten, rssWritten / payloadMiB);
    if (tempOut) std::filesystem::remove(out);
    return 0;
}

}  // namespace bench_generate
