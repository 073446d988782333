#include "core/scene/scene_summary_json.h"

namespace rrf {

namespace {
nlohmann::json arr(const Vec3& v) { return {v.x, v.y, v.z}; }

nlohmann::json materialJson(const Scene& scene, int index) {
    if (index < 0 || index >= int(scene.materials.size())) return nullptr;
    const Material& m = scene.materials[size_t(index)];
    nlohmann::json j = {{"name", m.name}, {"type", m.type == Material::Type::Phong ? "phong" : "lambert"}, {"kd", arr(m.kd)}};
    if (m.type == Material::Type::Phong) {
        j["ks"] = arr(m.ks);
        j["exponent"] = m.exponent;
    }
    return j;
}
}  // namespace

nlohmann::json sceneSummaryJson(const Scene& scene) {
    nlohmann::json objects = nlohmann::json::array(), lights = nlohmann::json::array();
    for (const Object& o : scene.objects)
        objects.push_back({{"name", o.name},
                           {"id", o.id},
                           {"kind", objectKindName(o.kind)},
                           {"primitives", o.primitiveCount()},
                           {"smooth_normals", !o.normals.empty()},
                           {"material", materialJson(scene, o.material)}});
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        nlohmann::json j = {{"name", l.name}, {"type", lightTypeName(l.type)}, {"center", arr(l.center())},
                            {"movable", int(i) == scene.movableLight}};
        if (l.isArea()) {
            j["radiance"] = arr(l.radiance);
            j["area"] = l.area();
            j["one_sided"] = l.oneSided;
            if (l.material >= 0) j["material"] = materialJson(scene, l.material);
        } else {
            j["intensity"] = arr(l.intensity);
        }
        lights.push_back(j);
    }
    nlohmann::json region = nullptr;
    if (!scene.lightRegion.empty()) region = {{"min", arr(scene.lightRegion.lo)}, {"max", arr(scene.lightRegion.hi)}};
    return {{"objects", objects}, {"lights", lights}, {"light_region", region}};
}

}  // namespace rrf
