// rrf: the command-line front end of RRF Workbench. It runs the same core engine as the GUI, with no
// display. Errors in inputs print one clear message (file, JSON path, what was expected) and exit 1.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "app/cli/commands.h"

int main(int argc, char** argv) {
    CLI::App app{"rrf - RRF Workbench: learn global illumination with radiance regression functions"};
    app.require_subcommand(1);
    int exitCode = 0;
    rrf::cli::addRenderCommand(app, exitCode);
    rrf::cli::addDataCommands(app, exitCode);
    rrf::cli::addTrainCommand(app, exitCode);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rrf: error: %s\n", e.what());
        return 1;
    }
    return exitCode;
}
