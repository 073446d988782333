#include "core/scene/light_drag.h"

#include <algorithm>
#include <cmath>

#include "core/scene/camera_rays.h"

namespace rrf {

namespace {
Vec3 clampTo(const Vec3& p, const Bounds3& range) {
    if (range.empty()) return p;
    return Vec3(std::clamp(p.x, range.lo.x, range.hi.x), std::clamp(p.y, range.lo.y, range.hi.y),
                std::clamp(p.z, range.lo.z, range.hi.z));
}
}  // namespace

bool projectToImage(const Camera& camera, int width, int height, const Vec3& p, float& x, float& y) {
    return CameraRays(camera, width, height).project(p - camera.eye, x, y);
}

Vec3 lightUnderPointer(const Camera& camera, int width, int height, float x, float y, const Vec3& start,
                       LightDragPlane plane, const Bounds3& range) {
    const float px = std::floor(x), py = std::floor(y);
    const Ray ray = CameraRays(camera, width, height).generate(int(px), int(py), x - px, y - py);
    const Vec3 normal = plane == LightDragPlane::Horizontal ? Vec3(0.f, 1.f, 0.f) : normalize(camera.target - camera.eye);
    const float denom = dot(ray.dir, normal);
    // A ray within about half a degree of the plane meets it too far away to be a useful position.
    if (std::fabs(denom) < 1e-4f) return clampTo(start, range);
    const float t = dot(start - ray.origin, normal) / denom;
    if (!(t > 0.f) || !std::isfinite(t)) return clampTo(start, range);
    return clampTo(ray.origin + ray.dir * t, range);
}

}  // namespace rrf
