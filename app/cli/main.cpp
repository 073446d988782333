// rrf: the command-line front end of RRF Workbench. It runs the same core engine as the GUI, with no
// display. Errors in inputs print one clear message (file, JSON path or flag, what was expected) and
// exit 1, whether CLI11 finds them in a flag's value or the engine in a file or a setting.
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "core/nn/mlp_kernel.h"
#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "app/mpi/ranks.h"

int main(int argc, char** argv) {
    CLI::App app{"rrf - RRF Workbench: learn global illumination with radiance regression functions"};
    app.require_subcommand(1);
    int exitCode = 0;
    rrf::cli::addRenderCommand(app, exitCode);
    rrf::cli::addGenerateCommand(app, exitCode);
    rrf::cli::addMergeCommand(app, exitCode);
    rrf::cli::addInspectCommand(app, exitCode);
    rrf::cli::addTrainCommand(app, exitCode);
    rrf::cli::addEvaluateCommand(app, exitCode);
    rrf::cli::addPredictCommand(app, exitCode);
    rrf::cli::addSweepCommand(app, exitCode);
    rrf::cli::addPipelineCommand(app, exitCode);
    rrf::cli::addReferenceCommand(app, exitCode);
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
    // Under an MPI launcher with more than one process only the commands that split their work across
    // ranks may run; any other would run N times over and write its outputs N times (docs/cluster.md).
    if (const rrf::mpi::Launch launch = rrf::mpi::launchFromEnvironment(); launch.size > 1 && argc > 1) {
        const std::string command = argv[1];
        const bool splits = command == "generate" || command == "train" || command == "evaluate" || command == "sweep" ||
                            command == "pipeline";
        if (!splits || !rrf::mpi::mpiBuilt()) {
            if (launch.rank == 0)
                std::fprintf(stderr, "rrf: error: %s\n",
                             splits ? "this rrf was built without MPI (configure with -DRRF_WITH_MPI=ON and "
                                      "libopenmpi-dev installed); run one process, or --shard k/n per process and rrf merge"
                                    : ("'" + command + "' does not split its work across MPI ranks (generate, train, evaluate, sweep and "
                                                       "pipeline do); run it as one process")
                                          .c_str());
            return 2;
        }
    }
    try {
        // MPI starts before anything can fail, so a rank that fails while reading its inputs ends the
        // whole job through MPI_Abort (stopJobOnError) instead of exiting alone while the others wait
        // in a collective call: srun, unlike mpirun, keeps them waiting unless --kill-on-bad-exit.
        if (rrf::mpi::launchFromEnvironment().size > 1) rrf::mpi::ranks();
        // The MLP kernel is chosen now, so an RRF_MLP_KERNEL this CPU cannot run is refused before
        // any work (nn/mlp_kernel.h).
        rrf::mlpKernel();
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // app.exit prints CLI11's message (or the help, which exits 0); a bad flag is bad input like
        // any other, so it exits 1 rather than with CLI11's per-kind code.
        if (app.exit(e) == 0) return 0;
        rrf::mpi::stopJobOnError(1);
        return 1;
    } catch (const std::exception& e) {
        const rrf::mpi::Launch launch = rrf::mpi::launchFromEnvironment();
        const std::string where = launch.size > 1 ? " (rank " + std::to_string(launch.rank) + "/" + std::to_string(launch.size) + ")" : "";
        std::fprintf(stderr, "rrf: error%s: %s\n", where.c_str(), rrf::cli::errorMessage(e).c_str());
        // In an MPI job one failing rank ends every rank: the others may be waiting for its part.
        rrf::mpi::stopJobOnError(1);
        return 1;
    }
    return exitCode;
}
