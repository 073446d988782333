#include "core/eval/evaluation.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "core/predict/footprint_mask_json.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/util/image_io.h"
#include "core/render/render_outputs.h"

namespace rrf {

namespace fs = std::filesystem;

namespace {
double since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}
}  // namespace

LightRender renderAtLight(const Scene& scene, const Vec3& lightPos, const RenderOptions& options, const std::atomic<bool>* cancel,
                          std::atomic<double>* progress) {
    Scene moved = scene;
    if (!moved.lights.empty()) moved.setLightPosition(lightPos);
    const Accel accel(moved);
    Renderer renderer(moved, accel, options);
    LightRender r;
    r.lightPosition = moved.lightPosition();
    while (renderer.progress() < 1.0) {
        if (cancel && cancel->load()) {
            r.cancelled = true;
            break;
        }
        if (!renderer.runPass()) break;
        if (progress) *progress = renderer.progress();
    }
    r.state = renderer.exportState();
    return r;
}

Reference renderReference(const Scene& scene, const Vec3& lightPos, const RenderOptions& options,
                          const std::atomic<bool>* cancel, std::atomic<double>* progress) {
    const LightRender rendered = renderAtLight(scene, lightPos, options, cancel, progress);
    Reference r = referenceOf(Renderer::snapshotOf(rendered.state), rendered.lightPosition);
    r.cancelled = rendered.cancelled;
    return r;
}

Reference referenceOf(const RenderSnapshot& s, const Vec3& lightPosition) {
    Reference r;
    for (Term t : kTerms) {
        r.images[int(t)] = s.image(t);
        if (s.varianceKnown()) r.variances[int(t)] = s.varianceOf(t);
    }
    r.lightPosition = lightPosition;
    r.spp = s.sppCompleted;
    r.seconds = s.seconds;
    r.nonFinite = s.nonFinite;
    return r;
}

Evaluation evaluate(const Predictor& predictor, const Reference& reference) {
    const Image& ref = reference.image(Term::Global);
    if (ref.empty()) throw std::invalid_argument("evaluate: the reference has no pixels");
    const auto t0 = std::chrono::steady_clock::now();
    const GBuffer gb = predictor.gbuffer(reference.lightPosition, ref.width, ref.height);
    const double gbufferSeconds = since(t0);
    Evaluation e = evaluatePrediction(gb, predictor.predict(gb), reference);
    e.gbufferSeconds = gbufferSeconds;
    return e;
}

Evaluation evaluatePrediction(const GBuffer& gb, Prediction prediction, const Reference& reference) {
    const Image& ref = reference.image(Term::Global);
    if (ref.empty()) throw std::invalid_argument("evaluate: the reference has no pixels");
    if (ref.width != gb.width || ref.height != gb.height)
        throw std::invalid_argument("evaluate: the prediction's size is not the reference's");
    Evaluation e;
    e.lightPosition = reference.lightPosition;
    e.referenceSeconds = reference.seconds;
    e.referenceSpp = reference.spp;
    e.referenceNonFinite = reference.nonFinite;
    e.referenceNoiseKnown = !reference.variance(Term::Global).empty();
    e.prediction = std::move(prediction);
    e.objectIds = gb.object;
    // Pixels whose footprint may cover more than one surface are left out and counted: the
    // reference's box filter mixes surfaces there, which a pixel-centre prediction cannot reproduce
    // whatever the network (core/predict/footprint_mask.h).
    e.footprint = footprintMask(gb);
    const std::vector<std::vector<uint32_t>>& masks = e.footprint.keptByObject;
    const std::vector<uint32_t>& covered = e.footprint.kept;
    for (int t = 0; t < kTermCount; ++t) {
        TermErrors& te = e.terms[t];
        te.available = e.prediction.available[t];
        const Image& variance = reference.variances[t];  // empty: noise unknown
        for (const auto& px : masks)
            te.perObject.push_back(errorStatsWithNoise(e.prediction.images[t], reference.images[t], variance, px));
        te.overall = errorStatsWithNoise(e.prediction.images[t], reference.images[t], variance, covered);
    }
    e.uncertainty = evaluateUncertainty(e.prediction, ref, masks, covered);
    return e;
}

