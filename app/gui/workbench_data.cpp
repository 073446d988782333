// Workbench: the data-generation job (core/data/data_generator.h) and its dataset file.
#include "app/gui/workbench.h"

#include <filesystem>

#include "core/data/data_generator.h"
#include "core/pipeline/generate_stage.h"
#include "core/data/dataset_file.h"
#include "core/data/record_layout.h"
#include "core/data/sampling_settings.h"

namespace rrf {

namespace fs = std::filesystem;

/// A dataset the generate job wrote: where, and what the generator did.
struct GeneratedDataset {
    std::string path;
    GeneratorStats stats;
    std::vector<std::string> objectNames;  ///< index = object id
    double seconds = 0.0;
    int inputCount = 0;
    SamplingSettings settings;  ///< what it was generated with (the coverage table's stale check)
    uint64_t sceneHash = 0;
};

bool Workbench::generateRunning() const { return generateJob_.running(); }

bool Workbench::startGenerate() {
    if (!state_.hasProject) {
        state_.log.error("generate: no project is open");
        return false;
    }
    const SamplingSettings settings = state_.project.samplingOrDefault();
    auto scene = std::make_shared<const Scene>(state_.project.scene);
    const std::string out = (fs::path(projectDir()) / "data" / "dataset.rrfd").string();
    const std::string name = "dataset " + std::to_string(settings.nx) + "x" + std::to_string(settings.ny) + "x" +
                             std::to_string(settings.nz) + " x " + std::to_string(settings.directions);
    const bool started = generateJob_.start(name, [scene, settings, out](JobContext& ctx) -> std::optional<GeneratedDataset> {
        ctx.setStatus("preparing");
        const DataGenerator gen(*scene, settings);
        GenerateRequest request;
        request.datasetPath = out;
        GenerateOutcome generated = generateStage(gen, request, ctx.stageObserver());
        if (!generated.written) return std::nullopt;  // cancelled: the stage wrote nothing
        GeneratedData& data = generated.data;
        GeneratedDataset written;
        written.path = out;
        written.stats = std::move(data.stats);
        for (const Object& o : scene->objects) written.objectNames.push_back(o.name);
        written.seconds = data.seconds;
        written.inputCount = gen.layout().inputCount();
        written.settings = settings;
        written.sceneHash = scene->contentHash();
        return written;
    });
    if (!started) return false;
    state_.dataset.running = true;
    state_.dataset.progress = 0.0;

    state_.log.info("generate started: " + name + " -> " + out);
    return true;
}

void Workbench::pollGenerate() {
    const bool wasRunning = state_.dataset.running;
    if (generateRunning()) state_.dataset.progress = generateJob_.progress();
    bool delivered = false;
    generateJob_.poll([&](GeneratedDataset& d) {
        delivered = true;
        ++datasetsDelivered_;
        state_.dataset.progress = 1.0;
        state_.dataset.path = d.path;
        state_.dataset.objectNames = std::move(d.objectNames);
        state_.dataset.generator = std::move(d.stats);
        state_.dataset.seconds = d.seconds;
        state_.dataset.inputCount = d.inputCount;
        state_.dataset.madeWith = d.settings;
        state_.dataset.sceneHash = d.sceneHash;
        state_.dataset.lastCancelled = false;
        state_.log.info("dataset written: " + d.path + " (" + std::to_string(state_.dataset.generator.records) + " records)");
    });
    // Read after poll(): a job that ended between the two checks delivers this frame, not the next.
    state_.dataset.running = generateRunning();
    // A cancelled generation writes nothing: the table still shows the dataset before it, marked stale.
    if (wasRunning && !state_.dataset.running && !delivered) state_.dataset.lastCancelled = true;  // until a result arrives
}

}  // namespace rrf
