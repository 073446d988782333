#include "app/cli/cli_evaluation.h"

#include <atomic>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "app/cli/cli_common.h"
#include "core/eval/held_out.h"
#include "core/project/project.h"
#include "core/util/atomic_file.h"

namespace rrf::cli {

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

std::vector<Evaluation> evaluateAll(const Project& p, const Predictor& predictor, const std::vector<Vec3>& lights,
                                    const RenderOptions& ro, const Reference* given, const std::string& out, float exposure) {
    std::vector<Evaluation> evals;
    nlohmann::json reports = nlohmann::json::array();
    for (size_t k = 0; k < (given ? 1 : lights.size()); ++k) {
        const Reference ref = given ? *given
                                    : renderWithProgress(p.scene, lights[k], ro,
                                                         "reference " + std::to_string(k + 1) + "/" + std::to_string(lights.size()));
        const std::string dir = lights.size() > 1 ? outputPath(out, "light_" + std::to_string(k)) : out;
        evals.push_back(evaluate(predictor, ref));
        const Evaluation& e = evals.back();
        nlohmann::json report = evaluationJson(p.scene, e);
        report["images"] = writeEvaluationImages(dir, e, ref, exposure);
        writeFileAtomically(outputPath(dir, "evaluation.json"), report.dump(2) + "\n");
        const std::string table = evaluationTable(p.scene, e);
        writeFileAtomically(outputPath(dir, "evaluation.txt"), table);
        std::printf("\n%s", table.c_str());
        std::printf("prediction: G-buffer %.1f ms, networks %.1f ms, exact direct %.1f ms; reference %.2f s; files in %s\n",
                    1e3 * e.gbufferSeconds, 1e3 * e.prediction.inferenceSeconds, 1e3 * e.prediction.directSeconds,
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
