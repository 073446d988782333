#include "app/cli/cli_common.h"

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <thread>
#include <utility>

#include <unistd.h>

#include "core/scene/coordinate_range.h"
#include "core/scene/scene_parse.h"
#include "core/project/project.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace rrf::cli {

namespace {
std::atomic<bool> g_interrupted{false};

extern "C" void onSignal(int sig) {
    if (g_interrupted.exchange(true)) {
        removeInFlightTemporaryFiles();  // the second signal kills at once: no half-written *.tmp left behind
        std::signal(sig, SIG_DFL);
        std::raise(sig);
    }
}

std::string formatSeconds(double s) {
    char buf[32];
    if (s < 60) std::snprintf(buf, sizeof buf, "%.0fs", s);
    else if (s < 3600) std::snprintf(buf, sizeof buf, "%dm%02ds", int(s) / 60, int(s) % 60);
    else std::snprintf(buf, sizeof buf, "%dh%02dm", int(s) / 3600, (int(s) / 60) % 60);
    return buf;
}
}  // namespace

std::atomic<bool>& installInterruptHandler() {
    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);
    return g_interrupted;
}

std::unique_ptr<tbb::global_control> limitThreads(int threads) {
    if (threads <= 0) return nullptr;
    return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(threads));
}

void checkLightPosition(const Scene& scene, const Vec3& p, const std::string& flag) {
    if (scene.lights.empty()) throw InputError("command line", flag, "the scene has no light to move");
    if (const std::string why = lightPlacementProblem(scene.lights[size_t(scene.movableLight)], p); !why.empty())
        throw InputError("command line", flag, why);
}

void refuseOverwritingInputs(const std::string& output, const std::vector<std::string>& inputs, const std::string& flag) {
    if (output.empty()) return;
    for (const std::string& in : inputs) {
        std::error_code ec;
        if (in.empty() || !std::filesystem::equivalent(output, in, ec) || ec) continue;
        throw InputError("command line", flag,
                         "'" + output + "' is the input '" + in + "' (the same file): an output must not replace an input");
    }
}

std::vector<std::string> projectInputs(const Project& project) {
    std::vector<std::string> files{project.path};
    if (!project.sceneRef.empty()) files.push_back(resolvePath(directoryOf(project.path), project.sceneRef));
    return files;
}

std::string outputPath(const std::string& dir, const std::string& name) {
    return (std::filesystem::path(dir) / name).string();
}

void writeReported(const std::string& file, const std::string& text) {
    writeFileAtomically(file, text);
    std::printf("wrote %s\n", file.c_str());
}

std::string errorMessage(const std::exception& e) {
    const auto* setting = dynamic_cast<const SettingError*>(&e);
    if (!setting) return e.what();
    // Core names settings, not flags (core/util/error.h); each one core can name, and the flag that sets it.
    static const std::pair<const char*, const char*> kFlags[] = {
        {"shard", "--shard"},
        {"sweep values", "--values"},
        {"sweep dimension", "--what"},
        {"grid and directions", "--grid/--dirs"},
        {"image size", "--width/--height"},
    };
    for (const auto& [name, flag] : kFlags)
        if (setting->setting() == name) return std::string("command line: ") + flag + ": " + setting->detail();
    return e.what();
}

void runWithProgress(const std::string& label, const std::function<void()>& work,
                     const std::function<std::pair<double, std::string>()>& progress,
                     const std::function<void()>& cancel) {
    std::atomic<bool>& interrupted = installInterruptHandler();
    std::exception_ptr error;
    std::atomic<bool> done{false};
    std::thread worker([&] {
        try {
            work();
        } catch (...) {
            error = std::current_exception();
        }
        done = true;
    });
    const bool tty = ::isatty(STDERR_FILENO);
    const auto start = std::chrono::steady_clock::now();
    int lastDecile = -1;
    bool cancelled = false;
    while (!done) {
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
        if (interrupted && !cancelled) {
            cancelled = true;
            cancel();
            std::fprintf(stderr, "\n%s: interrupted, stopping cleanly...\n", label.c_str());
        }
        const auto [fraction, text] = progress();
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const std::string eta = fraction > 0.01 ? formatSeconds(elapsed * (1.0 - fraction) / fraction) : "?";
        if (tty) {
            const int width = 30, filled = int(fraction * width);
            std::fprintf(stderr, "\r%s [%s%s] %5.1f%% ETA %s %s   ", label.c_str(), std::string(size_t(filled), '#').c_str(),
                         std::string(size_t(width - filled), ' ').c_str(), 100.0 * fraction, eta.c_str(), text.c_str());
            std::fflush(stderr);
        } else if (int(fraction * 10) > lastDecile) {
            lastDecile = int(fraction * 10);
            std::fprintf(stderr, "%s: %3.0f%% (ETA %s) %s\n", label.c_str(), 100.0 * fraction, eta.c_str(), text.c_str());
        }
    }
    worker.join();
    if (tty) std::fprintf(stderr, "\n");
    if (error) std::rethrow_exception(error);
}

}  // namespace rrf::cli
