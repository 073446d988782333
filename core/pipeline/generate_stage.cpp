#include "core/pipeline/generate_stage.h"

#include <chrono>
#include <filesystem>
#include <future>

#include "core/data/dataset_file.h"
#include "core/data/dataset_header_json.h"

namespace rrf {

GenerateOutcome generateStage(const DataGenerator& generator, const GenerateRequest& request, const StageObserver& observer) {
    GenerateOutcome out;
    if (request.generate) {
        out.data = request.generate(generator);
    } else {
        GeneratorProgress progress;
        // The generator blocks its caller; a second thread lets this one report progress.
        auto result = std::async(std::launch::async, [&] { return generator.run(0, 1, observer.cancel, &progress); });
        while (result.wait_for(std::chrono::milliseconds(100)) != std::future_status::ready) {
            observer.setProgress(progress.fraction());
            observer.setStatus(std::to_string(progress.records.load()) + " records");
        }
        out.data = result.get();
    }
    if (out.data.cancelled) {
        observer.setStatus("cancelled; no file written");
        return out;
    }
    if (request.writes && !request.datasetPath.empty()) {
        const std::filesystem::path parent = std::filesystem::path(request.datasetPath).parent_path();
        std::error_code ec;
        if (!parent.empty()) std::filesystem::create_directories(parent, ec);
        writeDataset(request.datasetPath, datasetHeader(out.data), out.data.sceneHash, out.data.perObject);
        out.written = true;
        observer.setStatus("written");
    }
    observer.setProgress(1.0);
    return out;
}

}  // namespace rrf
