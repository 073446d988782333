#include "core/data/jitter_grid.h"

#include <vector>

namespace rrf {

Vec3 JitterGrid::viewpoint(int cell, uint64_t seed) const {
    int ix, iy, iz;
    cellCoords(cell, ix, iy, iz);
    // Domain-separated stream: viewpoints never share random numbers with records or paths.
    Rng rng(mix64(seed ^ 0x5649455750544553ULL), uint64_t(cell));
    const Vec3 e = bounds_.extent();
    const float u = rng.uniform(), v = rng.uniform(), w = rng.uniform();
    return {bounds_.lo.x + e.x * (float(ix) + u) / float(nx_), bounds_.lo.y + e.y * (float(iy) + v) / float(ny_),
            bounds_.lo.z + e.z * (float(iz) + w) / float(nz_)};
}

ViewpointStatus ViewpointClassifier::classify(const Vec3& p) const {
    // 6 axis and 8 diagonal directions, tilted by an irrational-looking rotation so that no probe
    // runs exactly along an axis-aligned wall or box edge.
    static const Vec3 kProbes[14] = {
        normalize(Vec3(1, 0.0123f, 0.0371f)),   normalize(Vec3(-1, 0.0213f, -0.0311f)),
        normalize(Vec3(0.0279f, 1, -0.0137f)),  normalize(Vec3(-0.0191f, -1, 0.0241f)),
        normalize(Vec3(0.0317f, -0.0229f, 1)),  normalize(Vec3(-0.0143f, 0.0337f, -1)),
        normalize(Vec3(1, 1.031f, 0.977f)),     normalize(Vec3(-1, 0.969f, 1.023f)),
        normalize(Vec3(1.017f, -1, 0.983f)),    normalize(Vec3(0.973f, 1.029f, -1)),
        normalize(Vec3(-1.021f, -0.981f, 1)),   normalize(Vec3(-0.987f, 1.013f, -1)),
        normalize(Vec3(1.009f, -0.991f, -1)),   normalize(Vec3(-1, -1.019f, -0.979f)),
    };
    const Scene& scene = tracer_.scene();
    const Accel& accel = tracer_.accel();
    int insideVotes = 0, escapes = 0, objectHits = 0, backHits = 0;
    std::vector<int> crossings(scene.objects.size());
    for (const Vec3& dir : kProbes) {
        std::fill(crossings.begin(), crossings.end(), 0);
        Ray ray;
        ray.origin = p;
        ray.dir = dir;
        Hit hit;
        bool first = true;
        // Walk along the probe; 256 surfaces is far more than any scene layer count.
        for (int step = 0; step < 256 && accel.intersect(ray, hit); ++step) {
            if (first && hit.object >= 0) {
                // The first surface this probe sees, and from which side (an open surface's front
                // normal is its authored orientation; closed ones are seen from outside anyway).
                ++objectHits;
                if (!scene.objects[size_t(hit.object)].closed && dot(dir, hit.ng) > 0.f) ++backHits;
            }
            first = false;
            if (hit.object >= 0 && scene.objects[size_t(hit.object)].closed) ++crossings[size_t(hit.object)];
            ray.tmin = hit.t + accel.offset(hit.p);
        }
        if (first) ++escapes;
        for (int c : crossings)
            if (c % 2 == 1) {
                ++insideVotes;
                break;
            }
    }
    if (2 * insideVotes > 14) return ViewpointStatus::InsideObject;
    if (4 * escapes > 3 * 14) return ViewpointStatus::OutsideScene;
    if (2 * backHits > objectHits) return ViewpointStatus::BehindSurface;
    return ViewpointStatus::Kept;
}

}  // namespace rrf
