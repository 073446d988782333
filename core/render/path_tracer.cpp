#include "core/render/path_tracer.h"

#include "core/render/path_steps.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace rrf {

PathTracer::PathTracer(const Scene& scene, const Accel& accel, Estimator estimator, int maxDepth)
    : scene_(scene), accel_(accel), estimator_(estimator), maxDepth_(std::max(1, maxDepth)) {
    // Only NEE and naive are path tracing; BDPT and Auto resolved elsewhere would run as naive here.
    if (estimator != Estimator::NEE && estimator != Estimator::Naive)
        throw std::invalid_argument(std::string("PathTracer: estimator '") + estimatorName(estimator) +
                                    "' is not a path tracer's (nee or naive)");
    effects_ = Effects::derive(scene);
    for (const Material& m : scene.materials) brdfs_.emplace_back(m);
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        if (l.type == Light::Type::Triangle) {
            triangleLights_.push_back(int(i));
            triangleArea_ += double(l.area());
            triangleCdf_.push_back(triangleArea_);
        } else {
            (l.type == Light::Type::Rect ? rectLights_ : pointLights_).push_back(int(i));
        }
    }
    if (scene.movableLight >= 0 && scene.movableLight < int(scene.lights.size())) {
        movable_ = scene.movableLight;
        movableDefault_ = scene.lights[size_t(movable_)];
        movableShape_ = AreaLightShape(movableDefault_);
    }
    lanesPossible_ = estimator_ == Estimator::NEE && !effects_.glossy && triangleLights_.empty();
    if (lanesPossible_) Impl::buildLaneTables(*this);
    setLanes(path_lanes::bestIsa());
}

void PathTracer::setLanes(path_lanes::Isa isa) {
    if (!lanesPossible_ || !path_lanes::isaSupported(isa)) isa = path_lanes::Isa::None;
    lanes_ = isa;
    lanesKernels_ = path_lanes::kernelsOf(isa);
}

Light PathTracer::movableLightAt(const Vec3& p) const {
    Light l = movableDefault_;
    l.moveTo(p);
    return l;
}


bool PathTracer::intersect(const Ray& ray, const Light& movable, Hit& hit) const {
    const bool found = accel_.intersect(ray, hit);
    if (movable_ < 0 || !movable.isArea()) return found;
    AreaLightShape scratch;
    return withMovableLight(ray, movable, shapeOf(movable, scratch), movable_, found, hit);
}

bool PathTracer::occluded(const Ray& ray, const Light& movable) const {
    if (movable_ >= 0 && movable.isArea()) {
        AreaLightShape scratch;
        float t;
        if (intersectAreaLight(ray, movable.corner, shapeOf(movable, scratch), ray.tmax, t)) return true;
    }
    return accel_.occluded(ray);
}

void PathTracer::occludedPacket(const Ray* rays, int count, const Light& movable, bool* blocked) const {
    accel_.occludedPacket(rays, count, blocked);
    if (movable_ < 0 || !movable.isArea()) return;
    AreaLightShape scratch;
    const AreaLightShape& shape = shapeOf(movable, scratch);
    float t;
    for (int i = 0; i < count; ++i)
        if (!blocked[i] && intersectAreaLight(rays[i], movable.corner, shape, rays[i].tmax, t)) blocked[i] = true;
}


int PathTracer::materialOf(const Hit& hit) const {
    // Moving a light never changes its material, so the scene's copy answers for the movable one too.
    return hit.object >= 0 ? scene_.objects[size_t(hit.object)].material : scene_.lights[size_t(hit.light)].material;
}


Radiance PathTracer::trace(const Ray& ray, const Light& movable, Rng& rng, TraceCounters& counters) const {
    Hit hit;
    ++counters.rays;
    if (counters.rayLog) counters.rayLog->push_back(ray);
    if (!intersect(ray, movable, hit)) return {};
    return shade(hit, -ray.dir, movable, rng, counters);
}

Radiance PathTracer::shade(const Hit& hit, const Vec3& wo, const Light& movable, Rng& rng,
                           TraceCounters& counters) const {
    Impl::Vertex v;
    v.hit = hit;
    v.wo = wo;
    Impl::emissionSeen(*this, v, movable);
    if (effects_.glossy) Impl::finish<true>(*this, v, movable, rng, counters);
    else Impl::finish<false>(*this, v, movable, rng, counters);
    return v.L;
}

void PathTracer::traceBatch(const Ray* rays, Rng* rngs, int count, TraceCounters& counters, Radiance* out) const {
    if (count <= 0) return;
    if (count > Accel::kPacket) throw std::invalid_argument("PathTracer::traceBatch: more than 16 rays");
    if (effects_.glossy) Impl::traceBatch<true>(*this, rays, rngs, count, counters, out);
    else if (Impl::lanesTake(*this, movableDefault_, count, counters))
        Impl::traceLanes(*this, rays, rngs, count, counters, out);
    else Impl::traceBatch<false>(*this, rays, rngs, count, counters, out);
}

void PathTracer::shadeBatch(const Hit& hit, const Vec3& wo, const Light& movable, Rng* rngs, int count,
                            TraceCounters& counters, Radiance* out) const {
    if (count <= 0) return;
    if (count > Accel::kPacket) throw std::invalid_argument("PathTracer::shadeBatch: more than 16 paths");
    if (Impl::lanesTake(*this, movable, count, counters)) {
        Impl::shadeLanes(*this, hit, wo, movable, rngs, count, counters, out);
        return;
    }
    for (int i = 0; i < count; ++i) out[i] = shade(hit, wo, movable, rngs[i], counters);
}

