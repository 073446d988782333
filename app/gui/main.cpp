// rrf-workbench [project.json] [--frames N] [--screenshot out.png] [--script steps.json] [--size WxH]
//
// Opens the workbench on a project (by default the user's workspace copy of the bundled Cornell box
// of the data directory, see app/gui/user_workspace.h and core/util/data_dir.h, which also holds
// the shaders). --frames N draws N frames
// (after the script, if any) and exits; --screenshot writes the last frame to a PNG. The exit status
// is non-zero if the project cannot be opened, the script fails or the screenshot cannot be written
// in these automated modes.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "core/nn/mlp_kernel.h"
#include "app/gui/script.h"
#include "app/gui/user_config.h"
#include "app/gui/user_workspace.h"
#include "app/gui/window.h"
#include "app/gui/workbench.h"
#include "core/util/data_dir.h"
#include "core/util/image_io.h"

namespace {

struct Args {
    std::string project;  ///< empty: the bundled Cornell box from the data directory
    int frames = -1;
    std::string screenshot, script;
    int width = 1600, height = 1000;  ///< the window's size (--size)
};

/// Parses argv into `a`. Returns false with the exit status in `exitCode` when the program should
/// stop: 0 after --help, 2 for a usage error (CLI11 prints the message).
bool parse(int argc, char** argv, Args& a, int& exitCode) {
    CLI::App app{"RRF Workbench: learn global illumination with radiance regression functions", "rrf-workbench"};
    app.add_option("project", a.project, "project or scene file (default: the bundled Cornell box)");
    app.add_option("--frames", a.frames, "draw N frames (after the script), then exit")
        ->type_name("N")
        ->check(CLI::Range(1, 1000000));
    app.add_option("--screenshot", a.screenshot, "write the last frame to a PNG file")->type_name("FILE");
    app.add_option("--script", a.script, "run a scripted session (JSON array of steps) first")->type_name("FILE");
    std::string size;
    app.add_option("--size", size, "window size, e.g. 1280x720 (default 1600x1000)")
        ->type_name("WxH")
        ->check([](const std::string& v) -> std::string {
            int w = 0, h = 0;
            char x = 0, rest = 0;
            if (std::sscanf(v.c_str(), "%d%c%d%c", &w, &x, &h, &rest) != 3 || x != 'x' || w < 320 || h < 240 ||
                w > 16384 || h > 16384)
                return "expected WIDTHxHEIGHT with 320 <= WIDTH, 240 <= HEIGHT, both at most 16384, got '" + v + "'";
            return {};
        });
    try {
        app.parse(argc, argv);
        if (!size.empty()) std::sscanf(size.c_str(), "%dx%d", &a.width, &a.height);
        return true;
    } catch (const CLI::ParseError& e) {
        const int cliStatus = app.exit(e);
        exitCode = cliStatus == 0 ? 0 : 2;
        return false;
    }
}

bool writeScreenshot(const rrf::Window& window, const std::string& path, std::string& error) {
    try {
        const rrf::Image shot = window.readBackBuffer();
        rrf::writeImage(path, shot, rrf::ImageFormat::PNG);
        return true;
    } catch (const std::exception& e) {
        error = e.what();
        return false;
    }
}

}  // namespace

