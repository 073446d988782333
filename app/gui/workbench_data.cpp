// Workbench: the data-generation job (core/data/data_generator.h) and its dataset file.
#include "app/gui/workbench.h"

#include <filesystem>
#include <future>
#include <mutex>

#include "core/data/data_generator.h"
#include "core/data/dataset_file.h"
#include "core/data/record_layout.h"
#include "core/data/sampling_settings.h"

namespace rrf {

namespace fs = std::filesystem;

/// Shared between the generate job (worker) and the UI thread.
struct GenerateSession {
    Scene scene;
    SamplingSettings settings;
    std::string out;
    GeneratorProgress progress;
    std::mutex mutex;                                      ///< guards the results below
    bool written = false;
    std::vector<std::pair<std::string, uint64_t>> counts;  ///< records per object
    double seconds = 0.0;
};

bool Workbench::generateRunning() const { return generateJob_ != 0 && jobs_.running(JobKind::Generate); }

bool Workbench::startGenerate() {
    if (!state_.hasProject) {
        state_.log.error("generate: no project is open");
        return false;
    }
    auto session = std::make_shared<GenerateSession>();
    try {
        session->settings = state_.project.samplingOrDefault();
    } catch (const std::exception& e) {
        state_.log.error(std::string("generate: ") + e.what());
        return false;
    }
    session->scene = state_.project.scene;
    session->out = (fs::path(projectDir()) / "data" / "dataset.rrfd").string();
    const std::string name = "dataset " + std::to_string(session->settings.nx) + "x" + std::to_string(session->settings.ny) +
                             "x" + std::to_string(session->settings.nz) + " x " + std::to_string(session->settings.directions);
    std::string why;
    const int id = jobs_.start(JobKind::Generate, name, [session](JobContext& ctx) {
        ctx.setStatus("preparing");
        DataGenerator gen(session->scene, session->settings);
        // The generator blocks its caller; an inner thread lets this one report progress.
        auto result = std::async(std::launch::async, [&] {
            return gen.run(0, 1, &ctx.cancelFlag(), &session->progress);
        });
        while (result.wait_for(std::chrono::milliseconds(100)) != std::future_status::ready) {
            ctx.setProgress(session->progress.fraction());
            ctx.setStatus(std::to_string(session->progress.records.load()) + " records");
        }
        GeneratedData data = result.get();
        if (data.cancelled) {
            ctx.setStatus("cancelled; no file written");
            return;
        }
        std::error_code ec;
        fs::create_directories(fs::path(session->out).parent_path(), ec);
        writeDataset(session->out, data.header, data.sceneHash, data.perObject);
        const size_t fpr = data.header.value("floats_per_record", size_t(1));
        std::lock_guard<std::mutex> lock(session->mutex);
        for (size_t i = 0; i < data.perObject.size(); ++i)
            session->counts.emplace_back(i < session->scene.objects.size() ? session->scene.objects[i].name : "?",
                                         uint64_t(data.perObject[i].size() / std::max<size_t>(1, fpr)));
        session->seconds = data.seconds;
        session->written = true;
        ctx.setProgress(1.0);
        ctx.setStatus("written");
    }, &why);
    if (!id) {
        state_.log.error("generate refused: " + why);
        return false;
    }
    generate_ = session;
    generateJob_ = id;
    state_.dataset.running = true;
    state_.dataset.progress = 0.0;
    state_.log.info("generate started: " + name + " -> " + session->out);
    return true;
}

void Workbench::pollGenerate() {
    state_.dataset.running = generateRunning();
    if (!generate_) return;
    state_.dataset.progress = generate_->progress.fraction();
    if (state_.dataset.running) return;
    // The local keeps the session (and its mutex) alive until the lock is released below.
    const std::shared_ptr<GenerateSession> session = generate_;
    std::lock_guard<std::mutex> lock(session->mutex);
    if (generate_->written) {
        state_.dataset.path = generate_->out;
        state_.dataset.recordsPerObject = generate_->counts;
        state_.dataset.seconds = generate_->seconds;
        state_.dataset.inputCount = RecordLayout::forScene(generate_->scene).inputCount();
        uint64_t total = 0;
        for (const auto& c : generate_->counts) total += c.second;
        state_.log.info("dataset written: " + generate_->out + " (" + std::to_string(total) + " records)");
    }
    generate_.reset();
}

}  // namespace rrf
