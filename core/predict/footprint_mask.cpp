#include "core/predict/footprint_mask.h"

#include <cmath>
#include <cstdio>

namespace rrf {

namespace {
/// The first reason (in the order of the header) why object pixel (x, y) is left out, or Kept.
Footprint judge(const GBuffer& g, int x, int y, float cosNormal) {
    const size_t i = size_t(y) * size_t(g.width) + size_t(x);
    const int32_t id = g.object[i];
    const Vec3 n = g.normal[i];
    const Vec3 p = g.position(i);
    const float stepTolerance = float(kFootprintDepthFraction) * g.distance[i];
    const int x0 = x > 0 ? x - 1 : x, x1 = x + 1 < g.width ? x + 1 : x;
    const int y0 = y > 0 ? y - 1 : y, y1 = y + 1 < g.height ? y + 1 : y;
    // One pass per reason keeps the priority independent of where in the neighbourhood it occurs.
    auto any = [&](auto&& test) {
        for (int ny = y0; ny <= y1; ++ny)
            for (int nx = x0; nx <= x1; ++nx)
                if (test(size_t(ny) * size_t(g.width) + size_t(nx))) return true;
        return false;
    };
    if (any([&](size_t j) { return g.light[j] >= 0; })) return Footprint::NextToLight;
    if (any([&](size_t j) { return g.object[j] != id; })) return Footprint::ObjectEdge;
    if (any([&](size_t j) { return dot(g.normal[j], n) < cosNormal; })) return Footprint::NormalEdge;
    if (any([&](size_t j) { return std::fabs(dot(n, g.position(j) - p)) > stepTolerance; })) return Footprint::DepthStep;
    return Footprint::Kept;
}
}  // namespace

FootprintMask footprintMask(const GBuffer& g) {
    FootprintMask m;
    m.width = g.width;
    m.height = g.height;
    m.pixel.assign(g.pixelCount(), Footprint::Background);
    m.keptByObject.assign(g.pixelsByObject.size(), {});
    const float cosNormal = float(std::cos(kFootprintNormalDegrees * double(kPi) / 180.0));
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
            const size_t i = size_t(y) * size_t(g.width) + size_t(x);
            Footprint& f = m.pixel[i];
            if (g.light[i] >= 0) {
                f = Footprint::Emitter;
                ++m.counts.emitterPixels;
                continue;
            }
            if (g.object[i] < 0) continue;  // background
            f = judge(g, x, y, cosNormal);
            switch (f) {
                case Footprint::Kept:
                    m.keptByObject[size_t(g.object[i])].push_back(uint32_t(i));
                    m.kept.push_back(uint32_t(i));
                    break;
                case Footprint::NextToLight: ++m.counts.nextToLight; break;
                case Footprint::ObjectEdge: ++m.counts.objectEdge; break;
                case Footprint::NormalEdge: ++m.counts.normalEdge; break;
                case Footprint::DepthStep: ++m.counts.depthStep; break;
                case Footprint::Background:
                case Footprint::Emitter: break;  // not produced by judge()
            }
        }
    return m;
}

const char* footprintName(Footprint f) {
    switch (f) {
        case Footprint::Kept: return "kept";
        case Footprint::Background: return "background";
        case Footprint::Emitter: return "emitter";
        case Footprint::NextToLight: return "next_to_light";
        case Footprint::ObjectEdge: return "object_edge";
        case Footprint::NormalEdge: return "normal_edge";
        case Footprint::DepthStep: return "depth_step";
    }
    return "?";
}

std::string FootprintCounts::describe() const {
    char line[320];
    std::snprintf(line, sizeof line,
                  "%llu object pixels left out (footprint may cover more than one surface): %llu next to the "
                  "light, %llu at object edges, %llu at normal edges (> %g deg), %llu at depth steps (> %g %% of "
                  "distance)",
                  (unsigned long long)total(), (unsigned long long)nextToLight, (unsigned long long)objectEdge,
                  (unsigned long long)normalEdge, kFootprintNormalDegrees, (unsigned long long)depthStep,
                  100.0 * kFootprintDepthFraction);
    return line;
}

}  // namespace rrf