template <bool kGlossy>
void PathTracer::Impl::directLightBatch(const PathTracer& t, Vertex* v, const int* live, int count,
                                        const Light& movable, Rng* rngs, TraceCounters& counters) {
    constexpr int K = Accel::kPacket;
    // The k-th samples of all paths (the same light) go together: rays towards one light.
    struct LightSample {
        Ray shadow;
        Vec3 contribution;
        bool needsRay = false, blocked = false;
    };
    thread_local std::vector<LightSample> samples;
    samples.clear();
    int first[K + 1];
    size_t slots = 0;
    for (int j = 0; j < count; ++j) {
        const int i = live[j];
        first[j] = int(samples.size());
        lightSamples<kGlossy>(t, v[i], movable, rngs[i], counters, [&](bool needsRay, const Ray& s, auto&& contribution) {
            samples.push_back({s, contribution(), needsRay, false});
        });
        slots = std::max(slots, samples.size() - size_t(first[j]));
    }
    first[count] = int(samples.size());
    Ray packet[K];
    LightSample* owner[K];
    bool blocked[K];
    int m = 0;
    auto flush = [&] {
        if (m == 1) blocked[0] = t.occluded(packet[0], movable);
        else t.occludedPacket(packet, m, movable, blocked);
        for (int k = 0; k < m; ++k) owner[k]->blocked = blocked[k];
        m = 0;
    };
    for (size_t k = 0; k < slots; ++k)
        for (int j = 0; j < count; ++j) {
            const size_t n = size_t(first[j]) + k;
            if (n >= size_t(first[j + 1]) || !samples[n].needsRay) continue;
            packet[m] = samples[n].shadow;
            owner[m] = &samples[n];
            if (++m == K) flush();
        }
    if (m > 0) flush();
    // Each path's sum in the order of its samples, as directLight() takes it.
    for (int j = 0; j < count; ++j) {
        Vec3 sum(0.f);
        for (int n = first[j]; n < first[j + 1]; ++n) {
            const LightSample& ls = samples[size_t(n)];
            if (!ls.needsRay || !ls.blocked) sum += ls.contribution;
        }
        Vertex& vi = v[live[j]];
        vi.target() += vi.beta * sum;
    }
}

template <bool kGlossy>
void PathTracer::Impl::traceBatch(const PathTracer& t, const Ray* rays, Rng* rngs, int count, TraceCounters& counters,
                                  Radiance* out) {
    constexpr int K = Accel::kPacket;
    const Light& movable = t.movableDefault_;
    const AreaLightShape& shape = t.movableShape_;
    const bool nee = t.estimator_ == Estimator::NEE;
    // The camera rays as one packet against the static scene, then the movable light as intersect()
    // adds it.
    Hit hits[K];
    bool found[K];
    counters.rays += uint64_t(count);
    if (counters.rayLog) counters.rayLog->insert(counters.rayLog->end(), rays, rays + count);
    t.accel_.intersectPacket(rays, count, hits, found);
    Vertex v[K];
    int live[K];  // the paths that go on, in batch order
    int alive = 0;
    for (int i = 0; i < count; ++i) {
        if (!withMovableLight(rays[i], movable, shape, t.movable_, found[i], hits[i])) continue;
        v[i].hit = hits[i];
        v[i].wo = -rays[i].dir;
        emissionSeen(t, v[i], movable);
        if (enter<kGlossy>(t, v[i])) live[alive++] = i;
    }
    // The paths in lockstep over their first kLockstepVertices vertices: the light samples of all
    // live vertices, then their bounce rays, each as packets (Embree traces even incoherent rays
    // faster as a packet than one by one, bench/bench_render.cpp). Deeper, Russian roulette has
    // thinned the batch and the bookkeeping of sparse packets costs more than they save, so the paths
    // go on one by one. The hits of misses are never read, so `hits` is reused.
    constexpr int kLockstepVertices = 2;
    Ray bounce[K];
    Vec3 wiLocal[K];
    int lane[K];
    while (alive > 1 && v[live[0]].depth < kLockstepVertices) {
        if (nee) directLightBatch<kGlossy>(t, v, live, alive, movable, rngs, counters);
        int m = 0;
        for (int j = 0; j < alive; ++j)
            if (bounceRay<kGlossy>(t, v[live[j]], rngs[live[j]], counters, bounce[m], wiLocal[m])) lane[m++] = live[j];
        if (m == 1) found[0] = t.accel_.intersect(bounce[0], hits[0]);
        else if (m > 1) t.accel_.intersectPacket(bounce, m, hits, found);
        alive = 0;
        for (int j = 0; j < m; ++j) {
            const int i = lane[j];
            found[j] = withMovableLight(bounce[j], movable, shape, t.movable_, found[j], hits[j]);
            if (arrive(t, v[i], movable, bounce[j], wiLocal[j], found[j], hits[j]) && enter<kGlossy>(t, v[i]))
                live[alive++] = i;
        }
    }
    // The paths left go on one by one as in shade(), from the vertex enter() has set up.
    for (int j = 0; j < alive; ++j) {
        Vertex& last = v[live[j]];
        Rng& rng = rngs[live[j]];
        if (nee) directLight<kGlossy>(t, last, movable, rng, counters);
        if (scatter<kGlossy>(t, last, movable, rng, counters)) finish<kGlossy>(t, last, movable, rng, counters);
    }
    for (int i = 0; i < count; ++i) out[i] = v[i].L;
}

}  // namespace rrf
