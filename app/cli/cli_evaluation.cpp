#include "app/cli/cli_evaluation.h"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "app/cli/cli_common.h"
#include "core/eval/held_out.h"
#include "core/project/project.h"
#include "core/project/run_recording.h"
#include "core/util/atomic_file.h"

namespace rrf::cli {

namespace {
std::string num(double v) {
    if (!std::isfinite(v)) return "unknown";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
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

Reference renderWithProgress(const Scene& scene, const Vec3& lp, const RenderOptions& o, const std::string& label) {
    std::atomic<bool> cancel{false};
    std::atomic<double> progress{0.0};
    Reference r;
    runWithProgress(label, [&] { r = renderReference(scene, lp, o, &cancel, &progress); },
                    [&] { return std::make_pair(progress.load(), std::string()); }, [&] { cancel = true; });
    if (r.cancelled) throw std::runtime_error("interrupted while rendering the reference");
    return r;
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

namespace {
double globalErrorOf(const Evaluation& e) {
    const ErrorStats& g = e.term(Term::Global).overall;
    return std::isfinite(g.relativeRmseCorrected) ? g.relativeRmseCorrected : g.relativeRmse;
}
}  // namespace

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

ObtainedReference obtainWithProgress(ReferenceStore& store, const Project& p, const Vec3& lp, int width, int height,
                                     const NoiseTarget& target, const std::function<double(const Reference&)>& measuredError,
                                     const std::string& label) {
    const ReferenceKey key = ReferenceKey::of(p.scene, lp, width, height, p.render);
    std::atomic<bool> cancel{false};
    std::mutex m;
    ReferenceProgress last;
    ObtainedReference out;
    auto log = [](const std::string& line) {
        std::printf("%s\n", line.c_str());
        std::fflush(stdout);
    };
    runWithProgress(
        label,
        [&] {
            out.reference = store.obtain(
                p.scene, key, target, &cancel,
                [&](const ReferenceProgress& pr) {
                    std::lock_guard<std::mutex> lock(m);
                    last = pr;
                },
                measuredError, log);
        },
        [&] {
            std::lock_guard<std::mutex> lock(m);
            return std::make_pair(last.fraction, last.spp > 0 ? std::to_string(last.spp) + " spp, noise " + num(last.noise) +
                                                                     " -> " + num(last.target)
                                                               : std::string());
        },
        [&] { cancel = true; });
    if (out.reference.cancelled)
        throw std::runtime_error("interrupted while rendering the reference (saved in " + store.dir() +
                                 "; the next run continues it)");
    const std::optional<StoredReference> e = store.find(key);
    if (e) {
        std::printf("reference %s: %d spp, %.1f s, relative noise direct %s, indirect %s, global %s (wanted %s)\n",
                    key.id().c_str(), e->spp, e->seconds, num(e->noise.relativeRmse[int(Term::Direct)]).c_str(),
                    num(e->noise.relativeRmse[int(Term::Indirect)]).c_str(),
                    num(e->noise.relativeRmse[int(Term::Global)]).c_str(), num(e->wantedNoise).c_str());
        out.info = {{"store_entry", e->dir}, {"id", key.id()}, {"spp", e->spp}, {"seconds", e->seconds},
                    {"noise", e->noise.toJson()}, {"wanted_noise", noiseFigureJson(e->wantedNoise)},
                    {"noise_target", {{"noise", target.relativeRmse}, {"error_fraction", target.errorFraction},
                                      {"spp_cap", target.sppCap}}}};
    }
    return out;
}

ReferenceSource storeSource(ReferenceStore& store, const Project& p, const Predictor& predictor, int width, int height,
                            const NoiseTarget& target, size_t lightCount) {
    return [&store, &p, &predictor, width, height, target, lightCount](size_t k, const Vec3& light) {
        return obtainWithProgress(
            store, p, light, width, height, target, MeasuredErrorOfOnePrediction(predictor),
            "reference " + std::to_string(k + 1) + "/" + std::to_string(lightCount));
    };
}

ReferenceSource fixedSppSource(const Project& p, const RenderOptions& ro, size_t lightCount) {
    return [&p, ro, lightCount](size_t k, const Vec3& light) {
        ObtainedReference o;
        o.reference = renderWithProgress(p.scene, light, ro, "reference " + std::to_string(k + 1) + "/" + std::to_string(lightCount));
        o.info = {{"fixed_spp", ro.spp}, {"seed", ro.seed}};
        return o;
    };
}

std::vector<Evaluation> evaluateAll(const Project& p, const Predictor& predictor, const std::vector<Vec3>& lights,
                                    const ReferenceSource& source, const std::string& out, float exposure) {
    std::vector<Evaluation> evals;
    nlohmann::json reports = nlohmann::json::array();
    for (size_t k = 0; k < lights.size(); ++k) {
        const ObtainedReference obtained = source(k, lights[k]);
        const Reference& ref = obtained.reference;
        const std::string dir = lights.size() > 1 ? outputPath(out, "light_" + std::to_string(k)) : out;
        evals.push_back(evaluate(predictor, ref));
        const Evaluation& e = evals.back();
        nlohmann::json report = evaluationJson(p.scene, e);
        if (!obtained.info.is_null()) report["reference_source"] = obtained.info;
        report["images"] = writeEvaluationImages(dir, e, ref, exposure);
        writeFileAtomically(outputPath(dir, "evaluation.json"), report.dump(2) + "\n");
        const std::string table = evaluationTable(p.scene, e);
        writeFileAtomically(outputPath(dir, "evaluation.txt"), table);
        std::printf("\n%s", table.c_str());
        std::printf("prediction: G-buffer %.1f ms, networks %.1f ms, exact direct %.1f ms, glossy gather %.1f ms (%llu pixels); "
                    "reference %d spp, %.2f s; files in %s\n",
                    1e3 * e.gbufferSeconds, 1e3 * e.prediction.inferenceSeconds, 1e3 * e.prediction.directSeconds,
                    1e3 * e.prediction.gatherSeconds, (unsigned long long)e.prediction.pixelsGathered, e.referenceSpp,
                    e.referenceSeconds, dir.c_str());
        for (const std::string& why : e.prediction.unavailableWhy) std::printf("unavailable: %s\n", why.c_str());
        reports.push_back(report);
    }
    if (evals.size() > 1) {
        const HeldOutSummary s = summarizeHeldOut(evals, p.scene.objects.size());
        const std::string table = heldOutTable(p.scene, s);
        std::printf("\nheld-out lights: spread over %zu positions\n%s", evals.size(), table.c_str());
        writeReported(outputPath(out, "held_out.txt"), table);
        writeReported(outputPath(out, "held_out.json"),
                      nlohmann::json{{"summary", heldOutJson(p.scene, s)}, {"evaluations", reports}}.dump(2) + "\n");
    }
    return evals;
}

}  // namespace rrf::cli
