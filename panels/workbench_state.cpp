#include "panels/workbench_state.h"

#include <atomic>
#include <filesystem>

namespace rrf::panels {

const char* termName(Term t) {
    switch (t) {
        case Term::Global: return "global";
        case Term::Direct: return "direct";
        case Term::Indirect: return "indirect";
    }
    return "global";
}

const char* errorMetricName(ErrorMetric m) {
    switch (m) {
        case ErrorMetric::Absolute: return "absolute |d|";
        case ErrorMetric::Relative: return "relative |d|/(ref+0.01)";
        case ErrorMetric::Squared: return "squared d^2";
    }
    return "absolute";
}

std::string WorkbenchState::projectName() const {
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
