#include "core/render/render_settings.h"

#include <algorithm>

#include "core/render/renderer.h"
#include "core/util/error.h"
#include "core/util/memory_budget.h"

namespace rrf {

const char* estimatorName(Estimator e) {
    switch (e) {
    case Estimator::NEE: return "nee";
    case Estimator::Naive: return "naive";
    case Estimator::BDPT: return "bdpt";
    case Estimator::Auto: return "auto";
    }
    return "?";
}

std::optional<Estimator> parseEstimator(std::string_view name) {
    for (Estimator e : {Estimator::NEE, Estimator::Naive, Estimator::BDPT, Estimator::Auto})
        if (name == estimatorName(e)) return e;
    return std::nullopt;
}

const char* estimatorNames() { return "nee, naive, bdpt, auto"; }

const std::vector<std::string>& estimatorChoices() {
    static const std::vector<std::string> names = {"nee", "naive", "bdpt", "auto"};
    return names;
}

EstimatorChoice chooseEstimator(Estimator requested, const Effects& effects) {
    if (requested != Estimator::Auto)
        return {requested, std::string("requested (") + estimatorName(requested) + ")"};
    if (effects.caustics)
        return {Estimator::BDPT, "auto: glossy surfaces (Phong exponent up to " +
                                     std::to_string(int(effects.maxPhongExponent)) +
                                     ") can carry light from the emitters to diffuse surfaces (caustics), which the "
                                     "path tracer finds only by rare BRDF samples"};
    return {Estimator::NEE, effects.glossy ? "auto: glossy lobes too broad for caustics, the path tracer suffices"
                                           : "auto: no glossy surfaces, so no caustics; the path tracer suffices"};
}

uint64_t renderMemoryBytes(int width, int height) {
    const uint64_t perPixel = 2 * sizeof(PixelSums) + 2 * 6 * 3 * sizeof(float);
    return saturatingProduct(uint64_t(std::max(width, 0)), uint64_t(std::max(height, 0)), perPixel);
}

void requireRenderMemory(int width, int height) {
    const uint64_t perPixel = renderMemoryBytes(1, 1);
    const std::string why =
        memoryShortfall(renderMemoryBytes(width, height), availableMemoryBytes(),
                        std::to_string(width) + " x " + std::to_string(height) + " pixels x " + std::to_string(perPixel) +
                            " bytes of sums and images");
    if (!why.empty())
        throw SettingError("image size", "a " + std::to_string(width) + " x " + std::to_string(height) + " render " + why +
                                             "; choose a smaller width and height (each 1 ... " +
                                             std::to_string(kMaxImageSide) + ")");
}

}  // namespace rrf
