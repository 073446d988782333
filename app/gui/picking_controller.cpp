// PickingController (picking_controller.h): the picking BVH and object-id map built on a worker.
#include "app/gui/picking_controller.h"

#include "app/gui/render_session.h"
#include "core/scene/camera_rays.h"

namespace rrf {

std::optional<PickingMap> buildPickingMap(std::shared_ptr<const Scene> scene, int width, int height,
                                          const std::atomic<bool>* cancel) {
    // The accel reads smooth meshes' normals from the scene it was built from at every hit: it
    // keeps that scene alive beside it, at an address that never moves.
    struct Owned {
        std::shared_ptr<const Scene> scene;
        std::unique_ptr<Accel> accel;
    };
    auto owned = std::make_shared<Owned>();
    owned->scene = std::move(scene);
    owned->accel = std::make_unique<Accel>(*owned->scene);
    PickingMap map;
    map.width = width;
    map.height = height;
    map.objectIds.assign(size_t(width) * size_t(height), -1);
    CameraRays camera(owned->scene->camera, width, height);
    for (int y = 0; y < height; ++y) {
        if (cancel && cancel->load(std::memory_order_relaxed)) return std::nullopt;
        for (int x = 0; x < width; ++x) {
            Hit hit;
            if (owned->accel->intersect(camera.generate(x, y, 0.5f, 0.5f), hit))
                map.objectIds[size_t(y) * size_t(width) + size_t(x)] = hit.object;
        }
    }
    map.accel = std::shared_ptr<const Accel>(owned, owned->accel.get());
    return map;
}

PickingController::PickingController(ControllerContext& ctx) : ctx_(ctx), state_(ctx.state), read_(ctx.jobs, ctx.state.log) {}

void PickingController::sceneChanged(bool geometryChanged) {
    if (!state_.hasProject) return;
    if (geometryChanged) ++geometry_;
    const Camera camera = groundTruthCamera(state_.project.scene, state_.project.render);
    if (builtGeometry_ == geometry_ && builtWidth_ == camera.width && builtHeight_ == camera.height) return;
    builtGeometry_ = geometry_;
    builtWidth_ = camera.width;
    builtHeight_ = camera.height;
    auto scene = std::make_shared<const Scene>(state_.project.scene);
    read_.start(
        "picking map",
        [scene, w = camera.width, h = camera.height](JobContext& job) -> std::optional<PickingMap> {
            try {
                return buildPickingMap(scene, w, h, &job.cancelFlag());
            } catch (const std::exception& e) {
                job.post(std::string("building the picking BVH failed: ") + e.what());
                return std::nullopt;
            }
        },
        [this](PickingMap& map) {
            state_.pickAccel = std::move(map.accel);
            state_.objectIds = std::move(map.objectIds);
            state_.idWidth = map.width;
            state_.idHeight = map.height;
            ++state_.idsRevision;
            if (onPublished) onPublished();
        });
}

void PickingController::poll() { read_.poll(); }

void PickingController::drop() {
    read_.drop();
    state_.pickAccel.reset();
    state_.objectIds.clear();
    state_.idWidth = state_.idHeight = 0;
    ++state_.idsRevision;
    builtGeometry_ = 0;
    builtWidth_ = builtHeight_ = 0;
}

}  // namespace rrf
