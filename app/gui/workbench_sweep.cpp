// Workbench: the "Run sweep" job of the Cost panel (core/eval/sweep.h) with sizes small enough for an
// interactive session; the rows become an accuracy-versus-time series and are written as CSV and
// JSON under <project dir>/sweeps/, as `rrf sweep` writes them.
#include "app/gui/workbench.h"

#include <algorithm>
#include <filesystem>
#include <mutex>

#include "core/util/atomic_file.h"
#include "core/nn/network_settings.h"
#include "core/data/sampling_settings.h"
#include "core/eval/sweep.h"

namespace rrf {

namespace fs = std::filesystem;

struct SweepSession {
    Scene scene;
    SweepOptions options;
    std::string outBase;  ///< <project dir>/sweeps/<what>-<time>, + .csv / .json
    std::mutex mutex;
    std::vector<std::string> messages;
    bool done = false;
    SweepResult result;
};

bool Workbench::sweepRunning() const { return sweepJob_ != 0 && jobs_.running(JobKind::Sweep); }

bool Workbench::startSweep(const std::string& what) {
    if (!state_.hasProject) {
        state_.log.error("sweep: no project is open");
        return false;
    }
    auto session = std::make_shared<SweepSession>();
    session->scene = state_.project.scene;
    SweepOptions& o = session->options;
    o.what = what;
    try {
        defaultSweepValues(what);  // validates the kind
        o.sampling = state_.project.samplingOrDefault();
        o.training = state_.project.networkOrDefault().options;
        o.prediction = state_.project.prediction;
    } catch (const std::exception& e) {
        state_.log.error(std::string("sweep: ") + e.what());
        return false;
    }
    // Interactive sizes: 64x64 images and a 64-spp reference; data, epochs and samples bounded so a
    // whole series takes a minute or two on a laptop instead of the CLI defaults' much longer runs.
    o.width = o.height = 64;
    o.referenceSpp = what == "spp" ? 256 : 64;
    if (what == "spp") o.values = {"1", "4", "16", "64"};
    o.sampling.nx = std::min(o.sampling.nx, 4);
    o.sampling.ny = std::min(o.sampling.ny, 4);
    o.sampling.nz = std::min(o.sampling.nz, 4);
    o.sampling.directions = std::min(o.sampling.directions, 100);
    o.sampling.spp = std::min(o.sampling.spp, 16);
    o.training.trainer.lm.maxEpochs = std::min(o.training.trainer.lm.maxEpochs, 50);
    o.training.trainer.adam.maxEpochs = std::min(o.training.trainer.adam.maxEpochs, 50);
    session->outBase = (fs::path(projectDir()) / "sweeps" / (what + "-" + localTimestamp())).string();
    std::replace(session->outBase.end() - 8, session->outBase.end(), ':', '-');  // no ':' in file names
    std::string why;
    const int id = jobs_.start(JobKind::Sweep, "sweep " + what, [session](JobContext& ctx) {
        SweepOptions opt = session->options;
        opt.cancel = &ctx.cancelFlag();
        int lines = 0;
        const double expected = double(opt.values.empty() ? defaultSweepValues(opt.what).size() : opt.values.size()) + 1;
        opt.log = [&](const std::string& line) {
            ctx.setStatus(line);
            ctx.setProgress(std::min(0.99, ++lines / (2.0 * expected)));
            std::lock_guard<std::mutex> lock(session->mutex);
            session->messages.push_back(line);
        };
        SweepResult r = runSweep(session->scene, opt);
        if (!r.cancelled) {
            fs::create_directories(fs::path(session->outBase).parent_path());
            writeFileAtomically(session->outBase + ".csv", sweepCsv(session->scene, r));
            writeFileAtomically(session->outBase + ".json", sweepJson(session->scene, r).dump(2));
        }
        std::lock_guard<std::mutex> lock(session->mutex);
        session->result = std::move(r);
        session->done = true;
    }, &why);
    if (!id) {
        state_.log.error("sweep refused: " + why);
        return false;
    }
    sweep_ = session;
    sweepJob_ = id;
    state_.cost.running = true;
    state_.log.info("sweep '" + what + "' started (64x64 images, small data and epochs)");
    return true;
}

void Workbench::pollSweep() {
    state_.cost.running = sweepRunning();
    if (!sweep_) return;
    std::vector<std::string> messages;
    {
        std::lock_guard<std::mutex> lock(sweep_->mutex);
        messages.swap(sweep_->messages);
    }
    for (const std::string& m : messages) state_.log.info("sweep: " + m);
    for (const JobInfo& j : jobs_.jobs())
        if (j.id == sweepJob_) state_.cost.progress = j.progress;
    if (state_.cost.running) return;
    // The local keeps the session (and its mutex) alive until the lock is released below.
    const std::shared_ptr<SweepSession> session = sweep_;
    std::lock_guard<std::mutex> lock(session->mutex);
    if (sweep_->done && !sweep_->result.cancelled) {
        panels::CostSeries s;
        s.name = "sweep " + sweep_->result.what;
        for (const SweepRow& row : sweep_->result.rows) {
            double seconds = 0;
            for (const auto& stage : row.stageSeconds) seconds += stage.second;
            s.points.push_back({seconds, row.overall.relativeRmse, row.setting});
        }
        state_.cost.sweeps.push_back(std::move(s));
        state_.focusTab = "Cost";
        state_.log.info("sweep written to " + sweep_->outBase + ".csv and .json");
    }
    sweep_.reset();
}

}  // namespace rrf
