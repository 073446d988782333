// rrf-workbench [project.json] [--frames N] [--screenshot out.png] [--script steps.json]
//
// Opens the workbench on a project (the bundled Cornell box by default). --frames N draws N frames
// (after the script, if any) and exits; --screenshot writes the last frame to a PNG. The exit status
// is non-zero if the project cannot be opened, the script fails or the screenshot cannot be written
// in these automated modes.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "app/gui/script.h"
#include "app/gui/user_config.h"
#include "app/gui/window.h"
#include "app/gui/workbench.h"
#include "core/util/image_io.h"

namespace {

struct Args {
    std::string project = RRF_SOURCE_DIR "/projects/cornell-box/project.json";
    int frames = -1;
    std::string screenshot, script;
};

void usage(FILE* to) {
    std::fprintf(to,
                 "usage: rrf-workbench [project.json] [--frames N] [--screenshot out.png] [--script steps.json]\n"
                 "  project.json        project or scene file (default: the bundled Cornell box)\n"
                 "  --frames N          draw N frames (after the script), then exit\n"
                 "  --screenshot FILE   write the last frame to a PNG file\n"
                 "  --script FILE       run a scripted session (JSON array of steps) first\n");
}

bool parse(int argc, char** argv, Args& a, int& exitCode) {
    bool haveProject = false;
    for (int i = 1; i < argc; ++i) {
        const std::string s = argv[i];
        auto value = [&](const char* name) -> const char* {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "rrf-workbench: %s needs a value\n", name);
                return nullptr;
            }
            return argv[++i];
        };
        if (s == "-h" || s == "--help") {
            usage(stdout);
            exitCode = 0;
            return false;
        } else if (s == "--frames") {
            const char* v = value("--frames");
            char* end = nullptr;
            const long n = v ? std::strtol(v, &end, 10) : -1;
            if (!v || *end || n < 1 || n > 1000000) {
                std::fprintf(stderr, "rrf-workbench: --frames needs a positive integer\n");
                exitCode = 2;
                return false;
            }
            a.frames = int(n);
        } else if (s == "--screenshot" || s == "--script") {
            const char* v = value(s.c_str());
            if (!v) {
                exitCode = 2;
                return false;
            }
            (s == "--script" ? a.script : a.screenshot) = v;
        } else if (!s.empty() && s[0] == '-') {
            std::fprintf(stderr, "rrf-workbench: unknown option %s\n", s.c_str());
            usage(stderr);
            exitCode = 2;
            return false;
        } else if (haveProject) {
            std::fprintf(stderr, "rrf-workbench: only one project file may be given\n");
            exitCode = 2;
            return false;
        } else {
            a.project = s;
            haveProject = true;
        }
    }
    return true;
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

    const std::string configDir = rrf::userConfigDir();
    rrf::Window window;
    if (!window.create(1600, 1000, "RRF Workbench", configDir, !automated, error)) {
        std::fprintf(stderr, "rrf-workbench: %s\n", error.c_str());
        return 1;
    }

    int status = 0;
    {
        rrf::Workbench wb(configDir);
        if (!wb.openProject(args.project) && automated) {
            std::fprintf(stderr, "rrf-workbench: cannot open %s\n", args.project.c_str());
            status = 1;
        }
        bool scriptDone = script.empty();
        int framesDrawn = 0;
        std::string title;
        while (status == 0) {
            // Automated runs poll quickly; interactive ones sleep until input or a 30 Hz refresh
            // so the UI thread leaves the cores to the background jobs.
            window.waitEvents(automated ? 0.005 : 1.0 / 30.0);
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
                if (writeScreenshot(window, requested, error)) wb.state().log.info("screenshot written to " + requested);
                else wb.state().log.error("screenshot: " + error);
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
            if (last) break;

            const std::string t = wb.title();
            if (t != title) window.setTitle(title = t);
            if (window.shouldClose()) {
                if (wb.requestQuit()) break;
                window.setShouldClose(false);
            }
            if (wb.quitConfirmed()) break;
        }
        if (automated) {
            // CI reads what happened from the log.
            for (const rrf::panels::LogEntry& e : wb.state().log.entries())
                std::printf("[%s] %s\n", rrf::panels::logLevelName(e.level), e.text.c_str());
        }
    }
    return status;
}
