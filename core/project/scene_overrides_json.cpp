// The project's "scene_overrides" section in JSON (see scene_overrides_json.h).
#include "core/project/scene_overrides_json.h"

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

json toJson(const SceneOverrides& overrides) {
    json o = json::object();
    if (overrides.lightPosition) o["light_position"] = vec3Json(*overrides.lightPosition);
    if (!overrides.materials.empty()) {
        json mats = json::object();
        for (const auto& [name, m] : overrides.materials) {
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

SceneOverrides sceneOverridesFromJson(const JsonReader& section, std::vector<std::string>& warnings) {
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

}  // namespace rrf
