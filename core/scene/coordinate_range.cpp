#include "core/scene/coordinate_range.h"

#include <cmath>
#include <sstream>

namespace rrf {

namespace {
std::string rangeText() {
    std::ostringstream s;
    s << "[-" << double(kMaxCoordinate) << ", " << double(kMaxCoordinate) << "]";
    return s.str();
}
}  // namespace

bool withinCoordinateRange(const Vec3& p) { return coordinateRangeProblem(p).empty(); }

std::string coordinateRangeProblem(const Vec3& p) {
    for (int i = 0; i < 3; ++i) {
        const double v = p[i];
        if (std::isfinite(v) && std::fabs(v) <= double(kMaxCoordinate)) continue;
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
    Vec3 corners[4];
    const int n = moved.vertices(corners);
    for (int k = 0; k < n; ++k)
        if (std::string why = coordinateRangeProblem(corners[k]); !why.empty()) return "a corner of light '" + l.name + "' has " + why;
    return "";
}

}  // namespace rrf
