#include "core/scene/scene_summary.h"

#include <sstream>

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

const char* objectKindName(Object::Kind k) {
    switch (k) {
        case Object::Kind::Quads: return "quads";
        case Object::Kind::Triangles: return "triangles";
        case Object::Kind::Sphere: return "sphere";
    }
    return "?";
}

const char* lightTypeName(Light::Type type) {
    switch (type) {
        case Light::Type::Rect: return "rect";
        case Light::Type::Triangle: return "triangle";
        case Light::Type::Point: return "point";
    }
    return "?";
}

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

std::string formatSceneSummary(const Scene& scene) {
    std::ostringstream s;
    s << "scene: " << (scene.sourcePath.empty() ? "(built in code)" : scene.sourcePath) << "\n";
    s << scene.objects.size() << " objects:\n";
    for (const Object& o : scene.objects) {
        s << "  " << o.id << " " << o.name << ": " << o.primitiveCount() << " " << objectKindName(o.kind)
          << (o.normals.empty() ? "" : " (smooth normals)") << ", material ";
        if (o.material >= 0 && o.material < int(scene.materials.size())) {
            const Material& m = scene.materials[size_t(o.material)];
            s << m.name << " (";
            if (m.type == Material::Type::Phong)
                s << "Phong kd " << m.kd << " ks " << m.ks << " exponent " << m.exponent;
            else
                s << "Lambert albedo " << m.kd;
            s << ")";
        } else {
            s << "?";
        }
        s << "\n";
    }
    s << scene.lights.size() << " lights:\n";
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        s << "  " << l.name << ": " << lightTypeName(l.type);
        if (l.isArea()) s << ", area " << l.area() << ", radiance " << l.radiance << (l.oneSided ? "" : ", two-sided");
        else s << ", intensity " << l.intensity;
        s << ", centre " << l.center() << (int(i) == scene.movableLight ? ", movable" : "") << "\n";
    }
    if (scene.lightRegion.empty()) s << "light region: none (the light does not move)\n";
    else s << "light region: " << scene.lightRegion.lo << " .. " << scene.lightRegion.hi << "\n";
    for (const std::string& w : scene.warnings) s << "warning: " << w << "\n";
    return s.str();
}

}  // namespace rrf
