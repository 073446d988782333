#include "core/render/render_metadata_json.h"

#include "core/scene/effects_json.h"
#include "core/scene/scene_summary_json.h"
#include "core/util/text_format.h"

namespace rrf {

nlohmann::json renderMetadata(const Scene& scene, const Renderer& renderer, const RenderSnapshot& snapshot,
                              const RenderStats* stats) {
    const RenderOptions& o = renderer.options();
    const RenderStats st = stats ? *stats : renderer.stats();
    const Vec3 lp = scene.lightPosition();
    return {
        {"scene", scene.sourcePath},
        {"scene_hash", hexString(scene.contentHash())},
        {"width", o.width},
        {"height", o.height},
        {"spp_requested", o.spp},
        {"spp_completed", snapshot.sppCompleted},
        {"complete", snapshot.sppCompleted >= o.spp},
        {"estimator", estimatorName(renderer.estimatorChoice().estimator)},
        {"estimator_reason", renderer.estimatorChoice().reason},
        {"seed", o.seed},
        {"max_depth", o.maxDepth},
        {"light_position", {lp.x, lp.y, lp.z}},
        {"effects", toJson(renderer.tracer().effects())},
        {"scene_contents", sceneSummaryJson(scene)},
        {"seconds", st.seconds},
        {"samples", st.samples},
        {"rays", st.rays},
        {"shadow_rays", st.shadowRays},
        {"samples_per_second", st.samplesPerSecond()},
        {"rays_per_second", st.raysPerSecond()},
        {"non_finite_samples_dropped", st.nonFinite},
        {"relative_error_of_mean", snapshot.relativeError},
        {"mean_global", {snapshot.global.mean().x, snapshot.global.mean().y, snapshot.global.mean().z}},
    };
}

std::string renderMetadataText(const Scene& scene, const Renderer& renderer, const RenderSnapshot& snapshot,
                               const RenderStats* stats, const VarianceImageNames* varianceImages) {
    nlohmann::json meta = renderMetadata(scene, renderer, snapshot, stats);
    if (varianceImages) meta["variance_images"] = *varianceImages;
    return meta.dump(2) + "\n";
}

}  // namespace rrf
