#include "core/project/scene_overrides.h"

#include <algorithm>
#include <cmath>

namespace rrf {

using nlohmann::json;

namespace {
bool readVec3(const json& j, Vec3& out) {
    if (!j.is_array() || j.size() != 3) return false;
    float v[3];
    for (int i = 0; i < 3; ++i) {
        if (!j[i].is_number()) return false;
        v[i] = j[i].get<float>();
        if (!std::isfinite(v[i])) return false;
    }
    out = Vec3(v[0], v[1], v[2]);
    return true;
}

json vec3Json(const Vec3& v) { return json::array({v.x, v.y, v.z}); }

json& overrides(Project& p) {
    if (!p.doc.is_object()) p.doc = json::object();
    json& o = p.doc["scene_overrides"];
    if (!o.is_object()) o = json::object();
    return o;
}
}  // namespace

void applySceneOverrides(Project& project, std::vector<std::string>& problems) {
    if (!project.doc.is_object() || !project.doc.contains("scene_overrides")) return;
    const json& o = project.doc["scene_overrides"];
    if (!o.is_object()) {
        problems.push_back("/scene_overrides: expected an object; ignored");
        return;
    }
    Scene& scene = project.scene;
    if (o.contains("light_position")) {
        Vec3 p;
        if (!readVec3(o["light_position"], p)) {
            problems.push_back("/scene_overrides/light_position: expected [x, y, z]; ignored");
        } else if (scene.lights.empty()) {
            problems.push_back("/scene_overrides/light_position: the scene has no light; ignored");
        } else {
            const Vec3 c = clampToLightRegion(scene, p);
            if (c.x != p.x || c.y != p.y || c.z != p.z)
                problems.push_back("/scene_overrides/light_position: outside the light region; clamped into it");
            scene.setLightPosition(c);
        }
    }
    if (o.contains("materials")) {
        const json& mats = o["materials"];
        if (!mats.is_object()) {
            problems.push_back("/scene_overrides/materials: expected an object; ignored");
            return;
        }
        for (auto it = mats.begin(); it != mats.end(); ++it) {
            const std::string where = "/scene_overrides/materials/" + it.key();
            auto m = std::find_if(scene.materials.begin(), scene.materials.end(),
                                  [&](const Material& mat) { return mat.name == it.key(); });
            if (m == scene.materials.end()) {
                problems.push_back(where + ": no such material in the scene; ignored");
                continue;
            }
            const json& v = it.value();
            Material edited = *m;
            bool ok = v.is_object();
            if (ok && v.contains("kd")) ok = readVec3(v["kd"], edited.kd);
            if (ok && v.contains("ks")) ok = readVec3(v["ks"], edited.ks);
            if (ok && v.contains("exponent")) {
                ok = v["exponent"].is_number() && std::isfinite(v["exponent"].get<double>()) &&
                     v["exponent"].get<double>() >= 0.0;
                if (ok) edited.exponent = v["exponent"].get<float>();
            }
            if (!ok) {
                problems.push_back(where + ": expected {kd: [r,g,b], ks: [r,g,b], exponent: n ≥ 0}; ignored");
                continue;
            }
            if (enforceEnergyConservation(edited, true))
                problems.push_back(where + ": kd + ks exceeded 1 or left [0, 1]; ks lowered");
            if (edited.ks.x > 0.f || edited.ks.y > 0.f || edited.ks.z > 0.f) edited.type = Material::Type::Phong;
            *m = edited;
        }
    }
}

void recordMaterialOverride(Project& project, int index) {
    if (index < 0 || index >= int(project.scene.materials.size())) return;
    const Material& m = project.scene.materials[size_t(index)];
    overrides(project)["materials"][m.name] =
        json{{"kd", vec3Json(m.kd)}, {"ks", vec3Json(m.ks)}, {"exponent", m.exponent}};
}

void recordLightOverride(Project& project) {
    if (project.scene.lights.empty()) return;
    overrides(project)["light_position"] = vec3Json(project.scene.lightPosition());
}

bool enforceEnergyConservation(Material& m, bool kdEdited) {
    bool changed = false;
    auto fix = [&](float& kd, float& ks) {
        const float kd0 = kd, ks0 = ks;
        kd = std::clamp(std::isfinite(kd) ? kd : 0.f, 0.f, 1.f);
        ks = std::clamp(std::isfinite(ks) ? ks : 0.f, 0.f, 1.f);
        if (kd + ks > 1.f) {
            if (kdEdited) ks = 1.f - kd;
            else kd = 1.f - ks;
        }
        changed |= kd != kd0 || ks != ks0;
    };
    fix(m.kd.x, m.ks.x);
    fix(m.kd.y, m.ks.y);
    fix(m.kd.z, m.ks.z);
    if (!std::isfinite(m.exponent) || m.exponent < 0.f) {
        m.exponent = 1.f;
        changed = true;
    }
    return changed;
}

Vec3 clampToLightRegion(const Scene& scene, const Vec3& p) {
    const Bounds3& b = scene.lightRegion;
    if (b.empty()) return p;
    return Vec3(std::clamp(p.x, b.lo.x, b.hi.x), std::clamp(p.y, b.lo.y, b.hi.y), std::clamp(p.z, b.lo.z, b.hi.z));
}

}  // namespace rrf