std::string evaluationTable(const Scene& scene, const Evaluation& e) {
    std::ostringstream out;
    char line[420];
    std::snprintf(line, sizeof line, "light at (%.3f, %.3f, %.3f), reference %d spp, reference noise %s\n", e.lightPosition.x,
                  e.lightPosition.y, e.lightPosition.z, e.referenceSpp,
                  e.referenceNoiseKnown ? "known (per-pixel variance of the mean)" : "unknown (no variance images)");
    out << line;
    // Each error comes with the reference's noise floor (what the reference's noise alone gives) and
    // the corrected figure (the error against the noise-free truth); see core/eval/error_metrics.h.
    std::snprintf(line, sizeof line, "%-9s %-14s %8s %10s %11s %10s %10s %11s %10s %10s %10s %10s %10s %10s %10s\n", "term",
                  "object", "pixels", "RMSE", "noise floor", "corrected", "rel.RMSE", "noise floor", "corrected", "bias",
                  "relMSE", "SMAPE", "MAE", "max", "mean ref");
    out << line;
    for (int t = 0; t < kTermCount; ++t) {
        const TermErrors& te = e.terms[t];
        if (!te.available) {
            std::snprintf(line, sizeof line, "%-9s (not predicted by these networks)\n", termName(Term(t)));
            out << line;
            continue;
        }
        auto row = [&](const std::string& name, const ErrorStats& s) {
            std::snprintf(line, sizeof line, "%-9s %-14s %8llu %10s %11s %10s %10s %11s %10s %10s %10s %10s %10s %10s %10s\n",
                          termName(Term(t)), name.substr(0, 14).c_str(), (unsigned long long)s.pixels, num(s.rmse).c_str(),
                          noiseFigureText(s.rmseNoiseFloor).c_str(), noiseFigureText(s.rmseCorrected).c_str(),
                          num(s.relativeRmse).c_str(), noiseFigureText(s.relativeRmseNoiseFloor).c_str(),
                          noiseFigureText(s.relativeRmseCorrected).c_str(), num(s.signedRelativeMean).c_str(),
                          num(s.relMse).c_str(), num(s.smape).c_str(), num(s.mae).c_str(), num(s.maxError).c_str(),
                          num(s.meanReference).c_str());
            out << line;
        };
        for (size_t id = 0; id < te.perObject.size(); ++id)
            if (te.perObject[id].pixels) row(id < scene.objects.size() ? scene.objects[id].name : std::to_string(id), te.perObject[id]);
        row("ALL OBJECTS", te.overall);
    }
    out << "noise floor: the error the reference's own Monte Carlo noise gives; corrected: the error with that noise "
           "subtracted (sqrt(max(0, mean(d^2 - Var(ref))))), an estimate against the noise-free truth; bias: mean "
           "d / (|ref| + 0.01), signed; relMSE: mean d^2 / (ref^2 + 0.01); SMAPE: mean |d| / (|pred| + |ref| + 0.01)\n";
    if (e.flip.available) {
        const FlipEvaluation& f = e.flip;
        std::snprintf(line, sizeof line,
                      "FLIP (global term, %.1f pixels per degree; HDR over %d exposures %.2f to %.2f stops)\n%-14s %8s %10s %11s %10s %10s %10s %10s\n",
                      f.settings.pixelsPerDegree, f.range.count, f.range.start, f.range.stop, "object", "pixels", "HDR-FLIP",
                      "noise floor", "w.median", "w.Q1", "w.Q3", "LDR-FLIP");
        out << line;
        auto flipRow = [&](const std::string& name, const FlipStats& s, const std::string& floor, const std::string& ldr) {
            std::snprintf(line, sizeof line, "%-14s %8llu %10s %11s %10s %10s %10s %10s\n", name.substr(0, 14).c_str(),
                          (unsigned long long)s.pixels, num(s.mean).c_str(), floor.c_str(), num(s.weightedMedian).c_str(),
                          num(s.weightedFirstQuartile).c_str(), num(s.weightedThirdQuartile).c_str(), ldr.c_str());
            out << line;
        };
        for (size_t id = 0; id < f.hdrPerObject.size(); ++id)
            if (f.hdrPerObject[id].pixels)
                flipRow(id < scene.objects.size() ? scene.objects[id].name : std::to_string(id), f.hdrPerObject[id], "", "");
        flipRow("ALL OBJECTS", f.hdr, noiseFigureText(f.hdrNoiseFloor), num(f.ldr.mean));
        out << "FLIP: mean per-pixel perceived difference in [0, 1] (w. = weighted by the error, as the FLIP tools "
               "pool it); noise floor: the reference against itself plus one draw of its own noise\n";
    }
    if (e.uncertainty.available) {
        const UncertaintyEvaluation& u = e.uncertainty;
        std::snprintf(line, sizeof line, "uncertainty (ensemble members' spread, global term)\n%-14s %8s %12s %12s %10s\n",
                      "object", "pixels", "rel.spread", "rel.error", "Spearman");
        out << line;
        auto uRow = [&](const std::string& name, const UncertaintyStats& s) {
            std::snprintf(line, sizeof line, "%-14s %8llu %12s %12s %10s\n", name.substr(0, 14).c_str(),
                          (unsigned long long)s.pixels, num(s.meanRelativeSpread).c_str(), num(s.meanRelativeError).c_str(),
                          noiseFigureText(s.spearman).c_str());
            out << line;
        };
        for (size_t id = 0; id < u.perObject.size(); ++id)
            if (u.perObject[id].pixels) uRow(id < scene.objects.size() ? scene.objects[id].name : std::to_string(id), u.perObject[id]);
        uRow("ALL OBJECTS", u.overall);
        out << "rel.spread: mean sd / (|pred| + 0.01) over the members; Spearman: its rank correlation with the "
               "relative error per pixel (1: it ranks the pixels as their error does; 0: it does not)\n";
    }
    const Prediction& p = e.prediction;
    if (!p.objectsWithoutNetwork.empty())
        out << "objects without a network (shown black): " << p.objectsWithoutNetwork.size() << " objects, "
            << p.pixelsWithoutNetwork << " pixels\n";
    out << "NaN/Inf: " << p.nonFinite << " prediction values, " << e.referenceNonFinite << " reference samples\n";
    out << e.footprint.counts.describe() << "\n";
    return out.str();
}

