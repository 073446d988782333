#pragma once
/// Subcommands of `rrf`, one source file each (cli_<command>.cpp). Each adds itself to the app; its
/// callback stores the exit code.

#include <CLI/CLI.hpp>

namespace rrf::cli {

void addRenderCommand(CLI::App& app, int& exitCode);
void addGenerateCommand(CLI::App& app, int& exitCode);
void addMergeCommand(CLI::App& app, int& exitCode);
void addInspectCommand(CLI::App& app, int& exitCode);
void addTrainCommand(CLI::App& app, int& exitCode);
void addEvaluateCommand(CLI::App& app, int& exitCode);
void addPredictCommand(CLI::App& app, int& exitCode);
void addSweepCommand(CLI::App& app, int& exitCode);
void addPipelineCommand(CLI::App& app, int& exitCode);
void addReferenceCommand(CLI::App& app, int& exitCode);

}  // namespace rrf::cli
