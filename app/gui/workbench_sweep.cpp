// Workbench: the "Run sweep" job of the Cost panel (core/eval/sweep.h) with sizes small enough for an
// interactive session; the rows become an accuracy-versus-time series and are written as CSV and
// JSON under <project dir>/sweeps/, as `rrf sweep` writes them.
#include "app/gui/workbench.h"

#include <algorithm>
#include <filesystem>

#include "core/util/atomic_file.h"
#include "core/nn/network_settings.h"
#include "core/data/sampling_settings.h"
#include "core/eval/sweep.h"

namespace rrf {

namespace fs = std::filesystem;

/// A finished (not cancelled) sweep: its series for the Cost panel and where its files went.
struct SweepOutcome {
    panels::CostSeries series;
    std::string outBase;  ///< <project dir>/sweeps/<what>-<time>, + .csv / .json
};

bool Workbench::sweepRunning() const { return sweepJob_.running(); }

bool Workbench::startSweep(const std::string& what) {
    if (!state_.hasProject) {
        state_.log.error("sweep: no project is open");
        return false;
    }
    auto scene = std::make_shared<const Scene>(state_.project.scene);
    SweepOptions o;
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
    std::string outBase = (fs::path(projectDir()) / "sweeps" / (what + "-" + localTimestamp())).string();
    std::replace(outBase.end() - 8, outBase.end(), ':', '-');  // no ':' in file names
    const bool started = sweepJob_.start("sweep " + what, [scene, o, outBase](JobContext& ctx) -> std::optional<SweepOutcome> {
        SweepOptions opt = o;
        opt.cancel = &ctx.cancelFlag();
        int lines = 0;
        const double expected = double(opt.values.empty() ? defaultSweepValues(opt.what).size() : opt.values.size()) + 1;
        opt.log = [&](const std::string& line) {
            ctx.setStatus(line);
            ctx.setProgress(std::min(0.99, ++lines / (2.0 * expected)));
            ctx.post(line);
        };
        const SweepResult r = runSweep(*scene, opt);
        if (r.cancelled) return std::nullopt;
        fs::create_directories(fs::path(outBase).parent_path());
        writeFileAtomically(outBase + ".csv", sweepCsv(*scene, r));
        writeFileAtomically(outBase + ".json", sweepJson(*scene, r).dump(2));
        SweepOutcome out;
        out.outBase = outBase;
        out.series.name = "sweep " + r.what;
        for (const SweepRow& row : r.rows) {
            double seconds = 0;
            for (const auto& stage : row.stageSeconds) seconds += stage.second;
            out.series.points.push_back({seconds, row.overall.relativeRmse, row.setting});
        }
        return out;
    });
    if (!started) return false;
    state_.cost.running = true;
    state_.log.info("sweep '" + what + "' started (64x64 images, small data and epochs)");
    return true;
}

void Workbench::pollSweep() {
    state_.cost.running = sweepRunning();
    if (state_.cost.running) state_.cost.progress = sweepJob_.progress();
    sweepJob_.poll([&](SweepOutcome& out) {
        state_.cost.sweeps.push_back(std::move(out.series));
        state_.focusTab = "Cost";
        state_.log.info("sweep written to " + out.outBase + ".csv and .json");
    });
}

}  // namespace rrf
