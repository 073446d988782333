#include "app/cli/cli_evaluation.h"

#include "app/cli/cli_stage.h"

namespace rrf::cli {

Reference renderWithProgress(const Scene& scene, const Vec3& lp, const RenderOptions& o, const std::string& label) {
    Reference r;
    runStage(label, [&](const StageObserver& obs) { r = renderFixedReference(scene, lp, o, obs).reference; });
    return r;
}

ObtainedReference obtainWithProgress(ReferenceStore& store, const Project& p, const Vec3& lp, int width, int height,
                                     const NoiseTarget& target, const std::function<double(const Reference&)>& measuredError,
                                     const std::string& label) {
    ObtainedReference out;
    runStage(label, [&](const StageObserver& obs) { out = obtainReference(store, p, lp, width, height, target, measuredError, obs); });
    return out;
}

ReferenceSource storeSource(ReferenceStore& store, const Project& p, const Predictor& predictor, int width, int height,
                            const NoiseTarget& target, size_t lightCount) {
    return storeReferenceSource(store, p, predictor, width, height, target, lightCount, stageRunner());
}

ReferenceSource fixedSppSource(const Project& p, const RenderOptions& ro, size_t lightCount) {
    return fixedSppReferenceSource(p, ro, lightCount, stageRunner());
}

std::vector<Evaluation> evaluateAll(const Project& p, const Predictor& predictor, const std::vector<Vec3>& lights,
                                    const ReferenceSource& source, const std::string& out, float exposure) {
    return evaluateAtLights(p, predictor, lights, source, out, exposure, printingObserver());
}

LightGridOutcome lightGrid(const Project& p, const Predictor& predictor, const LightGridSpec& grid,
                           const ReferenceSource& source, const std::string& out, float exposure, const LightGridMarks& marks) {
    return evaluateLightGrid(p, predictor, grid, source, out, exposure, marks, printingObserver());
}

}  // namespace rrf::cli
