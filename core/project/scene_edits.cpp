#include "core/project/scene_edits.h"

namespace rrf {

Vec3 moveLight(Project& project, const Vec3& position) {
    Scene& scene = project.scene;
    if (scene.lights.empty()) return position;
    const Vec3 p = clampToLightRegion(scene, position);
    scene.setLightPosition(p);
    project.overrides.lightPosition = scene.lightPosition();
    return p;
}

bool editMaterial(Project& project, int index, Material edited, bool kdEdited) {
    Scene& scene = project.scene;
    if (index < 0 || index >= int(scene.materials.size())) return false;
    const bool limited = enforceEnergyConservation(edited, kdEdited);
    if (edited.ks.x > 0.f || edited.ks.y > 0.f || edited.ks.z > 0.f) edited.type = Material::Type::Phong;
    Material& m = scene.materials[size_t(index)];
    m = edited;
    project.overrides.materials[m.name] = MaterialOverride{m.kd, m.ks, m.exponent};
    return limited;
}

}  // namespace rrf
