#include "core/scene/effects.h"

#include <sstream>

namespace rrf {

Effects Effects::derive(const Scene& scene) {
    Effects e;
    int reflectingSurfaces = 0;
    bool concave = false;
    auto addMaterial = [&](int index) -> bool {
        if (index < 0 || index >= int(scene.materials.size())) return false;
        const Material& m = scene.materials[size_t(index)];
        const bool glossy = m.type == Material::Type::Phong && !m.ks.isZero();
        if (!m.kd.isZero()) e.diffuse = true;
        if (glossy) {
            e.glossy = true;
            e.maxPhongExponent = std::max(e.maxPhongExponent, double(m.exponent));
        }
        const Vec3 albedo = m.kd + (glossy ? m.ks : Vec3(0.f));
        e.maxAlbedo = std::max(e.maxAlbedo, albedo.maxComponent());
        return !albedo.isZero();
    };
    for (const Object& o : scene.objects) {
        if (!addMaterial(o.material)) continue;
        // A single convex primitive cannot light itself; anything else may (meshes are concave in general).
        const size_t prims = o.primitiveCount();
        reflectingSurfaces += int(prims);
        if (o.kind != Object::Kind::Sphere && prims > 1) concave = true;
    }
    for (const Light& l : scene.lights) {
        if (l.isArea()) {
            (l.type == Light::Type::Rect ? e.rectLights : e.triangleLights) = true;
            if (addMaterial(l.material)) {
                e.reflectiveEmitters = true;
                ++reflectingSurfaces;
            }
        } else {
            e.pointLights = true;
        }
    }
    e.indirect = reflectingSurfaces >= 2 || concave;
    e.caustics = e.indirect && e.diffuse && e.glossy && e.maxPhongExponent >= kCausticExponent;
    return e;
}

std::vector<std::string> Effects::describe() const {
    std::vector<std::string> out;
    if (rectLights) out.push_back("area lights (next-event estimation, visible to rays)");
    if (triangleLights)
        out.push_back("triangle emitters (mesh lights; next-event estimation picks one triangle by area, visible to rays)");
    if (pointLights) out.push_back("point lights (next-event estimation only; the naive estimator cannot see them)");
    if (reflectiveEmitters) out.push_back("emitters that also reflect light");
    if (diffuse) out.push_back("diffuse reflection (Lambert)");
    if (glossy) {
        std::ostringstream s;
        s << "glossy reflection (Phong, exponent up to " << maxPhongExponent << ")";
        out.push_back(s.str());
    }
    if (caustics) out.push_back("caustics (glossy lobes focus the emitters' light onto diffuse surfaces)");
    if (indirect) {
        std::ostringstream s;
        s << "indirect light (multiple bounces, Russian roulette; max albedo " << maxAlbedo << ")";
        out.push_back(s.str());
    } else {
        out.push_back("no indirect light possible: bounce rays are skipped");
    }
    return out;
}

}  // namespace rrf
