#include "core/pipeline/evaluate_stage.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <future>
#include <stdexcept>

#include "core/data/dataset_file.h"
#include "core/eval/held_out.h"
#include "core/pipeline/evaluation_reports_file.h"
#include "core/pipeline/run_recording.h"
#include "core/eval/reference_noise.h"
#include "core/util/atomic_file.h"
#include "core/util/image_io.h"

namespace rrf {

namespace {
std::string figureText(double v) {
    if (!std::isfinite(v)) return "unknown";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

std::string evaluationFile(const std::string& dir, const std::string& name) { return (std::filesystem::path(dir) / name).string(); }

/// `text` without its final newline: notes are lines, the front end ends them.
std::string withoutFinalNewline(std::string text) {
    if (!text.empty() && text.back() == '\n') text.pop_back();
    return text;
}

/// `e` without its per-pixel data (images, maps, masks), its figures kept: an evaluation at many
/// lights holds each light's pixels only while its files are written.
void dropPixels(Evaluation& e) {
    for (Image& im : e.prediction.images) im = Image{};
    e.prediction.leaf = {};
    e.objectIds = {};
    e.footprint.pixel = {};
    e.footprint.keptByObject = {};
    e.footprint.kept = {};
    e.flip.hdrMap = Image{};
    e.flip.ldrMap = Image{};
    e.prediction.spread = Image{};
    e.prediction.spreadKnown = {};
}

double globalErrorOf(const Evaluation& e) {
    const ErrorStats& g = e.term(Term::Global).overall;
    return std::isfinite(g.relativeRmseCorrected) ? g.relativeRmseCorrected : g.relativeRmse;
}
}  // namespace

RenderOptions referenceOptions(const Project& p, int spp, int width, int height) {
    RenderSettings s = p.render;
    if (spp > 0) s.spp = spp;
    if (width > 0) s.width = width;
    if (height > 0) s.height = height;
    // Enough passes for a live progress line, few enough that pass overhead stays negligible.
    return renderOptionsFor(p.scene, s, 16);
}

NoiseTarget noiseTargetFor(const Project& p, double noise, int sppCap) {
    NoiseTarget t = p.reference.target;
    if (noise > 0) t.relativeRmse = noise;
    if (sppCap > 0) t.sppCap = sppCap;
    return t;
}

std::pair<int, int> referenceSize(const Project& p, int width, int height) {
    auto pick = [](int flag, int section, int render, int camera) {
        return flag > 0 ? flag : section > 0 ? section : render > 0 ? render : camera;
    };
    return {pick(width, p.reference.width, p.render.width, p.scene.camera.width),
            pick(height, p.reference.height, p.render.height, p.scene.camera.height)};
}

double measuredGlobalError(const Predictor& predictor, const Reference& reference) {
    return globalErrorOf(evaluate(predictor, reference));
}

double MeasuredErrorOfOnePrediction::operator()(const Reference& reference) {
    const Image& ref = reference.image(Term::Global);
    if (!gb_ || gb_->width != ref.width || gb_->height != ref.height || !(light_ == reference.lightPosition)) {
        light_ = reference.lightPosition;
        gb_ = predictor_.gbuffer(reference.lightPosition, ref.width, ref.height);
        prediction_ = predictor_.predict(*gb_);
    }
    return globalErrorOf(evaluatePrediction(*gb_, prediction_, reference));
}

ObtainedReference obtainReference(ReferenceStore& store, const Project& p, const Vec3& lp, int width, int height,
                                  const NoiseTarget& target, const std::function<double(const Reference&)>& measuredError,
                                  const StageObserver& observer) {
    const ReferenceKey key = ReferenceKey::of(p.scene, lp, width, height, p.render);
    ObtainedReference out;
    out.reference = store.obtain(
        p.scene, key, target, observer.cancel,
        [&](const ReferenceProgress& pr) {
            observer.setProgress(pr.fraction);
            if (pr.spp > 0) observer.setStatus(std::to_string(pr.spp) + " spp, noise " + figureText(pr.noise) + " -> " + figureText(pr.target));
        },
        measuredError, [&](const std::string& line) { observer.note(line); });
    if (out.reference.cancelled)
        throw std::runtime_error("interrupted while rendering the reference (saved in " + store.dir() +
                                 "; the next run continues it)");
    if (const std::optional<StoredReference> e = store.find(key)) {
        char line[400];
        std::snprintf(line, sizeof line, "reference %s: %d spp, %.1f s, relative noise direct %s, indirect %s, global %s (wanted %s)",
                      key.id().c_str(), e->spp, e->seconds, figureText(e->noise.relativeRmse[int(Term::Direct)]).c_str(),
                      figureText(e->noise.relativeRmse[int(Term::Indirect)]).c_str(),
                      figureText(e->noise.relativeRmse[int(Term::Global)]).c_str(), figureText(e->wantedNoise).c_str());
        observer.note(line);
        out.info.storeEntry = *e;
        out.info.noiseTarget = target;
    }
    return out;
}

ObtainedReference renderFixedReference(const Scene& scene, const Vec3& lp, const RenderOptions& ro, const StageObserver& observer) {
    std::atomic<double> progress{0.0};
    auto result = std::async(std::launch::async, [&] { return renderReference(scene, lp, ro, observer.cancel, &progress); });
    while (result.wait_for(std::chrono::milliseconds(100)) != std::future_status::ready) observer.setProgress(progress.load());
    ObtainedReference o;
    o.reference = result.get();
    if (o.reference.cancelled) throw std::runtime_error("interrupted while rendering the reference");
    o.info.fixedSpp = ro.spp;
    o.info.seed = ro.seed;
    return o;
}

ReferenceSource storeReferenceSource(ReferenceStore& store, const Project& p, const Predictor& predictor, int width,
                                     int height, const NoiseTarget& target, size_t lightCount, const StageRunner& run) {
    return [&store, &p, &predictor, width, height, target, lightCount, run](size_t k, const Vec3& light) {
        ObtainedReference o;
        run("reference " + std::to_string(k + 1) + "/" + std::to_string(lightCount), [&](const StageObserver& obs) {
            o = obtainReference(store, p, light, width, height, target, MeasuredErrorOfOnePrediction(predictor), obs);
        });
        return o;
    };
}

ReferenceSource fixedSppReferenceSource(const Project& p, const RenderOptions& ro, size_t lightCount, const StageRunner& run) {
    return [&p, ro, lightCount, run](size_t k, const Vec3& light) {
        ObtainedReference o;
        run("reference " + std::to_string(k + 1) + "/" + std::to_string(lightCount),
            [&](const StageObserver& obs) { o = renderFixedReference(p.scene, light, ro, obs); });
        return o;
    };
}

std::vector<Evaluation> evaluateAtLights(const Project& p, const Predictor& predictor, const std::vector<Vec3>& lights,
                                         const ReferenceSource& source, const std::string& out, float exposure,
                                         const StageObserver& observer) {
    std::vector<Evaluation> evals;
    EvaluationReports reports;
    for (size_t k = 0; k < lights.size(); ++k) {
        if (observer.cancelled()) throw std::runtime_error("interrupted while evaluating");
        const ObtainedReference obtained = source(k, lights[k]);
        const Reference& ref = obtained.reference;
        const std::string dir = lights.size() > 1 ? evaluationFile(out, "light_" + std::to_string(k)) : out;
        evals.push_back(evaluate(predictor, ref));
        evals.back().flip = flipEvaluation(evals.back(), ref);
        const Evaluation& e = evals.back();
        reports.writeLight(evaluationFile(dir, "evaluation.json"), p.scene, e, obtained.info,
                           writeEvaluationImages(dir, e, ref, exposure));
        const std::string table = evaluationTable(p.scene, e);
        writeFileAtomically(evaluationFile(dir, "evaluation.txt"), table);
        observer.note("\n" + withoutFinalNewline(table));
        char line[400];
        std::snprintf(line, sizeof line,
                      "prediction: G-buffer %.1f ms, networks %.1f ms, exact direct %.1f ms, glossy gather %.1f ms (%llu pixels); "
                      "reference %d spp, %.2f s; files in %s",
                      1e3 * e.gbufferSeconds, 1e3 * e.prediction.inferenceSeconds, 1e3 * e.prediction.directSeconds,
                      1e3 * e.prediction.gatherSeconds, (unsigned long long)e.prediction.pixelsGathered, e.referenceSpp,
                      e.referenceSeconds, dir.c_str());
        observer.note(line);
        for (const std::string& why : e.prediction.unavailableWhy) observer.note("unavailable: " + why);
        if (lights.size() > 1) dropPixels(evals.back());
        observer.setProgress(double(k + 1) / double(lights.size()));
    }
    if (evals.size() > 1) {
        const HeldOutSummary s = summarizeHeldOut(evals, p.scene.objects.size());
        const std::string table = heldOutTable(p.scene, s);
        observer.note("\nheld-out lights: spread over " + std::to_string(evals.size()) + " positions\n" + withoutFinalNewline(table));
        const std::string text = evaluationFile(out, "held_out.txt"), json = evaluationFile(out, "held_out.json");
        writeFileAtomically(text, table);
        observer.note("wrote " + text);
        reports.writeHeldOut(json, p.scene, s);
        observer.note("wrote " + json);
    }
    return evals;
}

LightGridMarks trainingLightMarks(const Project& p, const std::string& models) {
    constexpr size_t kMaxMarks = 600;  // enough to show the coverage of each slice, few enough to see its colours
    LightGridMarks m;
    const Run* trained = isBareScene(p) ? nullptr : findTrainRun(p.runs, projectDirectory(p), models);
    if (!trained) {
        m.why = "the models are not from a train run recorded in the project";
        return m;
    }
    const std::string rel = trained->settings.dataset.value_or("");
    if (rel.empty()) {
        m.why = "the train run '" + trained->name + "' names no dataset";
        return m;
    }
    const std::filesystem::path path = std::filesystem::path(rel).is_absolute() ? std::filesystem::path(rel)
                                                                                : std::filesystem::path(projectDirectory(p)) / rel;
    if (!std::filesystem::exists(path)) {
        m.why = "the dataset " + path.string() + " of train run '" + trained->name + "' is gone";
        return m;
    }
    try {
        const Dataset d(path.string(), false, p.scene.contentHash());
        m.positions = datasetLightPositions(d, kMaxMarks);
        m.source = path.string();
    } catch (const std::exception& e) {
        m.why = std::string("its dataset could not be read: ") + e.what();
    }
    return m;
}

LightGridOutcome evaluateLightGrid(const Project& p, const Predictor& predictor, const LightGridSpec& grid,
                                   const ReferenceSource& source, const std::string& out, float exposure,
                                   const LightGridMarks& marks, const StageObserver& observer) {
    const Bounds3 region = p.scene.lightRange();
    LightGridOutcome outcome;
    outcome.evaluations = evaluateAtLights(p, predictor, grid.positions(region), source, out, exposure, observer);
    LightGridMap& map = outcome.map;
    map = lightGridMap(grid, region, outcome.evaluations, p.scene.objects.size());
    map.marks = marks.positions;
    map.marksSource = marks.source;
    map.marksWhy = marks.why;
    // Cells large enough to read a mark's place in them, the slice at least 256 pixels across.
    const int cell = std::max(8, 256 / std::max(grid.counts[0], grid.counts[2]));
    const double scale = LightGridMap::scaleOf(map.global);
    std::vector<LightGridSlice> slices;
    for (int j = 0; j < grid.counts[1]; ++j) {
        const std::string name = "light_grid_y" + std::to_string(j) + ".png";
        writeImage(evaluationFile(out, name), lightGridSlice(map, map.global, j, cell, scale), ImageFormat::PNG);
        slices.push_back({map.lights[grid.index(0, j, 0)].y, name});
    }
    // The set of slices is replaced whole: slices of an earlier, taller grid in `out` go.
    for (int j = grid.counts[1];; ++j) {
        std::error_code ec;
        if (!std::filesystem::remove(evaluationFile(out, "light_grid_y" + std::to_string(j) + ".png"), ec)) break;
    }
    const std::string table = lightGridTable(p.scene, map);
    writeFileAtomically(evaluationFile(out, "light_grid.txt"), table);
    writeLightGridReport(evaluationFile(out, "light_grid.json"), p.scene, map, slices);
    observer.note("\nerror across the light region (" + grid.text() + ", colour scale 0.." + figureText(scale) + "; " +
                  (map.marks.empty() ? "no training lights marked: " + map.marksWhy
                                     : std::to_string(map.marks.size()) + " training records' lights marked from " + map.marksSource) +
                  ")\n" + withoutFinalNewline(table));
    observer.note("wrote " + evaluationFile(out, "light_grid.json") + ", light_grid.txt and " + std::to_string(grid.counts[1]) +
                  " slice image(s) light_grid_y<j>.png");
    return outcome;
}

}  // namespace rrf
