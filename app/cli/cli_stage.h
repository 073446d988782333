#pragma once
/// How the CLI runs a core/pipeline stage: its observer's progress and status become the progress
/// line (runWithProgress, cli_common.h), its notes printed lines on stdout, Ctrl-C its cancel flag.

#include <functional>
#include <string>

#include "core/pipeline/stage_observer.h"

namespace rrf::cli {

/// Runs `stage` with an observer built on `observer` (which may carry the training's epoch callback
/// or a message printer of the caller's; its cancel, progress and status are replaced) under a
/// progress line labelled `label`. Notes are printed as lines unless the caller prints them. Exceptions thrown by the stage are rethrown here.
void runStage(const std::string& label, const std::function<void(const StageObserver&)>& stage, StageObserver observer = {});

/// runStage as a StageRunner (core/pipeline/stage_observer.h), for the stages core chains.
StageRunner stageRunner();

/// An observer that prints the stage's notes as lines on stdout (no progress line): for stages run
/// inside another stage's progress line.
StageObserver printingObserver();

}  // namespace rrf::cli
