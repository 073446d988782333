// rrf: the command-line front end of RRF Workbench. It runs the same core engine as the GUI, with no
// display. Errors in inputs print one clear message (file, JSON path, what was expected) and exit 1.
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "app/cli/commands.h"

int main(int argc, char** argv) {
    CLI::App app{"rrf - RRF Workbench: learn global illumination with radiance regression functions"};
    app.require_subcommand(1);
    int exitCode = 0;
    rrf::cli::addRenderCommand(app, exitCode);
    rrf::cli::addDataCommands(app, exitCode);
    rrf::cli::addTrainCommand(app, exitCode);
    rrf::cli::addPredictCommands(app, exitCode);
    // CLI11 would only say "A subcommand is required" for a typo; name the word and the choices.
    if (argc > 1 && argv[1][0] != '-') {
        std::string known;
        bool found = false;
        for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
            known += (known.empty() ? "" : ", ") + sub->get_name();
            found = found || sub->get_name() == argv[1];
        }
        if (!found) {
            std::fprintf(stderr, "rrf: unknown command '%s' (commands: %s; see rrf --help)\n", argv[1], known.c_str());
            return 2;
        }
    }
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
