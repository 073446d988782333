#include "app/cli/cli_stage.h"

#include <atomic>
#include <cstdio>
#include <memory>
#include <mutex>

#include "app/cli/cli_common.h"

namespace rrf::cli {

namespace {
void printLine(const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
}
}  // namespace

StageObserver printingObserver() {
    StageObserver o;
    o.message = printLine;
    return o;
}

StageRunner stageRunner() {
    return [](const std::string& label, const std::function<void(const StageObserver&)>& stage) { runStage(label, stage); };
}

void runStage(const std::string& label, const std::function<void(const StageObserver&)>& stage, StageObserver observer) {
    struct Shown {
        std::mutex mutex;
        double fraction = 0;
        std::string status;
    };
    auto shown = std::make_shared<Shown>();
    std::atomic<bool> cancel{false};
    observer.cancel = &cancel;
    observer.progress = [shown](double f) {
        std::lock_guard<std::mutex> lock(shown->mutex);
        shown->fraction = f;
    };
    observer.status = [shown](const std::string& s) {
        std::lock_guard<std::mutex> lock(shown->mutex);
        shown->status = s;
    };
    if (!observer.message) observer.message = printLine;
    runWithProgress(
        label, [&] { stage(observer); },
        [shown] {
            std::lock_guard<std::mutex> lock(shown->mutex);
            return std::make_pair(shown->fraction, shown->status);
        },
        [&cancel] { cancel = true; });
}

}  // namespace rrf::cli
