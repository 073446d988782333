#include "core/data/record_layout.h"

#include <cmath>

namespace rrf {

RecordLayout RecordLayout::forScene(const Scene& scene) {
    RecordLayout l;
    // Only materials that some object uses decide the layout: a glossy material defined but unused
    // must not add four all-zero columns.
    for (const Object& o : scene.objects) {
        if (o.material < 0 || o.material >= int(scene.materials.size())) continue;
        const Material& m = scene.materials[size_t(o.material)];
        if (m.type == Material::Type::Phong && !m.ks.isZero()) l.phong = true;
    }
    l.inputs = {"hit_x",   "hit_y",   "hit_z",   "view_x",   "view_y",   "view_z",   "light_x",  "light_y",
                "light_z", "normal_x", "normal_y", "normal_z", "kd_r", "kd_g", "kd_b"};
    if (l.phong) {
        for (const char* n : {"ks_r", "ks_g", "ks_b", "log10_exponent_plus_1"}) l.inputs.push_back(n);
    }
    l.targets = {"direct_r", "direct_g", "direct_b", "indirect_r", "indirect_g", "indirect_b"};
    l.noise = noiseNames();
    return l;
}

const std::vector<std::string>& RecordLayout::noiseNames() {
    static const std::vector<std::string> names = {"direct_var_r",   "direct_var_g",   "direct_var_b",
                                                   "indirect_var_r", "indirect_var_g", "indirect_var_b"};
    return names;
}

void RecordLayout::writeInputs(const Vec3& p, const Vec3& wo, const Vec3& lightPos, const Vec3& ng,
                               const Material& m, float* out) const {
    const Vec3 n = dot(wo, ng) >= 0.f ? ng : -ng;
    const Vec3 in[4] = {p, wo, lightPos, n};
    for (int k = 0; k < 4; ++k)
        for (int c = 0; c < 3; ++c) out[3 * k + c] = in[k][c];
    brdfParameters(m, out + 12);
}

void RecordLayout::brdfParameters(const Material& m, float* out) const {
    out[0] = m.kd.x;
    out[1] = m.kd.y;
    out[2] = m.kd.z;
    if (!phong) return;
    // A Phong material without a specular lobe reflects exactly like Lambert, so it is encoded alike.
    const bool glossy = m.type == Material::Type::Phong && !m.ks.isZero();
    out[3] = glossy ? m.ks.x : 0.f;
    out[4] = glossy ? m.ks.y : 0.f;
    out[5] = glossy ? m.ks.z : 0.f;
    out[6] = glossy ? float(std::log10(1.0 + double(m.exponent))) : 0.f;
}

}  // namespace rrf
