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

/// One setting of the series, read from its value before anything runs, so a bad value costs no
/// reference render.
struct SweepPoint {
    std::string setting;             ///< the value as given: the row's label
    int spp = 0;                     ///< spp
    SamplingSettings sampling;       ///< grid, dirs
    ObjectTrainingOptions training;  ///< hidden, trainer
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
    void log(const std::string& m) const {
        if (o.log) o.log(m);
    }
    bool cancelled() const { return o.cancel && o.cancel->load(); }
};

/// Trains on `samples`, predicts at the reference's light and fills the row's errors and stages.
/// Returns the training run (its curves feed the trainer sweep).
TrainingRun trainAndEvaluate(const Context& c, const std::vector<ObjectSamples>& samples, const ObjectTrainingOptions& t,
                             SweepRow& row) {
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
    int64_t params = 0;
    for (const ObjectModel& m : trained)
        if (!m.skipped) params += m.model.numParams();
    row.extra["parameters"] = params;
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

void sweepSpp(Context& c, SweepResult& r) {
    std::vector<SweepPoint> points = c.points;
    std::stable_sort(points.begin(), points.end(), [](const SweepPoint& a, const SweepPoint& b) { return a.spp < b.spp; });
    Scene moved = c.scene;
    moved.setLightPosition(c.reference.lightPosition);
    const Accel accel(moved);
    RenderOptions ro;
    ro.width = c.o.width;
    ro.height = c.o.height;
    ro.spp = points.back().spp;
    ro.seed = c.o.seed;
    Renderer renderer(moved, accel, ro);
    const PathTracer tracer(moved, accel, Estimator::NEE, 1);
    const GBuffer gb = buildGBuffer(tracer, c.layout, c.reference.lightPosition, ro.width, ro.height);
    std::vector<double> xs, ys, ysCorrected;
    const Image& reference = c.reference.image(Term::Global);
    const Image& variance = c.reference.variance(Term::Global);  // the reference's own noise
    int done = 0;  // one sample per pixel per pass (RenderOptions default)
    for (const SweepPoint& point : points) {
        const int target = point.spp;
        while (done < target && !c.cancelled() && renderer.runPass()) ++done;
        if (c.cancelled()) break;
        const RenderSnapshot s = renderer.snapshot();
        SweepRow row;
        row.setting = point.setting;
        row.stageSeconds.push_back({"render", s.seconds});
        row.overall = errorStatsWithNoise(s.global, reference, variance);
        for (const auto& px : gb.pixelsByObject) row.perObject.push_back(errorStatsWithNoise(s.global, reference, variance, px));
        row.extra["non_finite_samples_dropped"] = s.nonFinite;
        xs.push_back(double(target));
        ys.push_back(row.overall.rmse);
        ysCorrected.push_back(row.overall.rmseCorrected);
        c.log("spp " + row.setting + ": RMSE " + std::to_string(row.overall.rmse) + " (reference noise floor " +
              noiseFigureText(row.overall.rmseNoiseFloor) + ", corrected " + noiseFigureText(row.overall.rmseCorrected) + ")");
        r.rows.push_back(std::move(row));
    }
    r.extra["loglog_slope_rmse"] = logLogSlope(xs, ys);
    // Without the reference's noise the curve flattens towards its floor; the corrected slope does not.
    r.extra["loglog_slope_rmse_corrected"] = noiseFigureJson(logLogSlope(xs, ysCorrected));
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
        trainAndEvaluate(c, samplesFromGenerated(data, c.scene, c.layout), c.o.training, row);
        c.log(r.what + " " + p.setting + ": " + std::to_string(records) + " records, relative RMSE " +
              std::to_string(row.overall.relativeRmse) + " (noise floor " + noiseFigureText(row.overall.relativeRmseNoiseFloor) +
              ", corrected " + noiseFigureText(row.overall.relativeRmseCorrected) + ")");
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
        const TrainingRun run = trainAndEvaluate(c, samples, p.training, row);
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
              noiseFigureText(row.overall.relativeRmseCorrected) + ")");
        r.rows.push_back(std::move(row));
    }
}

/// A CSV field: quoted when it holds a comma (grid "4,4,4", hidden "20,10") or a quote (RFC 4180).
std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char ch : text) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return quoted + "\"";
}

