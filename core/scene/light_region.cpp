#include "core/scene/light_region.h"

#include <algorithm>
#include <cmath>

namespace rrf {

namespace {
/// Fraction of the room's extent along the emitter's normal that the light may travel.
constexpr float kNormalTravel = 0.25f;
/// How far the light may travel across its normal, in emitter half-sizes.
constexpr float kAcrossTravel = 2.f;
}  // namespace

Bounds3 deriveLightRegion(const Scene& scene, int lightIndex) {
    if (lightIndex < 0 || lightIndex >= int(scene.lights.size())) return {};
    const Light& l = scene.lights[size_t(lightIndex)];
    // The room: objects and area lights (an OBJ's lamp is often the highest thing in it).
    const Bounds3 room = scene.bounds();
    if (!l.isArea() || scene.objects.empty()) return {};
    Vec3 v[4];
    Bounds3 emitter;
    for (int k = 0, n = l.vertices(v); k < n; ++k) emitter.expand(v[k]);
    const Vec3 c = l.center(), half = emitter.extent() * 0.5f, n = l.normal();
    // A one-sided light lights the side of its normal; a two-sided one moves towards the room's centre.
    const Vec3 into = l.oneSided ? n : (dot(room.center() - c, n) >= 0.f ? n : -n);
    const Vec3 ext = room.extent();
    const float depth = kNormalTravel * (std::fabs(into.x) * ext.x + std::fabs(into.y) * ext.y + std::fabs(into.z) * ext.z);
    Bounds3 r;
    r.expand(c);
    r.expand(c + into * depth);
    for (int i = 0; i < 3; ++i) {
        // Across the normal (components of `into` small on this axis): the emitter's own extent.
        const float across = (1.f - std::fabs(into[i])) * kAcrossTravel * half[i];
        r.lo[i] -= across;
        r.hi[i] += across;
        // Keep the moved emitter inside the room; keep the current centre in the region.
        r.lo[i] = std::max(r.lo[i], room.lo[i] + half[i]);
        r.hi[i] = std::min(r.hi[i], room.hi[i] - half[i]);
        r.lo[i] = std::min(r.lo[i], c[i]);
        r.hi[i] = std::max(r.hi[i], c[i]);
    }
    return r;
}

}  // namespace rrf
