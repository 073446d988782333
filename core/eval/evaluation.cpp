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
nlohmann::json vec(const Vec3& v) { return {v.x, v.y, v.z}; }

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

Reference loadReference(const std::string& dir) {
    const std::string meta = (fs::path(dir) / "render.json").string();
    Reference r;
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(readFile(meta));
        const auto lp = j.at("light_position").get<std::vector<float>>();
        if (lp.size() != 3) throw InputError(meta, "/light_position", "expected 3 numbers");
        r.lightPosition = Vec3(lp[0], lp[1], lp[2]);
        r.spp = j.value("spp_completed", 0);
        r.seconds = j.value("seconds", 0.0);
        r.nonFinite = j.value("non_finite_samples_dropped", uint64_t(0));
    } catch (const nlohmann::json::exception& e) {
        throw InputError(meta, "", std::string("not a render.json written by rrf render: ") + e.what());
    } catch (const std::runtime_error& e) {
        throw InputError(meta, "", std::string("no reference render here: ") + e.what());
    }
    for (int t = 0; t < kTermCount; ++t) {
        std::string path;
        for (const char* ext : {".exr", ".pfm"}) {
            const std::string p = (fs::path(dir) / (std::string(termName(Term(t))) + ext)).string();
            if (fs::exists(p)) {
                path = p;
                break;
            }
        }
        if (path.empty())
            throw InputError((fs::path(dir) / termName(Term(t))).string() + ".exr", "",
                             "missing: render the reference with --format exr or pfm");
        r.images[t] = readImage(path);
    }
    // Variances are optional: a render.json without "variance_images" leaves the noise unknown.
    if (j.contains("variance_images")) {
        const nlohmann::json& files = j["variance_images"];
        for (Term t : kTerms) {
            const std::string pointer = std::string("/variance_images/") + termName(t);
            if (!files.is_object() || !files.contains(termName(t)) || !files[termName(t)].is_string())
                throw InputError(meta, pointer, "expected the file name of the variance image");
            const std::string path = (fs::path(dir) / files[termName(t)].get<std::string>()).string();
            if (!fs::exists(path)) throw InputError(path, "", std::string("missing: listed in ") + meta + " at " + pointer);
            Image v = readImage(path);
            const Image& im = r.image(t);
            if (v.width != im.width || v.height != im.height)
                throw InputError(path, "", "expected a " + std::to_string(im.width) + "x" + std::to_string(im.height) +
                                               " variance image like " + termName(t) + ", got " + std::to_string(v.width) +
                                               "x" + std::to_string(v.height));
            r.variances[int(t)] = std::move(v);
        }
    }
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

nlohmann::json evaluationJson(const Scene& scene, const Evaluation& e) {
    const Prediction& p = e.prediction;
    nlohmann::json terms = nlohmann::json::object();
    for (int t = 0; t < kTermCount; ++t) {
        const TermErrors& te = e.terms[t];
        nlohmann::json objects = nlohmann::json::array();
        for (size_t id = 0; id < te.perObject.size(); ++id) {
            nlohmann::json o = te.perObject[id].toJson();
            o["id"] = int(id);
            o["name"] = id < scene.objects.size() ? scene.objects[id].name : "";
            objects.push_back(o);
        }
        terms[termName(Term(t))] = {{"available", te.available}, {"overall", te.overall.toJson()}, {"objects", objects}};
    }
    nlohmann::json report = {
        {"light_position", vec(e.lightPosition)},
        {"footprint_mask", toJson(e.footprint.counts)},
        {"reference",
         {{"spp", e.referenceSpp},
          {"seconds", e.referenceSeconds},
          {"non_finite_samples_dropped", e.referenceNonFinite},
          {"noise", e.referenceNoiseKnown ? "per-pixel variance of the mean known: noise floor and corrected figures given"
                                          : "unknown (the reference has no variance images): noise floor and corrected figures are null"}}},
        {"prediction",
         {{"gbuffer_seconds", e.gbufferSeconds},
          {"inference_seconds", p.inferenceSeconds},
          {"exact_direct_seconds", p.directSeconds},
          {"gather_seconds", p.gatherSeconds},
          {"pixels_gathered", p.pixelsGathered},
          {"pixels_predicted", p.pixelsPredicted},
          {"pixels_without_network", p.pixelsWithoutNetwork},
          {"objects_without_network", p.objectsWithoutNetwork},
          {"non_finite_values", p.nonFinite},
          {"unavailable", p.unavailableWhy}}},
        {"metric",
         "per channel, averaged over RGB; relative error |d|/(|ref|+0.01); overall = all object pixels the footprint mask keeps; "
         "*_noise_floor = the figure the reference's own noise gives (sqrt of the mean variance of the mean, relative: "
         "divided by (|ref|+0.01)^2); *_corrected = sqrt(max(0, mean(d^2 - variance))) (relative: each term divided by "
         "(|ref|+0.01)^2), an estimate of the error against the noise-free truth"},
        {"terms", terms},
    };
    if (e.flip.available) {
        std::vector<std::string> names;
        for (const auto& o : scene.objects) names.push_back(o.name);
        report["flip"] = flipJson(e.flip, names);
    }
    if (e.uncertainty.available) {
        std::vector<std::string> names;
        for (const auto& o : scene.objects) names.push_back(o.name);
        report["uncertainty"] = e.uncertainty.toJson(names);
        report["prediction"]["spread_pixels"] = p.spreadPixels;
        report["prediction"]["spread_seconds"] = p.spreadSeconds;
    }
    return report;
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

nlohmann::json writeEvaluationImages(const std::string& dir, const Evaluation& e, const Reference& reference,
                                     float exposureStops) {
    nlohmann::json files = writePredictionImages(dir, e.prediction, exposureStops);
    nlohmann::json ranges = nlohmann::json::object();
    uint64_t nonFinite = 0;
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
            ranges[std::string(errorMapName(k)) + "_" + term] = {errorMapIsSigned(k) ? -double(hi) : 0.0, double(hi)};
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
            ranges[name] = {0.0, 1.0};
            files.push_back(base + ".exr");
            files.push_back(base + ".png");
        }
    return {{"files", files}, {"false_colour_ranges", ranges}, {"non_finite_map_pixels", nonFinite}};
}

}  // namespace rrf
