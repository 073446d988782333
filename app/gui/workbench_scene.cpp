// Workbench: scene edits. The picking BVH and object-id buffer follow the scene; the prediction
// follows the light at once and the ground truth restarts.
#include "app/gui/workbench.h"

#include "core/scene/camera_rays.h"

namespace rrf {

void Workbench::sceneChanged(bool restartRender, bool geometryChanged) {
    // Rebuilding traces a BVH and one ray per pixel on the UI thread; a drag must not pay that per frame.
    const RenderOptions o = renderOptionsFor(state_.project.scene, state_.project.render, kGuiRenderPasses);
    if (geometryChanged || !state_.pickAccel || o.width != state_.idWidth || o.height != state_.idHeight)
        rebuildPicking();
    // The prediction follows the light at once (GLSL: this frame); the ground truth restarts below.
    prediction_.refresh();
    if (!restartRender) return;
    // The old render no longer matches the scene: it restarts once it has stopped (after an edit of
    // materials or the light, once the edits rest).
    groundTruth_.restart(/*afterRest=*/!geometryChanged);
}

void Workbench::rebuildPicking() {
    state_.pickAccel.reset();
    state_.objectIds.clear();
    state_.idWidth = state_.idHeight = 0;
    if (!state_.hasProject) return;
    try {
        auto accel = std::make_shared<Accel>(state_.project.scene);
        // The object-id buffer for highlighting: one primary ray per pixel centre. For the
        // scenes this tool targets (≤ 1024² pixels) this takes milliseconds.
        const RenderOptions o = renderOptionsFor(state_.project.scene, state_.project.render, kGuiRenderPasses);
        CameraRays camera(state_.project.scene.camera, o.width, o.height);
        state_.objectIds.assign(size_t(o.width) * size_t(o.height), -1);
        for (int y = 0; y < o.height; ++y)
            for (int x = 0; x < o.width; ++x) {
                Hit hit;
                if (accel->intersect(camera.generate(x, y, 0.5f, 0.5f), hit))
                    state_.objectIds[size_t(y) * size_t(o.width) + size_t(x)] = hit.object;
            }
        state_.idWidth = o.width;
        state_.idHeight = o.height;
        state_.pickAccel = std::move(accel);
    } catch (const std::exception& e) {
        state_.log.error(std::string("building the picking BVH failed: ") + e.what());
    }
}

}  // namespace rrf
