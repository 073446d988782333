#include "core/scene/transform.h"

#include <cmath>


namespace rrf {

Vec3 Transform::apply(const Vec3& p) const {
    const Eigen::Vector3d q = linear * Eigen::Vector3d(p.x, p.y, p.z) + translation;
    return Vec3(float(q.x()), float(q.y()), float(q.z()));
}

namespace {

Eigen::Vector3d readVector(const JsonReader& r) {
    if (!r.isArray() || r.value().size() != 3) r.fail("expected array of 3 numbers, got " + JsonReader::describe(r.value()));
    Eigen::Vector3d v;
    for (size_t i = 0; i < 3; ++i) v[Eigen::Index(i)] = r.at(i).number();
    return v;
}

Eigen::Matrix3d readRotation(const JsonReader& r) {
    r.checkKeys({"axis", "degrees"});
    const JsonReader axisReader = r.at("axis");
    const Eigen::Vector3d axis = readVector(axisReader);
    const double norm = axis.norm();
    if (!(norm > 0) || !std::isfinite(norm)) axisReader.fail("rotation axis must be a non-zero vector");
    const double degrees = r.at("degrees").number();
    // Multiples of 90 degrees are common; exact sines and cosines keep axis-aligned shapes exact
    // (cos(pi/2) evaluates to 6e-17, not 0).
    double c = 0, s = 0;
    const double quarterTurns = degrees / 90.0;
    if (quarterTurns == std::floor(quarterTurns) && std::fabs(quarterTurns) < 1e15) {
        const int k = int(((long long)quarterTurns % 4 + 4) % 4);
        const double cs[4] = {1, 0, -1, 0}, sn[4] = {0, 1, 0, -1};
        c = cs[k];
        s = sn[k];
    } else {
        const double rad = degrees * (M_PI / 180.0);
        c = std::cos(rad);
        s = std::sin(rad);
    }
    // Rodrigues' formula, right-handed about the axis.
    const Eigen::Vector3d a = axis / norm;
    Eigen::Matrix3d k;
    k << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
    return c * Eigen::Matrix3d::Identity() + s * k + (1 - c) * a * a.transpose();
}

}  // namespace

Transform parseTransform(const JsonReader& r) {
    r.checkKeys({"scale", "rotate", "translate"});
    Transform t;
    Eigen::Vector3d scale = Eigen::Vector3d::Ones();
    if (auto s = r.find("scale")) {
        if (s->value().is_number()) scale = Eigen::Vector3d::Constant(s->number());
        else if (s->isArray() && s->value().size() == 3) scale = readVector(*s);
        else s->fail("expected a number or an array of 3 numbers, got " + JsonReader::describe(s->value()));
        for (int i = 0; i < 3; ++i)
            if (scale[i] == 0) s->fail("scale factors must be non-zero (a zero scale flattens the shape)");
    }
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    if (auto rot = r.find("rotate")) {
        if (rot->isArray()) {
            // Applied in list order: the first rotation acts on the shape first.
            for (size_t i = 0; i < rot->value().size(); ++i) rotation = readRotation(rot->at(i)) * rotation;
        } else if (rot->isObject()) {
            rotation = readRotation(*rot);
        } else {
            rot->fail("expected a rotation object or an array of them, got " + JsonReader::describe(rot->value()));
        }
    }
    t.linear = rotation * scale.asDiagonal();
    if (auto tr = r.find("translate")) t.translation = readVector(*tr);
    return t;
}

}  // namespace rrf
