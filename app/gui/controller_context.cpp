// The controllers' shared context (controller_context.h).
#include "app/gui/controller_context.h"

#include <filesystem>

#include "core/pipeline/run_recording.h"

namespace rrf {

std::string ControllerContext::projectDir() const {
    if (!state.hasProject) return std::filesystem::current_path().string();
    return projectDirectory(state.project);
}

}  // namespace rrf
