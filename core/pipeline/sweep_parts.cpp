// The bytes a sweep's processes exchange: the reference and the parts (sweep_parts.h).
#include "core/pipeline/sweep_parts.h"

#include <optional>
#include <stdexcept>

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
                     s.relativeRmseNoiseFloor, s.relativeRmseCorrected, s.signedRelativeMean, s.relMse,
                     s.relMseNoiseFloor, s.relMseCorrected, s.smape})
        out.f64(v);
    out.u64(s.noiseKnown);
}

ErrorStats readErrorStats(ByteReader& in) {
    ErrorStats s;
    s.pixels = in.u64();
    s.nonFinite = in.u64();
    for (double* v : {&s.rmse, &s.relativeRmse, &s.mae, &s.maxError, &s.meanReference, &s.rmseNoiseFloor, &s.rmseCorrected,
                      &s.relativeRmseNoiseFloor, &s.relativeRmseCorrected, &s.signedRelativeMean, &s.relMse,
                      &s.relMseNoiseFloor, &s.relMseCorrected, &s.smape})
        *v = in.f64();
    s.noiseKnown = in.u64() != 0;
    return s;
}

// A figure that may be absent: a presence flag, then its bits.
void writeOptional(ByteWriter& out, const std::optional<int64_t>& v) {
    out.u64(v.has_value());
    if (v) out.i64(*v);
}
void writeOptional(ByteWriter& out, const std::optional<uint64_t>& v) {
    out.u64(v.has_value());
    if (v) out.u64(*v);
}
void writeOptional(ByteWriter& out, const std::optional<double>& v) {
    out.u64(v.has_value());
    if (v) out.f64(*v);
}
void writeOptional(ByteWriter& out, const std::optional<SweepTermFigures>& v) {
    out.u64(v.has_value());
    if (v)
        for (double f : {v->relativeRmse, v->relativeRmseNoiseFloor, v->relativeRmseCorrected}) out.f64(f);
}

void readOptional(ByteReader& in, std::optional<int64_t>& v) {
    if (in.u64()) v = in.i64();
}
void readOptional(ByteReader& in, std::optional<uint64_t>& v) {
    if (in.u64()) v = in.u64();
}
void readOptional(ByteReader& in, std::optional<double>& v) {
    if (in.u64()) v = in.f64();
}
void readOptional(ByteReader& in, std::optional<SweepTermFigures>& v) {
    if (!in.u64()) return;
    SweepTermFigures f;
    for (double* p : {&f.relativeRmse, &f.relativeRmseNoiseFloor, &f.relativeRmseCorrected}) *p = in.f64();
    v = f;
}

void writeRowFigures(ByteWriter& out, const SweepRowFigures& f) {
    for (const std::optional<int64_t>* v : {&f.parameters, &f.modelBytes, &f.leaves, &f.leafEpochs}) writeOptional(out, *v);
    for (const std::optional<uint64_t>* v : {&f.pixelsWithoutNetwork, &f.nonFinitePredictionValues, &f.nonFiniteSamplesDropped,
                                             &f.records, &f.recordsAtSppCap})
        writeOptional(out, *v);
    writeOptional(out, f.direct);
    writeOptional(out, f.indirect);
    writeOptional(out, f.meanRecordSpp);
    out.u64(f.curve.has_value());
    if (f.curve) {
        out.u64(f.curve->size());
        for (const SweepCurvePoint& p : *f.curve) {
            out.i64(p.object);
            out.string(p.target);
            out.i64(p.epoch);
            for (double v : {p.seconds, p.trainLoss, p.validationLoss}) out.f64(v);
        }
    }
    out.string(f.other.text);
}

SweepRowFigures readRowFigures(ByteReader& in) {
    SweepRowFigures f;
    for (std::optional<int64_t>* v : {&f.parameters, &f.modelBytes, &f.leaves, &f.leafEpochs}) readOptional(in, *v);
    for (std::optional<uint64_t>* v : {&f.pixelsWithoutNetwork, &f.nonFinitePredictionValues, &f.nonFiniteSamplesDropped,
                                       &f.records, &f.recordsAtSppCap})
        readOptional(in, *v);
    readOptional(in, f.direct);
    readOptional(in, f.indirect);
    readOptional(in, f.meanRecordSpp);
    if (in.u64()) {
        std::vector<SweepCurvePoint>& curve = f.curve.emplace();
        for (uint64_t n = in.u64(); n > 0; --n) {
            SweepCurvePoint& p = curve.emplace_back();
            p.object = int(in.i64());
            p.target = in.string();
            p.epoch = int(in.i64());
            for (double* v : {&p.seconds, &p.trainLoss, &p.validationLoss}) *v = in.f64();
        }
    }
    f.other.text = in.string();
    return f;
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
    writeRowFigures(out, row.extra);
}

SweepRow readSweepRow(ByteReader& in) {
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
    row.extra = readRowFigures(in);
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
        for (uint64_t k = in.u64(); k > 0; --k) rows.push_back(readSweepRow(in));
    }
    part.cancelled = in.u64() != 0;
    if (!in.atEnd()) throw std::runtime_error(source + ": bytes left over after the sweep part");
    return part;
}

}  // namespace rrf