std::vector<std::string> writePredictionImages(const std::string& dir, const Prediction& p, float exposureStops) {
    makeDirectories(dir);
    std::vector<std::string> files;
    for (int t = 0; t < kTermCount; ++t) {
        if (!p.available[t]) continue;
        const std::string base = (fs::path(dir) / (std::string("prediction_") + termName(Term(t)))).string();
        writeImage(base + ".exr", p.images[t], ImageFormat::EXR);
        writeImage(base + ".png", p.images[t], ImageFormat::PNG, exposureStops);
        files.push_back(base + ".exr");
        files.push_back(base + ".png");
    }
    if (!p.spread.empty()) {
        // The members' spread (radiance, RGB) and its relative form on viridis over [0, p99].
        const std::string spread = (fs::path(dir) / "spread_global.exr").string();
        writeImage(spread, p.spread, ImageFormat::EXR);
        const Image rel = relativeSpreadMap(p.spread, p.image(Term::Global), p.spreadKnown);
        const std::string base = (fs::path(dir) / "spread_relative_global").string();
        writeImage(base + ".exr", rel, ImageFormat::EXR);
        writeImage(base + ".png", falseColor(rel, 0.f, relativeSpreadScale(rel, p.spreadKnown)), ImageFormat::PNG);
        for (const std::string& f : {spread, base + ".exr", base + ".png"}) files.push_back(f);
    }
    return files;
}

EvaluationImages writeEvaluationImages(const std::string& dir, const Evaluation& e, const Reference& reference,
                                      float exposureStops) {
    EvaluationImages out;
    out.files = writePredictionImages(dir, e.prediction, exposureStops);
    std::vector<std::string>& files = out.files;
    uint64_t& nonFinite = out.nonFiniteMapPixels;
    for (int t = 0; t < kTermCount; ++t) {
        if (!e.prediction.available[t]) continue;
        const std::string term = termName(Term(t));
        const std::string ref = (fs::path(dir) / ("reference_" + term + ".exr")).string();
        writeImage(ref, reference.images[t], ImageFormat::EXR);
        files.push_back(ref);
        for (ErrorMapKind k : kErrorMapKinds) {
            const Image map = errorMap(e.prediction.images[t], reference.images[t], k);
            const std::string base = (fs::path(dir) / (std::string("error_") + errorMapName(k) + "_" + term)).string();
            uint64_t replaced = 0;
            writeImage(base + ".exr", finiteMap(map, replaced), ImageFormat::EXR);
            nonFinite += replaced;
            // [0, p99]: a few edge pixels (box filter vs pixel centre) must not wash out the scale;
            // a signed map over ±p99 of |value|, centred at 0.
            const float hi = errorMapScale(map, k);
            writeImage(base + ".png", errorMapColour(map, k, hi), ImageFormat::PNG);
            out.falseColourRanges[std::string(errorMapName(k)) + "_" + term] = {errorMapIsSigned(k) ? -double(hi) : 0.0, double(hi)};
            files.push_back(base + ".exr");
            files.push_back(base + ".png");
        }
    }
    if (e.flip.available)
        for (const auto& [name, map] : {std::pair<const char*, const Image*>{"flip_hdr_global", &e.flip.hdrMap},
                                        std::pair<const char*, const Image*>{"flip_ldr_global", &e.flip.ldrMap}}) {
            const std::string base = (fs::path(dir) / name).string();
            uint64_t replaced = 0;
            writeImage(base + ".exr", finiteMap(*map, replaced), ImageFormat::EXR);
            nonFinite += replaced;
            writeImage(base + ".png", flipColour(*map), ImageFormat::PNG);  // magma over [0, 1], FLIP's own scale
            out.falseColourRanges[name] = {0.0, 1.0};
            files.push_back(base + ".exr");
            files.push_back(base + ".png");
        }
    return out;
}

}  // namespace rrf
