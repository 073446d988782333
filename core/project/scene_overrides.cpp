#include "core/project/scene_overrides.h"

#include <algorithm>
#include <cmath>

#include "core/scene/coordinate_range.h"
#include "core/scene/radiometric_range.h"
#include "core/util/json_reader.h"

namespace rrf {

void applySceneOverrides(const SceneOverrides& o, Scene& scene, std::vector<std::string>& problems,
                         const std::string& where) {
    if (o.lightPosition) {
        const std::string at = JsonReader::child(where, "light_position");
        const Vec3 p = *o.lightPosition;
        if (scene.lights.empty()) {
            problems.push_back(at + ": the scene has no light; ignored");
        } else {
            const Vec3 c = clampToLightRegion(scene, p);
            const std::string outOfRange = lightPlacementProblem(scene.lights[size_t(scene.movableLight)], p);
            if (scene.lightRegion.empty() && !outOfRange.empty())
                problems.push_back(at + ": " + outOfRange + "; ignored");
            else if (c.x != p.x || c.y != p.y || c.z != p.z)
                problems.push_back(at + ": outside the light region; clamped into it");
            scene.setLightPosition(c);
        }
    }
    for (const auto& [name, mo] : o.materials) {
        const std::string at = JsonReader::child(JsonReader::child(where, "materials"), name);
        // Captured by name: C++17 lambdas cannot capture a structured binding (clang rejects it).
        const std::string& wanted = name;
        auto m = std::find_if(scene.materials.begin(), scene.materials.end(),
                              [&wanted](const Material& mat) { return mat.name == wanted; });
        if (m == scene.materials.end()) {
            problems.push_back(at + ": no such material in the scene; ignored");
            continue;
        }
        Material edited = *m;
        if (mo.kd) edited.kd = *mo.kd;
        if (mo.ks) edited.ks = *mo.ks;
        if (mo.exponent) edited.exponent = *mo.exponent;
        if (enforceEnergyConservation(edited, true)) problems.push_back(at + ": kd + ks exceeded 1 or left [0, 1]; ks lowered");
        if (edited.ks.x > 0.f || edited.ks.y > 0.f || edited.ks.z > 0.f) edited.type = Material::Type::Phong;
        *m = edited;
    }
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
    } else if (m.exponent > kMaxPhongExponent) {
        // Beyond it the lobe's (n+2)/(2π) takes samples out of float range (radiometric_range.h).
        m.exponent = kMaxPhongExponent;
        changed = true;
    }
    return changed;
}

Vec3 clampToLightRegion(const Scene& scene, const Vec3& p) {
    const Bounds3& b = scene.lightRegion;
    if (b.empty()) {
        // A fixed light may go anywhere rays stay valid; beyond that it stays where the scene put it.
        const bool valid = scene.lights.empty() ||
                           lightPlacementProblem(scene.lights[size_t(scene.movableLight)], p).empty();
        return valid ? p : scene.lightPosition();
    }
    return Vec3(std::clamp(p.x, b.lo.x, b.hi.x), std::clamp(p.y, b.lo.y, b.hi.y), std::clamp(p.z, b.lo.z, b.hi.z));
}

}  // namespace rrf
