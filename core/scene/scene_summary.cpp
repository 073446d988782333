#include "core/scene/scene_summary.h"

#include <sstream>

namespace rrf {

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
