#include "core/scene/coordinate_range.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace rrf {

namespace {
std::string rangeText() {
    std::ostringstream s;
    s << "[-" << kMaxCoordinate << ", " << kMaxCoordinate << "]";
    return s.str();
}
}  // namespace

bool withinCoordinateRange(const Vec3& p) { return coordinateRangeProblem(p).empty(); }

std::string coordinateRangeProblem(const Vec3& p) {
    for (int i = 0; i < 3; ++i) {
        const double v = p[i];
        if (std::isfinite(v) && std::fabs(v) <= kMaxCoordinate) continue;
        std::ostringstream s;
        s << "xyz"[i] << " = " << v << " is outside " << rangeText() << ", the coordinate range in which rays stay valid";
        return s.str();
    }
    return "";
}

std::string lightPlacementProblem(const Light& l, const Vec3& centre) {
    Light moved = l;
    moved.moveTo(centre);
    if (moved.type == Light::Type::Point) return coordinateRangeProblem(moved.position);
    const Vec3 corners[4] = {moved.corner, moved.corner + moved.edge1, moved.corner + moved.edge2,
                             moved.corner + moved.edge1 + moved.edge2};
    for (const Vec3& c : corners)
        if (std::string why = coordinateRangeProblem(c); !why.empty()) return "a corner of light '" + l.name + "' has " + why;
    return "";
}

Vec3 clampToCoordinateRange(const Vec3& p) {
    const float m = float(kMaxCoordinate);
    auto clamp = [m](float v) { return std::isnan(v) ? 0.f : std::clamp(v, -m, m); };
    return Vec3(clamp(p.x), clamp(p.y), clamp(p.z));
}

}  // namespace rrf
