#include "core/scene/scene.h"

#include <cstring>

#include "core/util/rng.h"

namespace rrf {

Bounds3 Object::bounds() const {
    Bounds3 b;
    if (kind == Kind::Sphere) {
        b.expand(center - Vec3(radius));
        b.expand(center + Vec3(radius));
    } else {
        for (const Vec3& p : positions) b.expand(p);
    }
    return b;
}

Bounds3 Scene::bounds() const {
    Bounds3 b;
    for (const Object& o : objects) b.expand(o.bounds());
    for (const Light& l : lights) {
        Vec3 v[4];
        if (!l.isArea()) continue;
        for (int k = 0, n = l.vertices(v); k < n; ++k) b.expand(v[k]);
    }
    return b;
}

float Scene::scale() const {
    const Bounds3 b = bounds();
    if (b.empty()) return 1.f;
    const float d = length(b.extent());
    return d > 0 ? d : 1.f;
}

Vec3 Scene::lightPosition() const {
    if (movableLight < 0 || movableLight >= int(lights.size())) return Vec3(0.f);
    return lights[size_t(movableLight)].center();
}

void Scene::setLightPosition(const Vec3& p) {
    if (movableLight < 0 || movableLight >= int(lights.size())) return;
    lights[size_t(movableLight)].moveTo(p);
}

Bounds3 Scene::lightRange() const {
    if (!lightRegion.empty()) return lightRegion;
    Bounds3 r;
    r.expand(lightPosition());
    return r;
}

namespace {
/// Order-dependent 64-bit hash built from mix64 (FNV-like fold of 64-bit words).
struct Hasher {
    uint64_t h = 0x84222325CBF29CE4ULL;
    void word(uint64_t w) { h = mix64(h ^ (w + 0x9E3779B97F4A7C15ULL)); }
    void f(float v) {
        uint32_t u;
        std::memcpy(&u, &v, 4);
        word(u);
    }
    void v3(const Vec3& v) { f(v.x); f(v.y); f(v.z); }
    void str(const std::string& s) {
        word(s.size());
        for (char c : s) word(uint64_t(uint8_t(c)));
    }
};
}  // namespace

uint64_t Scene::contentHash() const {
    Hasher h;
    h.word(materials.size());
    for (const Material& m : materials) {
        h.word(uint64_t(m.type));
        h.v3(m.kd);
        h.v3(m.ks);
        h.f(m.exponent);
    }
    h.word(objects.size());
    for (const Object& o : objects) {
        h.word(uint64_t(o.kind));
        h.str(o.name);
        h.word(uint64_t(o.material));
        h.word(o.positions.size());
        for (const Vec3& p : o.positions) h.v3(p);
        h.word(o.indices.size());
        for (uint32_t i : o.indices) h.word(i);
        h.word(o.normals.size());
        for (const Vec3& n : o.normals) h.v3(n);
        h.v3(o.center);
        h.f(o.radius);
    }
    h.word(lights.size());
    for (const Light& l : lights) {
        h.word(uint64_t(l.type));
        h.v3(l.edge1);
        h.v3(l.edge2);
        h.v3(l.radiance);
        h.word(l.oneSided);
        h.v3(l.intensity);
        // The movable light's position is a free input, so it does not enter the hash.
        if (&l - lights.data() != movableLight) {
            h.v3(l.corner);
            h.v3(l.position);
        }
    }
    h.word(uint64_t(movableLight));
    h.v3(lightRegion.lo);
    h.v3(lightRegion.hi);
    return h.h;
}

}  // namespace rrf
