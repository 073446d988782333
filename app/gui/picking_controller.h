#pragma once
/// The views' object picking as a controller: the picking BVH (hover read-out "pixel (x, y) #3
/// floor") and the object-id map, one primary ray per pixel centre (highlighting the selected
/// object, hatching objects without a network), both of the scene's geometry at the ground truth's
/// size. Building them traces a BVH and a ray per pixel: tens of milliseconds on the Cornell box and
/// far more on a large mesh, so it is done on a worker (a ReadBack job, app/gui/read_back.h) when a
/// project opens, the geometry changes or the view size does (issue 29: no UI-thread stall over
/// 100 ms at open). The result is published into state.pickAccel / objectIds / idWidth / idHeight /
/// idsRevision when it arrives; until then the views use the previous map (an edit's) or none (a
/// new project's: its first frames show no highlight and "?" as the hovered object).
/// UI thread only.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "app/gui/controller_context.h"
#include "app/gui/read_back.h"
#include "core/scene/accel.h"
#include "core/scene/scene.h"

namespace rrf {

/// A picking BVH and object-id map of one scene at one size.
struct PickingMap {
    /// Shares the scene it was built from, which its smooth meshes' normals are read from at each hit.
    std::shared_ptr<const Accel> accel;
    std::vector<int> objectIds;  ///< per pixel (top row first): the object hit, -1 background or light
    int width = 0, height = 0;
};

/// Builds the map of `scene` at width × height (a pure function of them, any thread). The map's
/// accel shares the scene (never copied again: the caller's snapshot is the copy). Stops early
/// (returning nothing) once `cancel` is set. Throws std::runtime_error when Embree fails.
std::optional<PickingMap> buildPickingMap(std::shared_ptr<const Scene> scene, int width, int height,
                                          const std::atomic<bool>* cancel = nullptr);

class PickingController {
public:
    explicit PickingController(ControllerContext& ctx);

    /// The scene changed. `geometryChanged` false means materials or the movable light only (the
    /// light is not in the BVH): the map then stays unless the view size changed. Starts a build
    /// when needed (one in flight for an older request is dropped); returns at once.
    void sceneChanged(bool geometryChanged);
    /// Each frame: publishes a map that has arrived; then tells `onPublished` (the prediction's
    /// hatching follows the new ids).
    void poll();
    /// Another project was opened: its map is cleared now (the old one is of another scene) and
    /// the build in flight forgotten.
    void drop();
    /// True while a build is in flight.
    bool pending() const { return read_.pending(); }

    /// Told after a map has been published (UI thread).
    std::function<void()> onPublished;

private:
    ControllerContext& ctx_;
    panels::WorkbenchState& state_;
    ReadBack<PickingMap> read_;
    /// What the map in state_ (or the one on its way) is of: the geometry's generation (bumped by
    /// every geometry change) and the size. A light drag then costs no build per frame.
    uint64_t geometry_ = 1;
    uint64_t builtGeometry_ = 0;
    int builtWidth_ = 0, builtHeight_ = 0;
};

}  // namespace rrf