std::string num(double v) {
    if (!std::isfinite(v)) return "nan";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

/// A noise figure in CSV: empty when unknown (NaN), so a reader sees a missing value, never 0.
std::string noiseField(double v) { return std::isnan(v) ? std::string() : num(v); }

}  // namespace

std::vector<std::string> defaultSweepValues(const std::string& what) {
    if (what == "spp") return {"1", "2", "4", "8", "16", "32", "64"};
    if (what == "grid") return {"2,2,2", "3,3,3", "4,4,4"};
    if (what == "dirs") return {"50", "100", "200"};
    if (what == "hidden") return {"5", "10,5", "20,10"};
    if (what == "trainer") return {"lm", "adam"};
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
    Context c{scene, o, sweepPoints(o), RecordLayout::forScene(scene), {}};
    r.lightPosition = heldOutLightPositions(scene.lightRange(), 1, o.seed).front();
    RenderOptions ro;
    ro.width = o.width;
    ro.height = o.height;
    ro.spp = o.referenceSpp > 0 ? o.referenceSpp : (o.what == "spp" ? 1024 : 256);
    ro.samplesPerPass = std::max(1, ro.spp / 16);
    ro.seed = mix64(o.seed ^ 0x5245464552454E43ULL);  // never the seed of the renders it judges
    c.log("reference: " + std::to_string(ro.spp) + " spp at " + std::to_string(ro.width) + "x" + std::to_string(ro.height));
    c.reference = renderReference(scene, r.lightPosition, ro, o.cancel);
    r.referenceSpp = c.reference.spp;
    r.referenceSeconds = c.reference.seconds;
    if (!c.cancelled()) {
        if (o.what == "spp") sweepSpp(c, r);
        else if (o.what == "grid" || o.what == "dirs") sweepData(c, r);
        else sweepNetworks(c, r, o.what == "trainer");
    }
    r.cancelled = c.cancelled();
    return r;
}

std::string sweepCsv(const Scene& scene, const SweepResult& r) {
    std::ostringstream out;
    std::vector<std::string> stages;
    for (const SweepRow& row : r.rows)
        for (const auto& s : row.stageSeconds)
            if (std::find(stages.begin(), stages.end(), s.first) == stages.end()) stages.push_back(s.first);
    out << "what,setting";
    for (const std::string& s : stages) out << "," << s << "_seconds";
    out << ",pixels,rmse,rmse_noise_floor,rmse_corrected,relative_rmse,relative_rmse_noise_floor,relative_rmse_corrected,"
           "mae,max_error";
    for (const Object& o : scene.objects)
        out << "," << o.name << "_rmse," << o.name << "_relative_rmse," << o.name << "_relative_rmse_noise_floor," << o.name
            << "_relative_rmse_corrected";
    out << "\n";
    for (const SweepRow& row : r.rows) {
        out << r.what << "," << csvField(row.setting);
        for (const std::string& s : stages) {
            double v = std::numeric_limits<double>::quiet_NaN();
            for (const auto& kv : row.stageSeconds)
                if (kv.first == s) v = kv.second;
            out << "," << num(v);
        }
        const ErrorStats& e = row.overall;
        out << "," << e.pixels << "," << num(e.rmse) << "," << noiseField(e.rmseNoiseFloor) << "," << noiseField(e.rmseCorrected)
            << "," << num(e.relativeRmse) << "," << noiseField(e.relativeRmseNoiseFloor) << ","
            << noiseField(e.relativeRmseCorrected) << "," << num(e.mae) << "," << num(e.maxError);
        for (size_t id = 0; id < scene.objects.size(); ++id) {
            const bool seen = id < row.perObject.size() && row.perObject[id].pixels > 0;
            const ErrorStats& o = seen ? row.perObject[id] : ErrorStats{};
            out << "," << (seen ? num(o.rmse) : "") << "," << (seen ? num(o.relativeRmse) : "") << ","
                << noiseField(o.relativeRmseNoiseFloor) << "," << noiseField(o.relativeRmseCorrected);
        }
        out << "\n";
    }
    return out.str();
}

