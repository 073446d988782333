#include "core/project/scene_overrides.h"

#include <algorithm>
#include <cmath>

#include "core/scene/coordinate_range.h"
#include "core/scene/radiometric_range.h"

namespace rrf {

using nlohmann::json;

namespace {
json vec3Json(const Vec3& v) { return json::array({v.x, v.y, v.z}); }

MaterialOverride readMaterialOverride(const JsonReader& r, std::vector<std::string>& warnings) {
    // An unknown key (a typo such as "albedo") is reported like anywhere else; the known keys still apply.
    try {
        r.checkKeys({"kd", "ks", "exponent"});
    } catch (const InputError& e) {
        if (!r.isObject()) throw;
        warnings.push_back(std::string(e.what()) + "; ignored");
    }
    MaterialOverride m;
    if (const auto kd = r.find("kd")) m.kd = kd->vec3();
    if (const auto ks = r.find("ks")) m.ks = ks->vec3();
    if (const auto ex = r.find("exponent")) m.exponent = float(ex->number(0.0, double(kMaxPhongExponent)));
    return m;
}
}  // namespace

json SceneOverrides::toJson() const {
    json o = json::object();
    if (lightPosition) o["light_position"] = vec3Json(*lightPosition);
    if (!materials.empty()) {
        json mats = json::object();
        for (const auto& [name, m] : materials) {
            json entry = json::object();
            if (m.kd) entry["kd"] = vec3Json(*m.kd);
            if (m.ks) entry["ks"] = vec3Json(*m.ks);
            if (m.exponent) entry["exponent"] = *m.exponent;
            mats[name] = entry;
        }
        o["materials"] = mats;
    }
    return o;
}

SceneOverrides SceneOverrides::fromJson(const JsonReader& section, std::vector<std::string>& warnings) {
    SceneOverrides o;
    auto lenient = [&](auto&& read) {
        try {
            read();
        } catch (const InputError& e) {
            warnings.push_back(std::string(e.what()) + "; ignored");
        }
    };
    lenient([&] { section.checkKeys({"light_position", "materials"}); });
    if (!section.isObject()) return o;
    if (const auto light = section.find("light_position")) lenient([&] { o.lightPosition = light->vec3(); });
    if (const auto mats = section.find("materials")) {
        lenient([&] { mats->requireObject(); });
        if (!mats->isObject()) return o;
        for (auto it = mats->value().begin(); it != mats->value().end(); ++it) {
            const JsonReader entry = mats->at(it.key());
            lenient([&] { o.materials[it.key()] = readMaterialOverride(entry, warnings); });
        }
    }
    return o;
}

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
