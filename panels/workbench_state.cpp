#include "panels/workbench_state.h"

#include <atomic>
#include <filesystem>

namespace rrf::panels {

std::string WorkbenchState::projectName() const {
    if (!hasProject) return "untitled";
    if (project.doc.is_object() && project.doc.contains("name") && project.doc["name"].is_string()) {
        const std::string n = project.doc["name"].get<std::string>();
        if (!n.empty()) return n;
    }
    if (!project.path.empty()) return std::filesystem::path(project.path).stem().string();
    return "untitled";
}

void ImageSet::touch() {
    static std::atomic<uint64_t> counter{0};
    revision = ++counter;
}

}  // namespace rrf::panels
