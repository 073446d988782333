// Workbench: scene edits. The picking BVH and object-id buffer follow the geometry (built on a
// worker, app/gui/picking_controller.h); the prediction follows the light at once and the ground
// truth restarts.
#include "app/gui/workbench.h"


namespace rrf {

void Workbench::sceneChanged(bool restartRender, bool geometryChanged) {
    // The picking map follows the geometry and the view size on a worker (a drag of the light
    // costs nothing); the views keep the previous map until the new one arrives.
    picking_.sceneChanged(geometryChanged);
    // The prediction follows the light at once (GLSL: this frame); the ground truth restarts below.
    prediction_.refresh();
    if (!restartRender) return;
    // The old render no longer matches the scene: it restarts once it has stopped (after an edit of
    // materials or the light, once the edits rest).
    groundTruth_.restart(/*afterRest=*/!geometryChanged);
}

}  // namespace rrf
