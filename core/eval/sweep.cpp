#include "core/eval/sweep.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "core/util/error.h"
#include "core/eval/evaluation.h"
#include "core/eval/experiment.h"
#include "core/eval/held_out.h"
#include "core/eval/reference_noise.h"
#include "core/nn/encoding_presets.h"
#include "core/nn/network_settings.h"
#include "core/nn/training_run.h"

namespace rrf {

namespace {

/// The setting that lists what a sweep compares (front ends map it to their own field or flag).
const char* const kValuesSetting = "sweep values";

int positiveValue(const std::string& text, const std::string& value, int max, const std::string& expected) {
    try {
        size_t used = 0;
        const int v = std::stoi(text, &used);
        if (used == text.size() && v > 0 && v <= max) return v;
    } catch (const std::exception&) {
    }
    throw SettingError(kValuesSetting, "'" + value + "': expected " + expected);
}

/// A number in (0, max], the whole text.
double positiveNumber(const std::string& text, double max, const std::string& expected) {
    try {
        size_t used = 0;
        const double v = std::stod(text, &used);
        if (used == text.size() && v > 0 && v <= max) return v;
    } catch (const std::exception&) {
    }
    throw SettingError(kValuesSetting, "'" + text + "': expected " + expected);
}

/// One setting of the series, read from its value before anything runs, so a bad value costs no
/// reference render.
struct SweepPoint {
    std::string setting;             ///< the value as given: the row's label
    int spp = 0;                     ///< spp
    SamplingSettings sampling;       ///< grid, dirs, record_spp
    ObjectTrainingOptions training;  ///< hidden, trainer, goal, leaves
};

/// "4,4,4": the grid as --grid and the project's "grid": [4, 4, 4] spell it.
void readGrid(const std::string& v, SamplingSettings& s) {
    const std::string expected = "3 integers nx,ny,nz in 1.." + std::to_string(kMaxGridCells) + " (e.g. 4,4,4)";
    std::vector<int> n;
    std::istringstream in(v);
    for (std::string part; std::getline(in, part, ',');) n.push_back(positiveValue(part, v, kMaxGridCells, expected));
    if (n.size() != 3 || v.back() == ',') throw SettingError(kValuesSetting, "'" + v + "': expected " + expected);
    s.nx = n[0];
    s.ny = n[1];
    s.nz = n[2];
}

std::vector<SweepPoint> sweepPoints(const SweepOptions& o) {
    std::vector<SweepPoint> points;
    for (const std::string& v : o.values) {
        SweepPoint p{v, 0, o.sampling, o.training};
        if (o.what == "spp") {
            p.spp = positiveValue(v, v, 1 << 20, "one positive integer (samples per pixel)");
        } else if (o.what == "grid") {
            readGrid(v, p.sampling);
        } else if (o.what == "dirs") {
            p.sampling.directions = positiveValue(v, v, kMaxDirections, "one positive integer (directions per viewpoint)");
        } else if (o.what == "hidden") {
            p.training.hidden = parseHiddenSizes(v, kValuesSetting);
        } else if (o.what == "goal") {
            // One figure for both: the trainer stops at it and the kd-tree splits nodes above it.
            const double goal = positiveNumber(v, 10.0, "an error goal in (0, 10] (validation relative RMSE, e.g. 0.05)");
            p.training.trainer.lm.errorGoal = p.training.trainer.adam.errorGoal = goal;
            p.training.partition.goal = goal;
        } else if (o.what == "leaves") {
            p.training.partition.maxLeaves = positiveValue(v, v, kMaxPartitionLeaves, "the most leaves per network, 1.." +
                                                                                        std::to_string(kMaxPartitionLeaves));
            if (p.training.partition.maxLeaves > 1 && p.training.partition.maxDepth == 0)
                p.training.partition.maxDepth = PartitionSettings{}.maxDepth;
        } else if (o.what == "encoding") {
            p.training.encoding = encodingPresetSettings(v, kValuesSetting);
            try {
                checkEncodingTrainer(p.training.encoding, p.training.trainer);
            } catch (const SettingError& e) {
                throw SettingError(kValuesSetting, "'" + v + "': " + e.detail());
            }
        } else if (o.what == "record_spp") {
            p.sampling.maxSpp = positiveValue(v, v, kMaxSamplesPerRecord, "the most paths per record, 1.." + std::to_string(kMaxSamplesPerRecord));
            p.sampling.spp = std::min(p.sampling.spp, p.sampling.maxSpp);
        } else {
            if (v != "lm" && v != "adam") throw SettingError(kValuesSetting, "'" + v + "': expected lm or adam");
            p.training.trainer = p.training.trainer.withType(v);
        }
        points.push_back(std::move(p));
    }
    return points;
}

struct Context {
    const Scene& scene;
    const SweepOptions& o;
    std::vector<SweepPoint> points;
    RecordLayout layout;
    Reference reference;
    /// The pixels every error of the sweep is measured over (the reference's G-buffer).
    FootprintMask footprint;
    /// The path tracer's series against `reference`, once rendered (the break-even of model rows).
    std::vector<PathTracerPoint> pathTracer;
    void log(const std::string& m) const {
        if (o.log) o.log(m);
    }
    bool cancelled() const { return o.cancel && o.cancel->load(); }
};

/// Trains on `samples`, predicts at the reference's light and fills the row's errors and stages.
/// Returns the training run (its curves feed the trainer sweep).
TrainingRun trainAndEvaluate(const Context& c, const std::vector<ObjectSamples>& samples, const ObjectTrainingOptions& t,
                             double generateSeconds, SweepRow& row) {
    ObjectTrainingObserver observer;
    observer.cancel = c.o.cancel;
    TrainingRun run = trainNetworks(samples, t, observer);
    const std::vector<ObjectModel>& trained = run.models;
    row.stageSeconds.push_back({"train", run.seconds});
    const ModelSet models = modelSetFromTrained(trained, c.scene, c.layout);
    const Predictor predictor(c.scene, models, c.o.prediction);
    const Evaluation e = evaluate(predictor, c.reference);
    row.stageSeconds.push_back({"gbuffer", e.gbufferSeconds});
    row.stageSeconds.push_back({"predict", e.prediction.inferenceSeconds + e.prediction.directSeconds});
    row.overall = e.term(Term::Global).overall;
    row.perObject = e.term(Term::Global).perObject;
    // What the model costs: once, its data and training; per frame, a G-buffer and the networks.
    row.oneOffSeconds = generateSeconds + run.seconds;
    row.frameSeconds = e.gbufferSeconds + e.prediction.inferenceSeconds + e.prediction.directSeconds;
    row.breakEven = breakEven(c.pathTracer, comparableError(row.overall));
    if (c.o.keepModels) row.models = std::make_shared<const ModelSet>(models);
    int64_t params = 0, leaves = 0, leafEpochs = 0, bytes = 0;
    for (const ObjectModel& m : trained) {
        if (m.skipped) continue;
        params += m.model.numParams();
        leaves += m.model.leafCount();
        for (const NetworkModel& leaf : m.model.leaves) {
            leafEpochs += leaf.training.epochs;
            bytes += modelPayloadBytes(leaf);
        }
    }
    row.extra["parameters"] = params;
    row.extra["model_bytes"] = bytes;
    // What the goal and leaves sweeps change: how far the trees grew and how long their leaves trained.
    row.extra["leaves"] = leaves;
    row.extra["leaf_epochs"] = leafEpochs;
    row.extra["pixels_without_network"] = e.prediction.pixelsWithoutNetwork;
    row.extra["non_finite_prediction_values"] = e.prediction.nonFinite;
    for (Term term : {Term::Direct, Term::Indirect})
        if (e.term(term).available) {
            const ErrorStats& st = e.term(term).overall;
            row.extra[std::string(termName(term)) + "_relative_rmse"] = st.relativeRmse;
            row.extra[std::string(termName(term)) + "_relative_rmse_noise_floor"] = noiseFigureJson(st.relativeRmseNoiseFloor);
            row.extra[std::string(termName(term)) + "_relative_rmse_corrected"] = noiseFigureJson(st.relativeRmseCorrected);
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
        row.extra["non_finite_samples_dropped"] = s.nonFinite;
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

void sweepSpp(Context& c, SweepResult& r) {
    std::vector<SweepPoint> points = c.points;
    std::stable_sort(points.begin(), points.end(), [](const SweepPoint& a, const SweepPoint& b) { return a.spp < b.spp; });
    std::vector<int> spps;
    std::vector<std::string> settings;
    for (const SweepPoint& p : points) spps.push_back(p.spp), settings.push_back(p.setting);
    r.rows = pathTracerSeries(c, spps, settings);
    std::vector<double> xs, ys, ysCorrected;
    for (const SweepRow& row : r.rows) {
        xs.push_back(double(row.spp));
        ys.push_back(row.overall.rmse);
        ysCorrected.push_back(row.overall.rmseCorrected);
        c.log("spp " + row.setting + ": RMSE " + std::to_string(row.overall.rmse) + " (reference noise floor " +
              noiseFigureText(row.overall.rmseNoiseFloor) + ", corrected " + noiseFigureText(row.overall.rmseCorrected) + ")");
    }
    r.extra["loglog_slope_rmse"] = logLogSlope(xs, ys);
    // Without the reference's noise the curve flattens towards its floor; the corrected slope does not.
    r.extra["loglog_slope_rmse_corrected"] = noiseFigureJson(logLogSlope(xs, ysCorrected));
}

/// Model sweeps: the path tracer's series against the same reference, first, so every model row
/// gets its break-even as it is measured.
void sweepPathTracer(Context& c, SweepResult& r) {
    std::vector<int> spps = c.o.pathTracerSpp;
    std::sort(spps.begin(), spps.end());
    spps.erase(std::unique(spps.begin(), spps.end()), spps.end());
    spps.erase(std::remove_if(spps.begin(), spps.end(), [](int v) { return v <= 0; }), spps.end());
    std::vector<std::string> settings;
    for (int v : spps) settings.push_back(std::to_string(v));
    r.pathTracer = pathTracerSeries(c, spps, settings);
    c.pathTracer = pointsOf(r.pathTracer);
    if (!r.pathTracer.empty())
        c.log("path tracer: relative RMSE " + noiseFigureText(comparableError(r.pathTracer.front().overall)) + " at " +
              r.pathTracer.front().setting + " spp, " + noiseFigureText(comparableError(r.pathTracer.back().overall)) + " at " +
              r.pathTracer.back().setting + " spp" +
              (std::isnan(r.pathTracer.back().overall.relativeRmseCorrected) ? " (raw: reference noise unknown)" : " (corrected)"));
}

/// grid and dirs: new data for each point, then the same networks on each.
void sweepData(Context& c, SweepResult& r) {
    for (const SweepPoint& p : c.points) {
        if (c.cancelled()) return;
        SweepRow row;
        row.setting = p.setting;
        const GeneratedData data = DataGenerator(c.scene, p.sampling).run(0, 1, c.o.cancel);
        row.stageSeconds.push_back({"generate", data.seconds});
        uint64_t records = 0;
        for (const auto& o : data.perObject) records += o.size() / size_t(c.layout.floatsPerRecord());
        row.extra["records"] = records;
        row.extra["mean_record_spp"] = records ? double(data.stats.paths) / double(records) : 0.0;
        row.extra["records_at_spp_cap"] = data.stats.recordsAtSppCap;
        trainAndEvaluate(c, samplesFromGenerated(data, c.scene, c.layout), c.o.training, data.seconds, row);
        c.log(r.what + " " + p.setting + ": " + std::to_string(records) + " records, relative RMSE " +
              std::to_string(row.overall.relativeRmse) + " (noise floor " + noiseFigureText(row.overall.relativeRmseNoiseFloor) +
              ", corrected " + noiseFigureText(row.overall.relativeRmseCorrected) + "); " + sweepBreakEvenText(row));
        r.rows.push_back(std::move(row));
    }
}

void sweepNetworks(Context& c, SweepResult& r, bool trainers) {
    const GeneratedData data = DataGenerator(c.scene, c.o.sampling).run(0, 1, c.o.cancel);
    r.extra["generate_seconds"] = data.seconds;
    const std::vector<ObjectSamples> samples = samplesFromGenerated(data, c.scene, c.layout);
    for (const SweepPoint& p : c.points) {
        if (c.cancelled()) return;
        SweepRow row;
        row.setting = p.setting;
        const TrainingRun run = trainAndEvaluate(c, samples, p.training, data.seconds, row);
        if (trainers) {
            // Each network's loss against time, networks in (object, target) order, epochs in order.
            nlohmann::json curve = nlohmann::json::array();
            for (const NetworkCurve& n : run.curves)
                for (const EpochRecord& e : n.epochs)
                    curve.push_back({{"object", n.objectId}, {"target", n.target}, {"epoch", e.epoch}, {"seconds", e.seconds},
                                     {"train_loss", e.trainLoss}, {"validation_loss", e.validationLoss}});
            row.extra["curve"] = curve;
        }
        c.log(r.what + " " + p.setting + ": relative RMSE " + std::to_string(row.overall.relativeRmse) + " (noise floor " +
              noiseFigureText(row.overall.relativeRmseNoiseFloor) + ", corrected " +
              noiseFigureText(row.overall.relativeRmseCorrected) + "); " + sweepBreakEvenText(row));
        r.rows.push_back(std::move(row));
    }
}

}  // namespace

std::vector<std::string> defaultSweepValues(const std::string& what) {
    if (what == "spp") return {"1", "2", "4", "8", "16", "32", "64"};
    if (what == "grid") return {"2,2,2", "3,3,3", "4,4,4"};
    if (what == "dirs") return {"50", "100", "200"};
    if (what == "hidden") return {"5", "10,5", "20,10"};
    if (what == "trainer") return {"lm", "adam"};
    if (what == "goal") return {"0.1", "0.05", "0.03"};
    if (what == "leaves") return {"1", "4", "16"};
    if (what == "record_spp") return {"64", "256", "1024"};
    if (what == "encoding") return {"raw", "frequency", "hash_grid"};
    std::string kinds;
    for (const char* k : kSweepKinds) kinds += std::string(kinds.empty() ? "" : ", ") + k;
    throw SettingError("sweep dimension", "expected one of " + kinds + ", got '" + what + "'");
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

SweepResult runSweep(const Scene& scene, const SweepOptions& options) {
    SweepOptions o = options;
    if (o.values.empty()) o.values = defaultSweepValues(o.what);
    else defaultSweepValues(o.what);  // validates the kind
    if (scene.lights.empty()) throw InputError(scene.sourcePath, "/lights", "a sweep needs a light");
    SweepResult r;
    r.what = o.what;
    Context c{scene, o, sweepPoints(o), RecordLayout::forScene(scene), {}, {}, {}};
    r.lightPosition = heldOutLightPositions(scene.lightRange(), 1, o.seed).front();
    RenderOptions ro;
    ro.width = o.width;
    ro.height = o.height;
    ro.spp = o.referenceSpp > 0 ? o.referenceSpp : (o.what == "spp" ? 1024 : 256);
    ro.samplesPerPass = std::max(1, ro.spp / 16);
    ro.seed = mix64(o.seed ^ 0x5245464552454E43ULL);  // never the seed of the renders it judges
    if (o.store) {
        RenderSettings rs;
        rs.seed = ro.seed;
        const ReferenceKey key = ReferenceKey::of(scene, r.lightPosition, ro.width, ro.height, rs);
        c.reference = o.store->obtain(scene, key, o.referenceTarget, o.cancel, {}, {}, o.log);
    } else {
        c.log("reference: " + std::to_string(ro.spp) + " spp at " + std::to_string(ro.width) + "x" + std::to_string(ro.height));
        c.reference = renderReference(scene, r.lightPosition, ro, o.cancel);
    }
    r.referenceSpp = c.reference.spp;
    r.referenceSeconds = c.reference.seconds;
    r.width = o.width;
    r.height = o.height;
    // Every error of the sweep is measured over the pixels of this one mask (the reference's G-buffer,
    // as evaluate() builds it), and the reference's floor over the same pixels is the sweep's floor.
    {
        const Accel accel(scene);
        const PathTracer tracer(scene, accel, Estimator::NEE, 1);
        c.footprint = footprintMask(buildGBuffer(tracer, c.layout, r.lightPosition, o.width, o.height));
    }
    r.relativeNoiseFloor = referenceNoise(c.reference, c.footprint).relativeRmse[int(Term::Global)];
    if (!c.cancelled()) {
        if (o.what == "spp") sweepSpp(c, r);
        else {
            sweepPathTracer(c, r);
            if (o.what == "grid" || o.what == "dirs" || o.what == "record_spp") sweepData(c, r);
            else sweepNetworks(c, r, o.what == "trainer");
        }
    }
    r.cancelled = c.cancelled();
    return r;
}

const std::vector<SweepRow>& pathTracerRows(const SweepResult& r) { return r.what == "spp" ? r.rows : r.pathTracer; }

std::vector<PathTracerPoint> pathTracerPoints(const SweepResult& r) { return pointsOf(pathTracerRows(r)); }

}  // namespace rrf
