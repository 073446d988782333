// EvaluationController: the "Run sweep" job of the Cost panel (core/pipeline/sweep.h) with sizes small enough for an
// interactive session. Every point of a sweep is measured against one reference at one resolution;
// model sweeps include the path tracer's series (1…256 spp) against that reference, so each model has
// its break-even. When the job is done a GL worker of its own (app/gl/gl_worker.h) times the GLSL
// predictor on each row's networks (core has no GL), then the rows become the Cost panel's series and are written as CSV and JSON under <project dir>/sweeps/, as `rrf sweep` writes them.
#include "app/gui/evaluation_controller.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/gl/gl_worker.h"
#include "app/gl/glsl_predictor.h"
#include "core/data/sampling_settings.h"
#include "core/pipeline/sweep.h"
#include "core/pipeline/sweep_file.h"
#include "core/util/text_format.h"
#include "core/nn/network_settings.h"
#include "core/pipeline/run_recording.h"
#include "core/util/atomic_file.h"
#include "core/util/stopwatch.h"

namespace rrf {

namespace fs = std::filesystem;

/// A finished (not cancelled) sweep: its rows (with their networks, for the GLSL timing) and where
/// its files go.
struct SweepOutcome {
    SweepResult result;
    std::shared_ptr<const Scene> scene;
    std::string outBase;  ///< <project dir>/sweeps/<what>-<time>, + .csv / .json
    PredictionSettings prediction;  ///< as the CPU rows were predicted (direct light), for the GLSL timing
};

namespace {

/// Frames timed per network set after one warm-up frame (first upload, driver shader compilation).
constexpr int kGlslTimedFrames = 5;

/// Seconds of one GLSL prediction frame of `models` at width × height with the light at `light`:
/// the GPU time of its passes (GL timer queries) plus any direct light the CPU computes for it
/// (GlslPredictor::frameSeconds, as the workbench records a run's GLSL frame), the mean over
/// kGlslTimedFrames. Needs the current GL context. Direct light as `prediction` says, like
/// the CPU frame time of the same row.
double glslFrameSeconds(const Scene& scene, const ModelSet& models, const PredictionSettings& prediction,
                        const Vec3& light, int width, int height) {
    GlslPredictor gp(scene, models);
    gp.setPrediction(prediction);
    Camera camera = scene.camera;
    camera.width = width;
    camera.height = height;
    gp.setCamera(camera);
    gp.setLightPosition(light);
    gp.render();
    gp.read(Term::Global);
    double seconds = 0.0;
    for (int i = 0; i < kGlslTimedFrames; ++i) {
        gp.render();
        seconds += gp.frameSeconds();
    }
    return seconds / kGlslTimedFrames;
}

panels::CostPoint costPoint(const SweepRow& row) {
    panels::CostPoint p;
    p.label = row.setting;
    // What a partition or data-quality setting actually did beside it: the leaves the trees grew, the
    // paths the adaptive sampler spent per record.
    if (row.extra.leaves) p.label += " · " + std::to_string(*row.extra.leaves) + " leaves";
    if (row.extra.meanRecordSpp) {
        char spp[48];
        std::snprintf(spp, sizeof spp, " · %.0f paths/record", *row.extra.meanRecordSpp);
        p.label += spp;
    }
    p.seconds = row.spp > 0 ? (row.stageSeconds.empty() ? 0.0 : row.stageSeconds.front().second) : row.oneOffSeconds;
    p.error = comparableError(row.overall);
    p.corrected = !std::isnan(row.overall.relativeRmseCorrected);
    p.rawError = row.overall.relativeRmse;
    p.spp = row.spp;
    p.frameSeconds = row.frameSeconds;
    p.glslFrameSeconds = row.glslFrameSeconds;
    return p;
}

/// The Cost panel's series of `r`: the path tracer's (an spp sweep has only that) and the models'.
/// `name` keys the colours, so a repeated sweep gets a name (and colour) of its own.
std::vector<panels::CostSeries> costSeries(const SweepResult& r, const std::string& name) {
    char reference[160];
    std::snprintf(reference, sizeof reference, "%dx%d, one reference of %d spp (relative noise floor %s), light (%.3g, %.3g, %.3g)",
                  r.width, r.height, r.referenceSpp, noiseFigureText(r.relativeNoiseFloor).c_str(), r.lightPosition.x,
                  r.lightPosition.y, r.lightPosition.z);
    panels::CostSeries pt;
    pt.kind = panels::CostKind::PathTracer;
    pt.name = r.what == "spp" ? name : "path tracer (" + name + ")";
    pt.noiseFloor = r.relativeNoiseFloor;
    pt.reference = reference;
    pt.resolution = sizeText(r.width, r.height);
    for (const SweepRow& row : pathTracerRows(r)) pt.points.push_back(costPoint(row));
    if (r.what == "spp") return {pt};
    panels::CostSeries models;
    models.kind = panels::CostKind::Models;
    models.name = name;
    models.pathTracer = pt.name;
    models.noiseFloor = r.relativeNoiseFloor;
    models.reference = reference;
    models.resolution = pt.resolution;
    for (const SweepRow& row : r.rows) models.points.push_back(costPoint(row));
    return {pt, models};
}

}  // namespace

void EvaluationController::addSweepSeries(const SweepResult& r) {
    int earlier = 0;
    for (const panels::CostSeries& s : state_.cost.sweeps)
        if (s.kind != panels::CostKind::PathTracer || r.what == "spp")
            earlier += s.name == "sweep " + r.what || s.name.rfind("sweep " + r.what + " #", 0) == 0;
    const std::string name = "sweep " + r.what + (earlier ? " #" + std::to_string(earlier + 1) : "");
    for (panels::CostSeries& s : costSeries(r, name)) state_.cost.sweeps.push_back(std::move(s));
}

/// The sweeps of a project read back from disk (restoreSweeps), on a worker: their number grows
/// with the project's history, and none of it is the UI thread's work.
struct RestoredSweeps {
    std::vector<SweepResult> results;  ///< in the order they ran, cancelled ones left out
    std::vector<std::string> problems; ///< files that could not be read (each names its file)
    std::string dir;                   ///< where they were read from, for the log
};

void EvaluationController::restoreSweeps() {
    // What the project's sweeps wrote (pollSweep below), read back in the order they ran; a file that
    // cannot be read is named in the Log and left out, the others still come back.
    const std::string dir = (fs::path(projectDir()) / "sweeps").string();
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return;  // the common case costs no thread
    restoreJob_.start("restore sweeps", [dir](JobContext& ctx) -> std::optional<RestoredSweeps> {
        RestoredSweeps out;
        out.dir = dir;
        const std::vector<std::string> files = sweepFilesIn(dir);
        for (size_t i = 0; i < files.size() && !ctx.cancelled(); ++i) {
            try {
                SweepResult r = readSweepFile(files[i]);
                if (!r.cancelled) out.results.push_back(std::move(r));
            } catch (const std::exception& e) {
                out.problems.push_back(e.what());
            }
            ctx.setProgress(double(i + 1) / double(files.size()));
        }
        return out;
    });
}

void EvaluationController::pollRestoredSweeps() {
    restoreJob_.poll([&](RestoredSweeps& restored) {
        for (const std::string& problem : restored.problems) state_.log.warning("sweep not restored: " + problem);
        for (const SweepResult& r : restored.results) addSweepSeries(r);
        if (!restored.results.empty())
            state_.log.info("restored " + std::to_string(restored.results.size()) + " sweep(s) from " +
                            projectRelative(projectDir(), restored.dir));
    });
}

bool EvaluationController::startSweep(const std::string& what) {
    if (!state_.hasProject) {
        state_.log.error("sweep: no project is open");
        return false;
    }
    if (sweepTiming_) {
        state_.notify(panels::LogLevel::Warning, "Cost", "sweep: the last sweep's GLSL frames are still being timed");
        return false;
    }
    auto scene = std::make_shared<const Scene>(state_.project.scene);
    SweepOptions o;
    o.what = what;
    try {
        defaultSweepValues(what);  // validates the kind
        o.sampling = state_.project.samplingOrDefault();
        o.training = state_.project.trainingOptions();
        o.prediction = state_.project.prediction;
    } catch (const std::exception& e) {
        state_.log.error(std::string("sweep: ") + e.what());
        return false;
    }
    // Interactive sizes: 64x64 images; data, epochs and samples bounded so a whole series stays
    // interactive instead of the CLI defaults' much longer runs. Every point, path
    // tracer and model, is judged against the one reference of the sweep.
    o.width = o.height = 64;
    // The one reference comes from the project's store, converged to the project's noise target
    // (once: later sweeps of the same scene and light reuse it).
    o.referenceTarget = state_.project.reference.target;
    const std::string storeDir = projectReferenceStore(state_.project).dir();
    if (what == "spp") o.values = {"1", "4", "16", "64"};
    o.pathTracerSpp = {1, 4, 16, 64, 256};
    o.keepModels = true;  // for the GLSL timing on the UI thread
    o.sampling.nx = std::min(o.sampling.nx, 4);
    o.sampling.ny = std::min(o.sampling.ny, 4);
    o.sampling.nz = std::min(o.sampling.nz, 4);
    o.sampling.directions = std::min(o.sampling.directions, 100);
    o.sampling.spp = std::min(o.sampling.spp, 16);
    for (TrainerCommon* c : o.training.trainer.everyTrainer()) c->maxEpochs = std::min(c->maxEpochs, 50);
    std::string outBase = (fs::path(projectDir()) / "sweeps" / (what + "-" + localTimestamp())).string();
    std::replace(outBase.end() - 8, outBase.end(), ':', '-');  // no ':' in file names
    const bool started = sweepJob_.start("sweep " + what, [scene, o, outBase, storeDir](JobContext& ctx) -> std::optional<SweepOutcome> {
        SweepOptions opt = o;
        ReferenceStore store(storeDir);
        opt.store = &store;
        opt.cancel = &ctx.cancelFlag();
        opt.log = [&](const std::string& line) {
            ctx.setStatus(line);
            ctx.post(line);
        };
        // The sweep's own fraction (reference, data, one share per task), never decreasing; the
        // last percent is left to the GLSL timing and the files written after it returns.
        opt.progress = [&](double f) { ctx.setProgress(std::min(0.99, f)); };
        SweepOutcome out;
        out.result = runSweep(*scene, opt);
        if (out.result.cancelled) return std::nullopt;
        out.scene = scene;
        out.outBase = outBase;
        out.prediction = opt.prediction;
        return out;
    });
    if (!started) return false;
    state_.cost.running = true;
    state_.log.info("sweep '" + what + "' started (64x64 images, small data and epochs; the path tracer and every model against one converged reference from " + storeDir + ")");
    return true;
}

/// A finished sweep whose rows' GLSL frames are timed on a GL worker of its own, a task per row.
struct SweepTiming {
    SweepOutcome out;
    std::unique_ptr<GlWorker> gl;
    std::vector<std::future<double>> seconds;  ///< per row with networks, in row order
    std::shared_ptr<std::atomic<bool>> dropped = std::make_shared<std::atomic<bool>>(false);
};

EvaluationController::~EvaluationController() {
    dropSweepTiming();
    retiredTimings_.clear();  // at exit: waits for the row being timed
}

void EvaluationController::dropSweepTiming() {
    if (!sweepTiming_) return;
    // Rows not started yet are skipped. The worker finishes the row it is timing (a compile takes
    // seconds), so it is stopped once idle (pollSweep), not here on the UI thread.
    sweepTiming_->dropped->store(true);
    retiredTimings_.push_back(std::move(sweepTiming_));
}

void EvaluationController::pollSweep() {
    retiredTimings_.erase(std::remove_if(retiredTimings_.begin(), retiredTimings_.end(),
                                         [](const std::unique_ptr<SweepTiming>& t) { return !t->gl || t->gl->pending() == 0; }),
                          retiredTimings_.end());
    state_.cost.running = sweepRunning();
    if (sweepJob_.running()) state_.cost.progress = sweepJob_.progress();
    sweepJob_.poll([&](SweepOutcome& out) { startSweepTiming(std::move(out)); });
    finishSweep();
}

void EvaluationController::startSweepTiming(SweepOutcome out) {
    auto timing = std::make_unique<SweepTiming>();
    timing->out = std::move(out);
    try {
        timing->gl = std::make_unique<GlWorker>();
    } catch (const std::exception& e) {
        state_.log.warning(std::string("sweep: GLSL frame times not measured: ") + e.what());
    }
    if (timing->gl) {
        const SweepOutcome& o = timing->out;
        for (const SweepRow& row : o.result.rows) {
            if (!row.models) continue;
            timing->seconds.push_back(timing->gl->post(
                [scene = o.scene, models = row.models, prediction = o.prediction, light = o.result.lightPosition,
                 width = o.result.width, height = o.result.height, dropped = timing->dropped]() -> double {
                    if (dropped->load()) return SweepRow::kUnknown;
                    return glslFrameSeconds(*scene, *models, prediction, light, width, height);
                }));
        }
    }
    sweepTiming_ = std::move(timing);
}

void EvaluationController::finishSweep() {
    if (!sweepTiming_) return;
    for (const std::future<double>& f : sweepTiming_->seconds)
        if (!resultReady(f)) return;
    std::unique_ptr<SweepTiming> timing = std::move(sweepTiming_);
    state_.cost.running = sweepRunning();
    timing->gl.reset();  // every task has run
    SweepOutcome& out = timing->out;
    SweepResult& r = out.result;
    size_t next = 0;
    bool warned = false;
    for (SweepRow& row : r.rows) {
        if (!row.models) continue;
        if (next >= timing->seconds.size()) {  // no GL worker: the times stay unknown (said when it failed)
            row.models.reset();
            continue;
        }
        try {
            row.glslFrameSeconds = timing->seconds[next++].get();
        } catch (const std::exception& e) {
            if (!warned) state_.log.warning(std::string("sweep: GLSL frame time not measured: ") + e.what());
            warned = true;
        }
        row.models.reset();
    }
    addSweepSeries(r);
    state_.focusTab = "Cost";
    try {
        fs::create_directories(fs::path(out.outBase).parent_path());
        writeFileAtomically(out.outBase + ".csv", sweepCsv(*out.scene, r));
        writeFileAtomically(out.outBase + ".json", sweepJson(*out.scene, r).dump(2));
    } catch (const std::exception& e) {
        state_.notify(panels::LogLevel::Error, "Cost", std::string("sweep: writing the results failed: ") + e.what());
        return;
    }
    state_.notify(panels::LogLevel::Info, "", "sweep written to " + out.outBase + ".csv and .json");
}

}  // namespace rrf
