#include "core/pipeline/sweep.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <optional>
#include <sstream>

#include "core/util/error.h"
#include "core/eval/evaluation.h"
#include "core/pipeline/experiment.h"
#include "core/eval/held_out.h"
#include "core/pipeline/sweep_values.h"
#include "core/eval/reference_noise.h"
#include "core/nn/encoding_presets.h"
#include "core/nn/network_settings.h"
#include "core/nn/training_run.h"
#include "core/pipeline/train_stage.h"

namespace rrf {

namespace {

struct Context {
    const Scene& scene;
    const SweepOptions& o;
    std::vector<SweepPoint> points;
    RecordLayout layout;
    const Reference& reference;
    /// The pixels every error of the sweep is measured over (the reference's G-buffer).
    const FootprintMask& footprint;
    /// The path tracer's series against `reference`, once rendered in this process (the break-even
    /// of model rows; joinSweepParts fills it in where another process rendered the series).
    std::vector<PathTracerPoint> pathTracer;
    bool pathTracerKnown = false;
    void log(const std::string& m) const {
        if (o.log) o.log(m);
    }
    bool cancelled() const { return o.cancel && o.cancel->load(); }
};

/// Trains on `samples`, predicts at the reference's light and fills the row's errors and stages.
/// Returns the training run (its curves feed the trainer sweep).
TrainingRun trainAndEvaluate(const Context& c, const std::vector<ObjectSamples>& samples, const ObjectTrainingOptions& t,
                             double generateSeconds, SweepRow& row) {
    StageObserver observer;
    observer.cancel = c.o.cancel;
    TrainRequest request;
    request.options = t;
    TrainingRun run = trainStage(samples, request, observer).run;
    const std::vector<ObjectModel>& trained = run.models;
    row.stageSeconds.push_back({"train", run.seconds});
    const ModelSet models = modelSetFromTrained(trained, c.scene, c.layout);
    const Predictor predictor(c.scene, models, c.o.prediction);
    const Evaluation e = evaluate(predictor, c.reference);
    row.stageSeconds.push_back({"gbuffer", e.gbufferSeconds});
    row.stageSeconds.push_back({"predict", e.prediction.inferenceSeconds + e.prediction.directSeconds + e.prediction.gatherSeconds});
    row.overall = e.term(Term::Global).overall;
    row.perObject = e.term(Term::Global).perObject;
    // What the model costs: once, its data and training; per frame, a G-buffer and the networks.
    row.oneOffSeconds = generateSeconds + run.seconds;
    row.frameSeconds = e.gbufferSeconds + e.prediction.inferenceSeconds + e.prediction.directSeconds + e.prediction.gatherSeconds;
    row.breakEven = breakEven(c.pathTracer, comparableError(row.overall));
    if (c.o.keepModels) row.models = std::make_shared<const ModelSet>(models);
    int64_t params = 0, leaves = 0, leafEpochs = 0, bytes = 0;
    for (const ObjectModel& m : trained) {
        if (m.skipped) continue;
        params += m.model.numParams();
        leaves += m.model.leafCount();
        for (const NetworkModel& leaf : m.model.leaves) {
            leafEpochs += leaf.training.memberEpochs;  // every member's epochs: the training work
            bytes += modelPayloadBytes(leaf);
        }
    }
    row.extra.parameters = params;
    row.extra.modelBytes = bytes;
    // What the goal and leaves sweeps change: how far the trees grew and how long their leaves trained.
    row.extra.leaves = leaves;
    row.extra.leafEpochs = leafEpochs;
    row.extra.pixelsWithoutNetwork = e.prediction.pixelsWithoutNetwork;
    row.extra.nonFinitePredictionValues = e.prediction.nonFinite;
    for (Term term : {Term::Direct, Term::Indirect})
        if (e.term(term).available) {
            const ErrorStats& st = e.term(term).overall;
            (term == Term::Direct ? row.extra.direct : row.extra.indirect) =
                SweepTermFigures{st.relativeRmse, st.relativeRmseNoiseFloor, st.relativeRmseCorrected};
        }
    return run;
}

/// The path tracer's error at each of `spps` (ascending; labels `settings`) from one progressive
/// render with the sweep's seed (never the reference's), against the reference over the footprint
/// mask's pixels, with the render time to reach each. Stops early when cancelled.
std::vector<SweepRow> pathTracerSeries(const Context& c, const std::vector<int>& spps, const std::vector<std::string>& settings) {
    std::vector<SweepRow> rows;
    if (spps.empty()) return rows;
    Scene moved = c.scene;
    moved.setLightPosition(c.reference.lightPosition);
    const Accel accel(moved);
    RenderOptions ro;
    ro.width = c.o.width;
    ro.height = c.o.height;
    ro.spp = spps.back();
    ro.seed = c.o.seed;
    Renderer renderer(moved, accel, ro);
    const Image& reference = c.reference.image(Term::Global);
    const Image& variance = c.reference.variance(Term::Global);  // the reference's own noise
    int done = 0;  // one sample per pixel per pass (RenderOptions default)
    for (size_t i = 0; i < spps.size(); ++i) {
        const int target = spps[i];
        while (done < target && !c.cancelled() && renderer.runPass()) ++done;
        if (c.cancelled()) break;
        const RenderSnapshot s = renderer.snapshot();
        SweepRow row;
        row.setting = settings[i];
        row.spp = target;
        row.stageSeconds.push_back({"render", s.seconds});
        row.overall = errorStatsWithNoise(s.global, reference, variance, c.footprint.kept);
        for (const auto& px : c.footprint.keptByObject) row.perObject.push_back(errorStatsWithNoise(s.global, reference, variance, px));
        row.extra.nonFiniteSamplesDropped = s.nonFinite;
        rows.push_back(std::move(row));
    }
    return rows;
}

std::vector<PathTracerPoint> pointsOf(const std::vector<SweepRow>& rows) {
    std::vector<PathTracerPoint> points;
    for (const SweepRow& row : rows)
        points.push_back({double(row.spp), row.stageSeconds.empty() ? 0.0 : row.stageSeconds.front().second,
                          comparableError(row.overall)});
    return points;
}


/// The spp sweep's one task: one progressive render, a snapshot at each value (ascending spp).
std::vector<SweepRow> sppSeries(Context& c) {
    std::vector<SweepPoint> points = c.points;
    std::stable_sort(points.begin(), points.end(), [](const SweepPoint& a, const SweepPoint& b) { return a.spp < b.spp; });
    std::vector<int> spps;
    std::vector<std::string> settings;
    for (const SweepPoint& p : points) spps.push_back(p.spp), settings.push_back(p.setting);
    std::vector<SweepRow> rows = pathTracerSeries(c, spps, settings);
    for (const SweepRow& row : rows)
        c.log("spp " + row.setting + ": RMSE " + std::to_string(row.overall.rmse) + " (reference noise floor " +
              noiseFigureText(row.overall.rmseNoiseFloor) + ", corrected " + noiseFigureText(row.overall.rmseCorrected) + ")");
    return rows;
}

/// The ascending, distinct, positive spp of the model sweeps' path tracer series.
std::vector<int> seriesSpp(const SweepOptions& o) {
    std::vector<int> spps = o.pathTracerSpp;
    std::sort(spps.begin(), spps.end());
    spps.erase(std::unique(spps.begin(), spps.end()), spps.end());
    spps.erase(std::remove_if(spps.begin(), spps.end(), [](int v) { return v <= 0; }), spps.end());
    return spps;
}

/// Model sweeps' task 0: the path tracer's series against the same reference, run first in a part
/// that holds it, so that part's model rows log their break-even as they are measured.
std::vector<SweepRow> modelSeries(Context& c) {
    std::vector<std::string> settings;
    const std::vector<int> spps = seriesSpp(c.o);
    for (int v : spps) settings.push_back(std::to_string(v));
    std::vector<SweepRow> rows = pathTracerSeries(c, spps, settings);
    c.pathTracer = pointsOf(rows);
    c.pathTracerKnown = true;
    if (!rows.empty())
        c.log("path tracer: relative RMSE " + noiseFigureText(comparableError(rows.front().overall)) + " at " +
              rows.front().setting + " spp, " + noiseFigureText(comparableError(rows.back().overall)) + " at " +
              rows.back().setting + " spp" +
              (std::isnan(rows.back().overall.relativeRmseCorrected) ? " (raw: reference noise unknown)" : " (corrected)"));
    return rows;
}

/// The log line of a model row; its break-even only where this process rendered the series.
void logModelRow(const Context& c, const std::string& what, const std::string& records, const SweepRow& row) {
    c.log(what + " " + row.setting + ": " + records + "relative RMSE " + std::to_string(row.overall.relativeRmse) +
          " (noise floor " + noiseFigureText(row.overall.relativeRmseNoiseFloor) + ", corrected " +
          noiseFigureText(row.overall.relativeRmseCorrected) + ")" + (c.pathTracerKnown ? "; " + sweepBreakEvenText(row) : ""));
}

/// grid, dirs and record_spp: new data for the point, then the same networks on it.
SweepRow dataPoint(const Context& c, const SweepPoint& p) {
    SweepRow row;
    row.setting = p.setting;
    const GeneratedData data = DataGenerator(c.scene, p.sampling).run(0, 1, c.o.cancel);
    row.stageSeconds.push_back({"generate", data.seconds});
    uint64_t records = 0;
    for (const auto& o : data.perObject) records += o.size() / size_t(c.layout.floatsPerRecord());
    row.extra.records = records;
    row.extra.meanRecordSpp = records ? double(data.stats.paths) / double(records) : 0.0;
    row.extra.recordsAtSppCap = data.stats.recordsAtSppCap;
    trainAndEvaluate(c, samplesFromGenerated(data, c.scene, c.layout), c.o.training, data.seconds, row);
    logModelRow(c, c.o.what, std::to_string(records) + " records, ", row);
    return row;
}

/// hidden, trainer, goal, leaves, encoding: the point's networks on the shared dataset's samples.
SweepRow networkPoint(const Context& c, const SweepPoint& p, const std::vector<ObjectSamples>& samples, double generateSeconds) {
    SweepRow row;
    row.setting = p.setting;
    const TrainingRun run = trainAndEvaluate(c, samples, p.training, generateSeconds, row);
    if (c.o.what == "trainer") {
        // Each network's loss against time, networks in (object, target) order, epochs in order.
        std::vector<SweepCurvePoint> curve;
        for (const NetworkCurve& n : run.curves)
            for (const EpochRecord& e : n.epochs)
                curve.push_back({n.objectId, n.target, e.epoch, e.seconds, e.trainLoss, e.validationLoss});
        row.extra.curve = std::move(curve);
    }
    logModelRow(c, c.o.what, "", row);
    return row;
}

/// Equal, or both unknown (NaN).
bool sameFigure(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }
bool sameFigure(const std::optional<double>& a, const std::optional<double>& b) {
    return a.has_value() == b.has_value() && (!a || sameFigure(*a, *b));
}
bool sameFigures(const std::optional<SweepTermFigures>& a, const std::optional<SweepTermFigures>& b) {
    return a.has_value() == b.has_value() &&
           (!a || (sameFigure(a->relativeRmse, b->relativeRmse) && sameFigure(a->relativeRmseNoiseFloor, b->relativeRmseNoiseFloor) &&
                   sameFigure(a->relativeRmseCorrected, b->relativeRmseCorrected)));
}
bool sameCurve(const std::optional<std::vector<SweepCurvePoint>>& a, const std::optional<std::vector<SweepCurvePoint>>& b) {
    if (a.has_value() != b.has_value()) return false;
    if (!a) return true;
    if (a->size() != b->size()) return false;
    for (size_t i = 0; i < a->size(); ++i) {
        const SweepCurvePoint &p = (*a)[i], &q = (*b)[i];
        if (p.object != q.object || p.target != q.target || p.epoch != q.epoch || !sameFigure(p.seconds, q.seconds) ||
            !sameFigure(p.trainLoss, q.trainLoss) || !sameFigure(p.validationLoss, q.validationLoss))
            return false;
    }
    return true;
}

}  // namespace

bool isModelRow(const SweepRow& row) { return !std::isnan(row.oneOffSeconds); }

bool SweepRowFigures::operator==(const SweepRowFigures& o) const {
    return parameters == o.parameters && modelBytes == o.modelBytes && leaves == o.leaves && leafEpochs == o.leafEpochs &&
           pixelsWithoutNetwork == o.pixelsWithoutNetwork && nonFinitePredictionValues == o.nonFinitePredictionValues &&
           sameFigures(direct, o.direct) && sameFigures(indirect, o.indirect) &&
           nonFiniteSamplesDropped == o.nonFiniteSamplesDropped && records == o.records &&
           sameFigure(meanRecordSpp, o.meanRecordSpp) && recordsAtSppCap == o.recordsAtSppCap && sameCurve(curve, o.curve) &&
           other == o.other;
}

double logLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int n = 0;
    for (size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
        if (!(x[i] > 0 && y[i] > 0)) continue;
        const double lx = std::log(x[i]), ly = std::log(y[i]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
        ++n;
    }
    const double den = n * sxx - sx * sx;
    if (n < 2 || den == 0) return std::numeric_limits<double>::quiet_NaN();
    return (n * sxy - sx * sy) / den;
}

SweepOptions checkedSweepOptions(const Scene& scene, const SweepOptions& options) {
    SweepOptions o = options;
    if (o.values.empty()) o.values = defaultSweepValues(o.what);
    else defaultSweepValues(o.what);  // validates the kind
    if (scene.lights.empty()) throw InputError(scene.sourcePath, "/lights", "a sweep needs a light");
    sweepPoints(o);  // reads every value before anything runs
    return o;
}

std::vector<SweepTask> sweepTasks(const SweepOptions& o) {
    std::vector<SweepTask> tasks;
    const std::vector<SweepPoint> points = sweepPoints(o);
    if (o.what == "spp") {
        SweepTask t{"spp series", true, 0, false, o.sampling, o.training};
        for (const SweepPoint& p : points) t.maxSpp = std::max(t.maxSpp, p.spp);
        return {t};
    }
    const std::vector<int> spps = seriesSpp(o);
    tasks.push_back({"path tracer", true, spps.empty() ? 0 : spps.back(), false, o.sampling, o.training});
    const bool newData = !sweepSharesData(o);
    for (const SweepPoint& p : points) tasks.push_back({p.setting, false, 0, newData, p.sampling, p.training});
    return tasks;
}

Vec3 sweepLightPosition(const Scene& scene, const SweepOptions& o) {
    return heldOutLightPositions(scene.lightRange(), 1, o.seed).front();
}

RenderOptions sweepReferenceOptions(const SweepOptions& o) {
    RenderOptions ro;
    ro.width = o.width;
    ro.height = o.height;
    ro.spp = o.referenceSpp > 0 ? o.referenceSpp : (o.what == "spp" ? 1024 : 256);
    ro.samplesPerPass = std::max(1, ro.spp / 16);
    ro.seed = mix64(o.seed ^ 0x5245464552454E43ULL);  // never the seed of the renders it judges
    return ro;
}

Reference obtainSweepReference(const Scene& scene, const SweepOptions& o,
                               const std::function<void(const ReferenceProgress&)>& progress) {
    const Vec3 light = sweepLightPosition(scene, o);
    const RenderOptions ro = sweepReferenceOptions(o);
    if (o.store) {
        RenderSettings rs;
        rs.seed = ro.seed;
        const ReferenceKey key = ReferenceKey::of(scene, light, ro.width, ro.height, rs);
        return o.store->obtain(scene, key, o.referenceTarget, o.cancel, progress, {}, o.log);
    }
    if (o.log) o.log("reference: " + std::to_string(ro.spp) + " spp at " + std::to_string(ro.width) + "x" + std::to_string(ro.height));
    return renderReference(scene, light, ro, o.cancel);
}

bool sweepSharesData(const SweepOptions& o) {
    return o.what != "spp" && o.what != "grid" && o.what != "dirs" && o.what != "record_spp";
}

SweepInputs sweepInputs(const Scene& scene, const SweepOptions& o, Reference reference, std::shared_ptr<const GeneratedData> data) {
    SweepInputs in;
    in.reference = std::move(reference);
    in.data = std::move(data);
    // Every error of the sweep is measured over the pixels of this one mask (the reference's G-buffer,
    // as evaluate() builds it), and the reference's floor over the same pixels is the sweep's floor.
    const Accel accel(scene);
    const PathTracer tracer(scene, accel, Estimator::NEE, 1);
    in.footprint = footprintMask(buildGBuffer(tracer, RecordLayout::forScene(scene), sweepLightPosition(scene, o), o.width, o.height));
    return in;
}

SweepPart runSweepTasks(const Scene& scene, const SweepOptions& o, const SweepInputs& in, const std::vector<int>& tasks,
                        const std::function<void(int)>& taskDone) {
    Context c{scene, o, sweepPoints(o), RecordLayout::forScene(scene), in.reference, in.footprint, {}, false};
    const int taskCount = o.what == "spp" ? 1 : 1 + int(c.points.size());
    SweepPart part;
    std::vector<ObjectSamples> shared;  // the shared dataset's samples, made once for this part's points
    for (int t : tasks) {
        if (t < 0 || t >= taskCount || (!part.tasks.empty() && t <= part.tasks.back()))
            throw std::invalid_argument("runSweepTasks: task " + std::to_string(t) + " is out of range or out of order");
        part.tasks.push_back(t);
        std::vector<SweepRow> rows;
        if (!c.cancelled()) {
            if (o.what == "spp") rows = sppSeries(c);
            else if (t == 0) rows = modelSeries(c);
            else if (!sweepSharesData(o)) rows.push_back(dataPoint(c, c.points[size_t(t - 1)]));
            else {
                if (!in.data) throw std::invalid_argument("runSweepTasks: a " + o.what + " sweep needs the shared dataset");
                if (shared.empty()) shared = samplesFromGenerated(*in.data, c.scene, c.layout);
                rows.push_back(networkPoint(c, c.points[size_t(t - 1)], shared, in.data->seconds));
            }
        }
        part.rows.push_back(std::move(rows));
        if (taskDone) taskDone(int(part.tasks.size()));
    }
    part.cancelled = c.cancelled();
    return part;
}

const std::vector<SweepRow>& pathTracerRows(const SweepResult& r) { return r.what == "spp" ? r.rows : r.pathTracer; }

std::vector<PathTracerPoint> pathTracerPoints(const SweepResult& r) { return pointsOf(pathTracerRows(r)); }

SweepResult joinSweepParts(const Scene& scene, const SweepOptions& o, const SweepInputs& in, std::vector<SweepPart> parts) {
    const std::vector<SweepTask> tasks = sweepTasks(o);
    std::vector<std::optional<std::vector<SweepRow>>> byTask(tasks.size());
    SweepResult r;
    for (SweepPart& part : parts) {
        if (part.rows.size() != part.tasks.size()) throw std::runtime_error("joinSweepParts: a part's rows do not match its tasks");
        for (size_t i = 0; i < part.tasks.size(); ++i) {
            const int t = part.tasks[i];
            if (t < 0 || size_t(t) >= tasks.size()) throw std::runtime_error("joinSweepParts: no task " + std::to_string(t));
            if (byTask[size_t(t)]) throw std::runtime_error("joinSweepParts: task " + std::to_string(t) + " was run twice");
            byTask[size_t(t)] = std::move(part.rows[i]);
        }
        r.cancelled = r.cancelled || part.cancelled;
    }
    for (size_t t = 0; t < tasks.size(); ++t)
        if (!byTask[t]) throw std::runtime_error("joinSweepParts: task " + std::to_string(t) + " (" + tasks[t].label + ") is missing");
    r.what = o.what;
    r.lightPosition = sweepLightPosition(scene, o);
    r.width = o.width;
    r.height = o.height;
    r.referenceSpp = in.reference.spp;
    r.referenceSeconds = in.reference.seconds;
    r.relativeNoiseFloor = referenceNoise(in.reference, in.footprint).relativeRmse[int(Term::Global)];
    if (o.what == "spp") {
        r.rows = std::move(*byTask[0]);
        std::vector<double> xs, ys, ysCorrected;
        for (const SweepRow& row : r.rows) {
            xs.push_back(double(row.spp));
            ys.push_back(row.overall.rmse);
            ysCorrected.push_back(row.overall.rmseCorrected);
        }
        r.extra.loglogSlopeRmse = logLogSlope(xs, ys);
        // Without the reference's noise the curve flattens towards its floor; the corrected slope does not.
        r.extra.loglogSlopeRmseCorrected = logLogSlope(xs, ysCorrected);
        return r;
    }
    r.pathTracer = std::move(*byTask[0]);
    // Every model row's break-even against the series, wherever the series was rendered.
    const std::vector<PathTracerPoint> series = pathTracerPoints(r);
    for (size_t t = 1; t < tasks.size(); ++t)
        for (SweepRow& row : *byTask[t]) {
            row.breakEven = breakEven(series, comparableError(row.overall));
            r.rows.push_back(std::move(row));
        }
    if (in.data) r.extra.generateSeconds = in.data->seconds;
    return r;
}

SweepResult runSweep(const Scene& scene, const SweepOptions& options) {
    const SweepOptions o = checkedSweepOptions(scene, options);
    // Progress never goes back: the reference's own estimate can (its noise estimate is noisy).
    double reported = 0;
    auto report = [&](double f) {
        if (!o.progress) return;
        reported = std::max(reported, std::clamp(f, 0.0, 1.0));
        o.progress(reported);
    };
    report(0);
    Reference reference =
        obtainSweepReference(scene, o, [&](const ReferenceProgress& p) { report(kSweepReferenceShare * p.fraction); });
    report(kSweepReferenceShare);
    const bool cancelled = o.cancel && o.cancel->load();
    std::shared_ptr<const GeneratedData> data;
    if (sweepSharesData(o) && !cancelled) data = std::make_shared<const GeneratedData>(DataGenerator(scene, o.sampling).run(0, 1, o.cancel));
    const double start = kSweepReferenceShare + kSweepDataShare;
    report(start);
    const SweepInputs in = sweepInputs(scene, o, std::move(reference), std::move(data));
    std::vector<int> all(sweepTasks(o).size());
    std::iota(all.begin(), all.end(), 0);
    std::vector<SweepPart> parts;
    parts.push_back(runSweepTasks(scene, o, in, all, [&](int done) { report(start + (1 - start) * done / double(all.size())); }));
    return joinSweepParts(scene, o, in, std::move(parts));
}

}  // namespace rrf
