#include "panels/workbench_state.h"

#include <atomic>
#include <filesystem>

namespace rrf::panels {

std::string projectDisplayName(const Project& project, bool hasProject) {
    if (!hasProject) return "untitled";
    if (!project.name.empty()) return project.name;
    if (!project.path.empty()) return std::filesystem::path(project.path).stem().string();
    return "untitled";
}

void ImageSet::touch() {
    static std::atomic<uint64_t> counter{0};
    revision = ++counter;
}

}  // namespace rrf::panels