int main(int argc, char** argv) {
    Args args;
    int exitCode = 0;
    if (!parse(argc, argv, args, exitCode)) return exitCode;
    // --script or --screenshot without --frames still ends by itself: one frame after the script.
    const bool automated = args.frames > 0 || !args.script.empty() || !args.screenshot.empty();
    if (automated && args.frames < 0) args.frames = 1;

    rrf::Script script;
    std::string error;
    if (!args.script.empty() && !script.load(args.script, error)) {
        std::fprintf(stderr, "rrf-workbench: %s\n", error.c_str());
        return 2;
    }

    // The shaders and the bundled projects: a program without them is a broken build or installation,
    // so say so (and where it looked) before opening a window.
    std::string dataDir;
    try {
        // The MLP kernel now, so an RRF_MLP_KERNEL this CPU cannot run stops here, not in a job.
        rrf::mlpKernel();
        dataDir = rrf::dataDir().string();
        if (args.project.empty()) {
            // The bundled project is read-only data: work happens in the user's workspace copy.
            bool created = false;
            args.project = rrf::userWorkspaceProject(
                rrf::bundledProject(rrf::kDefaultProject).string(), created);
            std::printf("rrf-workbench: %s the workspace copy of the bundled project: %s\n",
                        created ? "created" : "opening", args.project.c_str());
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rrf-workbench: %s\n", e.what());
        return 1;
    }

    const std::string configDir = rrf::userConfigDir();
    rrf::Window window;
    if (!window.create(args.width, args.height, "RRF Workbench", configDir, !automated, error)) {
        std::fprintf(stderr, "rrf-workbench: %s\n", error.c_str());
        return 1;
    }

    int status = 0;
    {
        rrf::Workbench wb(configDir);
        wb.state().log.info("data directory: " + dataDir);
        wb.startGlWorker();
        if (!wb.openProject(args.project) && automated) {
            std::fprintf(stderr, "rrf-workbench: cannot open %s\n", args.project.c_str());
            status = 1;
        }
        bool scriptDone = script.empty();
        int framesDrawn = 0;
        std::string title;
        int eventFrames = 0;  // frames still drawn at full rate after an event
        int slowFrames = 0;   // frames over 100 ms, and the longest frame (seconds)
        double longestFrame = 0.0;
        std::string slowLog;  // "frame at T s: X ms" of each slow frame, for CI's log
        const auto runStart = std::chrono::steady_clock::now();
        while (status == 0) {
            // Automated runs poll quickly. Interactive ones redraw at 30 Hz while something changes
            // by itself (a job, a held mouse button) and for a few frames after input (ImGui settles
            // hover and click states over 2-3 frames); otherwise they wait for events, waking twice
            // a second, so an idle workbench leaves the cores to whatever else runs.
            // The first frame does not wait: the window is shown once it is drawn (Window::swap).
            const double timeout = wb.frameStats().recent().empty() ? 0.0
                                   : automated                      ? 0.005
                                   : (wb.busy() || eventFrames > 0) ? 1.0 / 30.0
                                                                    : 0.5;
            if (window.waitEvents(timeout)) eventFrames = 3;
            else if (eventFrames > 0) --eventFrames;
            const auto frameStart = std::chrono::steady_clock::now();
            window.beginFrame();
            wb.frame();
            if (!scriptDone) {
                const rrf::Script::Status s = script.step(wb);
                if (s == rrf::Script::Status::Failed) {
                    std::fprintf(stderr, "rrf-workbench: %s\n", script.error().c_str());
                    status = 1;
                }
                scriptDone = s != rrf::Script::Status::Running;
            }
            window.render();

            const std::string requested = wb.takeScreenshotRequest();
            if (!requested.empty()) {
                if (writeScreenshot(window, requested, error))
                    wb.state().notify(rrf::panels::LogLevel::Info, "", "screenshot written to " + requested);
                else wb.state().notify(rrf::panels::LogLevel::Error, "", "screenshot: " + error);
            }
            const bool last = automated && scriptDone && ++framesDrawn >= args.frames;
            if (last && !args.screenshot.empty()) {
                if (writeScreenshot(window, args.screenshot, error)) {
                    std::printf("rrf-workbench: screenshot written to %s\n", args.screenshot.c_str());
                } else {
                    std::fprintf(stderr, "rrf-workbench: screenshot: %s\n", error.c_str());
                    status = 1;
                }
            }
            window.swap();
            const double frameSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - frameStart).count();
            wb.frameStats().add(frameSeconds);
            // Stalls of the whole run, start and opens included (issue 29: none over 100 ms).
            if (frameSeconds > 0.1) {
                ++slowFrames;
                char line[96];
                std::snprintf(line, sizeof line, "rrf-workbench: a frame at %.2f s took %.1f ms\n",
                              std::chrono::duration<double>(frameStart - runStart).count(), 1e3 * frameSeconds);
                if (slowFrames <= 20) slowLog += line;
            }
            longestFrame = std::max(longestFrame, frameSeconds);
            if (last) break;

            const std::string t = wb.title();
            if (t != title) window.setTitle(title = t);
            if (window.shouldClose()) {
                if (wb.requestQuit()) break;
                window.setShouldClose(false);
            }
            if (wb.quitConfirmed()) break;
        }
        window.hide();  // before ~Workbench waits for the jobs and the GL worker
        if (automated) {
            // CI reads what happened from the log.
            for (const rrf::panels::LogEntry& e : wb.state().log.entries())
                std::printf("[%s %.2f s] %s\n", rrf::panels::logLevelName(e.level), e.time, e.text.c_str());
            std::fputs(slowLog.c_str(), stdout);
            std::printf("rrf-workbench: %d frame(s) over 100 ms, the longest %.1f ms (after the first, drawn before the window "
                        "is shown: %.1f ms)\n",
                        slowFrames, 1e3 * longestFrame, 1e3 * wb.frameStats().longestAfterFirst());
        }
    }
    return status;
}