std::string sweepCurveCsv(const SweepResult& r) {
    std::ostringstream out;
    bool any = false;
    for (const SweepRow& row : r.rows) {
        if (!row.extra.contains("curve")) continue;
        if (!any) out << "trainer,object,target,epoch,seconds,train_loss,validation_loss\n";
        any = true;
        for (const nlohmann::json& p : row.extra["curve"]) {
            const double val = p["validation_loss"].is_number() ? p["validation_loss"].get<double>() : std::nan("");
            out << csvField(row.setting) << "," << p["object"].get<int>() << "," << p["target"].get<std::string>() << ","
                << p["epoch"].get<int>() << "," << num(p["seconds"].get<double>()) << ","
                << num(p["train_loss"].get<double>()) << "," << num(val) << "\n";
        }
    }
    return out.str();
}

nlohmann::json sweepJson(const Scene& scene, const SweepResult& r) {
    nlohmann::json rows = nlohmann::json::array();
    for (const SweepRow& row : r.rows) {
        nlohmann::json stages = nlohmann::json::object(), objects = nlohmann::json::array();
        for (const auto& kv : row.stageSeconds) stages[kv.first] = kv.second;
        for (size_t id = 0; id < row.perObject.size(); ++id) {
            nlohmann::json o = row.perObject[id].toJson();
            o["id"] = int(id);
            o["name"] = id < scene.objects.size() ? scene.objects[id].name : "";
            objects.push_back(o);
        }
        rows.push_back({{"setting", row.setting}, {"stage_seconds", stages}, {"error", row.overall.toJson()},
                        {"objects", objects}, {"extra", row.extra}});
    }
    return {{"what", r.what},
            {"light_position", {r.lightPosition.x, r.lightPosition.y, r.lightPosition.z}},
            {"reference", {{"spp", r.referenceSpp}, {"seconds", r.referenceSeconds}}},
            {"error_term", "global"},
            {"metric", "per channel averaged over RGB; relative error |d|/(|ref|+0.01); *_noise_floor = the figure the "
                       "reference's own noise gives, *_corrected = the figure with the reference's per-pixel variance of the "
                       "mean subtracted from the squared error (clamped at 0); null when unknown"},
            {"cancelled", r.cancelled},
            {"extra", r.extra},
            {"rows", rows}};
}

std::string sweepTable(const SweepResult& r) {
    std::ostringstream out;
    char line[640];
    for (const SweepRow& row : r.rows) {
        std::string stages;
        for (const auto& kv : row.stageSeconds) {
            std::snprintf(line, sizeof line, "%s %.3f s  ", kv.first.c_str(), kv.second);
            stages += line;
        }
        const ErrorStats& e = row.overall;
        std::snprintf(line, sizeof line, "| %-10s | %-58s | %10.4g | %11s | %10s | %10.4g | %11s | %10s | %10.4g |\n",
                      row.setting.c_str(), stages.c_str(), e.rmse, noiseFigureText(e.rmseNoiseFloor).c_str(),
                      noiseFigureText(e.rmseCorrected).c_str(), e.relativeRmse, noiseFigureText(e.relativeRmseNoiseFloor).c_str(),
                      noiseFigureText(e.relativeRmseCorrected).c_str(), e.mae);
        out << line;
    }
    const std::string rule10(12, '-'), rule11(13, '-');
    std::snprintf(line, sizeof line, "| %-10s | %-58s | %10s | %11s | %10s | %10s | %11s | %10s | %10s |\n|%s|%s|%s|%s|%s|%s|%s|%s|%s|\n",
                  r.what.c_str(), "wall time per stage", "RMSE", "noise floor", "corrected", "rel.RMSE", "noise floor",
                  "corrected", "MAE", rule10.c_str(), std::string(60, '-').c_str(), rule10.c_str(), rule11.c_str(),
                  rule10.c_str(), rule10.c_str(), rule11.c_str(), rule10.c_str(), rule10.c_str());
    std::string s = line + out.str();
    s += "noise floor: the error the reference's own noise gives; corrected: the error with that noise subtracted\n";
    if (r.extra.contains("loglog_slope_rmse")) {
        const auto slope = [&](const char* key) {
            return r.extra.contains(key) && r.extra[key].is_number() ? r.extra[key].get<double>() : std::nan("");
        };
        std::snprintf(line, sizeof line, "log-log slope of RMSE vs spp: %.3f raw, %s corrected (Monte Carlo: -0.5)\n",
                      slope("loglog_slope_rmse"), noiseFigureText(slope("loglog_slope_rmse_corrected")).c_str());
        s += line;
    }
    return s;
}

}  // namespace rrf
