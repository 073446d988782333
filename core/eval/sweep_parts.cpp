// A sweep's parts: runSweep as one part, the join of several, and their bytes between processes.
#include "core/eval/sweep_parts.h"

#include <numeric>
#include <optional>
#include <stdexcept>

#include "core/eval/reference_noise.h"
#include "core/util/byte_stream.h"

namespace rrf {

namespace {

void writeImageBytes(ByteWriter& out, const Image& image) {
    out.i64(image.width);
    out.i64(image.height);
    out.floats(image.data);
}

Image readImageBytes(ByteReader& in, const std::string& source) {
    Image image;
    image.width = int(in.i64());
    image.height = int(in.i64());
    image.data = in.floats();
    if (image.width < 0 || image.height < 0 || image.data.size() != 3 * image.pixelCount())
        throw std::runtime_error(source + ": an image of the wrong size");
    return image;
}

void writeErrorStats(ByteWriter& out, const ErrorStats& s) {
    out.u64(s.pixels);
    out.u64(s.nonFinite);
    for (double v : {s.rmse, s.relativeRmse, s.mae, s.maxError, s.meanReference, s.rmseNoiseFloor, s.rmseCorrected,
                     s.relativeRmseNoiseFloor, s.relativeRmseCorrected})
        out.f64(v);
    out.u64(s.noiseKnown);
}

ErrorStats readErrorStats(ByteReader& in) {
    ErrorStats s;
    s.pixels = in.u64();
    s.nonFinite = in.u64();
    for (double* v : {&s.rmse, &s.relativeRmse, &s.mae, &s.maxError, &s.meanReference, &s.rmseNoiseFloor, &s.rmseCorrected,
                      &s.relativeRmseNoiseFloor, &s.relativeRmseCorrected})
        *v = in.f64();
    s.noiseKnown = in.u64() != 0;
    return s;
}

void writeSweepRow(ByteWriter& out, const SweepRow& row) {
    out.string(row.setting);
    out.u64(row.stageSeconds.size());
    for (const auto& [stage, seconds] : row.stageSeconds) {
        out.string(stage);
        out.f64(seconds);
    }
    writeErrorStats(out, row.overall);
    out.u64(row.perObject.size());
    for (const ErrorStats& s : row.perObject) writeErrorStats(out, s);
    out.i64(row.spp);
    for (double v : {row.oneOffSeconds, row.frameSeconds, row.glslFrameSeconds, row.breakEven.spp, row.breakEven.seconds})
        out.f64(v);
    out.u64(row.breakEven.known);
    out.u64(row.breakEven.extrapolated);
    const std::vector<uint8_t> cbor = nlohmann::json::to_cbor(row.extra);
    out.string(std::string(cbor.begin(), cbor.end()));
}

SweepRow readSweepRow(ByteReader& in, const std::string& source) {
    SweepRow row;
    row.setting = in.string();
    for (uint64_t n = in.u64(); n > 0; --n) {
        std::string stage = in.string();
        row.stageSeconds.push_back({std::move(stage), in.f64()});
    }
    row.overall = readErrorStats(in);
    for (uint64_t n = in.u64(); n > 0; --n) row.perObject.push_back(readErrorStats(in));
    row.spp = int(in.i64());
    for (double* v : {&row.oneOffSeconds, &row.frameSeconds, &row.glslFrameSeconds, &row.breakEven.spp, &row.breakEven.seconds})
        *v = in.f64();
    row.breakEven.known = in.u64() != 0;
    row.breakEven.extrapolated = in.u64() != 0;
    const std::string cbor = in.string();
    try {
        row.extra = nlohmann::json::from_cbor(cbor);
    } catch (const nlohmann::json::exception& e) {
        throw std::runtime_error(source + ": a sweep row's extra fields do not read back (" + e.what() + ")");
    }
    return row;
}

}  // namespace

std::string encodeReference(const Reference& r) {
    ByteWriter out;
    for (int t = 0; t < kTermCount; ++t) writeImageBytes(out, r.images[t]);
    for (int t = 0; t < kTermCount; ++t) writeImageBytes(out, r.variances[t]);
    for (float v : {r.lightPosition.x, r.lightPosition.y, r.lightPosition.z}) out.f64(v);
    out.i64(r.spp);
    out.f64(r.seconds);
    out.u64(r.nonFinite);
    out.u64(r.cancelled);
    return out.take();
}

Reference decodeReference(const std::string& bytes, const std::string& source) {
    ByteReader in(bytes, source);
    Reference r;
    for (int t = 0; t < kTermCount; ++t) r.images[t] = readImageBytes(in, source);
    for (int t = 0; t < kTermCount; ++t) r.variances[t] = readImageBytes(in, source);
    for (float* v : {&r.lightPosition.x, &r.lightPosition.y, &r.lightPosition.z}) *v = float(in.f64());
    r.spp = int(in.i64());
    r.seconds = in.f64();
    r.nonFinite = in.u64();
    r.cancelled = in.u64() != 0;
    if (!in.atEnd()) throw std::runtime_error(source + ": bytes left over after the reference");
    return r;
}

std::string encodeSweepPart(const SweepPart& part) {
    ByteWriter out;
    out.u64(part.tasks.size());
    for (size_t i = 0; i < part.tasks.size(); ++i) {
        out.i64(part.tasks[i]);
        out.u64(part.rows[i].size());
        for (const SweepRow& row : part.rows[i]) writeSweepRow(out, row);
    }
    out.u64(part.cancelled);
    return out.take();
}

SweepPart decodeSweepPart(const std::string& bytes, const std::string& source) {
    ByteReader in(bytes, source);
    SweepPart part;
    for (uint64_t n = in.u64(); n > 0; --n) {
        part.tasks.push_back(int(in.i64()));
        std::vector<SweepRow>& rows = part.rows.emplace_back();
        for (uint64_t k = in.u64(); k > 0; --k) rows.push_back(readSweepRow(in, source));
    }
    part.cancelled = in.u64() != 0;
    if (!in.atEnd()) throw std::runtime_error(source + ": bytes left over after the sweep part");
    return part;
}

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
        r.extra["loglog_slope_rmse"] = logLogSlope(xs, ys);
        // Without the reference's noise the curve flattens towards its floor; the corrected slope does not.
        r.extra["loglog_slope_rmse_corrected"] = noiseFigureJson(logLogSlope(xs, ysCorrected));
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
    if (in.data) r.extra["generate_seconds"] = in.data->seconds;
    return r;
}

SweepResult runSweep(const Scene& scene, const SweepOptions& options) {
    const SweepOptions o = checkedSweepOptions(scene, options);
    Reference reference = obtainSweepReference(scene, o);
    const bool cancelled = o.cancel && o.cancel->load();
    std::shared_ptr<const GeneratedData> data;
    if (sweepSharesData(o) && !cancelled) data = std::make_shared<const GeneratedData>(DataGenerator(scene, o.sampling).run(0, 1, o.cancel));
    const SweepInputs in = sweepInputs(scene, o, std::move(reference), std::move(data));
    std::vector<int> all(sweepTasks(o).size());
    std::iota(all.begin(), all.end(), 0);
    std::vector<SweepPart> parts;
    parts.push_back(runSweepTasks(scene, o, in, all));
    return joinSweepParts(scene, o, in, std::move(parts));
}

}  // namespace rrf
