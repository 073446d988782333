#pragma once
/// Subcommands of `rrf`. Each adds itself to the app; its callback stores the exit code.

#include <CLI/CLI.hpp>

namespace rrf::cli {

void addRenderCommand(CLI::App& app, int& exitCode);
void addDataCommands(CLI::App& app, int& exitCode);
void addTrainCommand(CLI::App& app, int& exitCode);
void addPredictCommands(CLI::App& app, int& exitCode);

}  // namespace rrf::cli
