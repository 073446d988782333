#pragma once
/// Moving the light by dragging its handle in an image of the camera (the workbench's views): the
/// handle sits where the light's centre projects, and the pointer at image point (x, y) places the
/// light where the camera ray through that point meets a plane through the light's position at the
/// drag's start, clamped to the scene's light range (Scene::lightRange). In the plane facing the
/// camera the handle follows the pointer exactly until the range stops it; in the horizontal plane
/// the light keeps its height and the pointer moves it over the floor plan (what the Light region
/// panel's maps show).

#include "core/scene/scene.h"

namespace rrf {

/// The plane a light drag moves in.
enum class LightDragPlane {
    Facing,      ///< perpendicular to the camera's viewing direction
    Horizontal,  ///< y = the light's height at the start
};

/// Image coordinates (pixels, x right, y down, as core/scene/camera_rays.h) of world point `p` seen
/// by `camera` in an image of `width` × `height`; false when `p` is behind the camera.
bool projectToImage(const Camera& camera, int width, int height, const Vec3& p, float& x, float& y);

/// Where the light goes when the pointer is at image point (x, y): the camera ray through it meets
/// `plane` through `start` there, clamped to `range`. `start` (clamped) when the ray runs parallel
/// to the plane or meets it behind the camera.
Vec3 lightUnderPointer(const Camera& camera, int width, int height, float x, float y, const Vec3& start,
                       LightDragPlane plane, const Bounds3& range);

}  // namespace rrf
