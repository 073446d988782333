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
    if (lanesPossible_) {
        auto put = [](float* out, const Vec3& v) {
            out[0] = v.x;
            out[1] = v.y;
            out[2] = v.z;
        };
        for (int li : rectLights_) {
            const Light& l = light(li, movableDefault_);
            path_lanes::RectLight r{};
            put(r.corner, l.corner);
            put(r.edge1, l.edge1);
            put(r.edge2, l.edge2);
            put(r.nl, cross(l.edge1, l.edge2));
            put(r.radiance, l.radiance);
            r.oneSided = l.oneSided ? 1 : 0;
            laneRects_.push_back(r);
        }
        for (int li : pointLights_) {
            const Light& l = light(li, movableDefault_);
            path_lanes::PointLight pl{};
            put(pl.position, l.position);
            put(pl.intensity, l.intensity);
            lanePoints_.push_back(pl);
        }
        put(laneMovable_.corner, movableDefault_.corner);
        put(laneMovable_.edge1, movableShape_.edge1);
        put(laneMovable_.edge2, movableShape_.edge2);
        put(laneMovable_.n, movableShape_.n);
        laneMovable_.nn = movableShape_.nn;
        laneMovable_.triangle = movableShape_.triangle ? 1 : 0;
        if (movable_ >= 0) {
            put(laneMovable_.normal, movableDefault_.normal());
            laneMovable_.material = movableDefault_.material;
        }
        put(laneMovable_.radiance, movableDefault_.radiance);
        laneMovable_.oneSided = movableDefault_.oneSided ? 1 : 0;
        for (const Brdf& b : brdfs_) laneKd_.insert(laneKd_.end(), {b.kd.x, b.kd.y, b.kd.z});
        for (const Light& l : scene_.lights) {
            const Vec3 nl = cross(l.edge1, l.edge2);
            laneLightRadiance_.insert(laneLightRadiance_.end(), {l.radiance.x, l.radiance.y, l.radiance.z});
            laneLightNormal_.insert(laneLightNormal_.end(), {nl.x, nl.y, nl.z});
            laneLightOneSided_.push_back(l.oneSided ? 1 : 0);
        }
        const Accel::GeometryTable& g = accel_.geometryTable();
        for (size_t i = 0; i < g.object.size(); ++i)
            laneGeomMaterial_.push_back(g.object[i] >= 0 ? scene_.objects[size_t(g.object[i])].material
                                                         : scene_.lights[size_t(g.light[i])].material);
    }
    setLanes(path_lanes::bestIsa());
}

void PathTracer::setLanes(path_lanes::Isa isa) {
    if (!lanesPossible_ || !path_lanes::isaSupported(isa)) isa = path_lanes::Isa::None;
    lanes_ = isa;
    laneStep_ = path_lanes::stepOf(isa);
    laneStart_ = path_lanes::startOf(isa);
}

namespace path_lanes {
const char* isaName(Isa isa) {
    switch (isa) {
        case Isa::Avx2: return "AVX2 lanes";
        case Isa::Avx512: return "AVX-512 lanes";
        case Isa::None: break;
    }
    return "portable";
}

bool isaSupported(Isa isa) {
#ifdef RRF_PATH_LANES
    // __builtin_cpu_supports checks the OS's XSAVE state too.
    switch (isa) {
        case Isa::Avx2: return __builtin_cpu_supports("avx2");
        case Isa::Avx512: return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq");
        case Isa::None: return true;
    }
    return false;
#else
    return isa == Isa::None;
#endif
}

Isa bestIsa() {
    if (isaSupported(Isa::Avx512)) return Isa::Avx512;
    if (isaSupported(Isa::Avx2)) return Isa::Avx2;
    return Isa::None;
}

StepFunction stepOf(Isa isa) {
#ifdef RRF_PATH_LANES
    if (isa == Isa::Avx512) return &avx512::step;
    if (isa == Isa::Avx2) return &avx2::step;
#endif
    (void)isa;
    return nullptr;
}

StepFunction startOf(Isa isa) {
#ifdef RRF_PATH_LANES
    if (isa == Isa::Avx512) return &avx512::start;
    if (isa == Isa::Avx2) return &avx2::start;
#endif
    (void)isa;
    return nullptr;
}
}  // namespace path_lanes

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
#ifdef RRF_PATH_LANES
    else if (laneStep_ && !counters.rayLog && !counters.shadowRayLog) Impl::traceLanes(*this, rays, rngs, count, counters, out);
#endif
    else Impl::traceBatch<false>(*this, rays, rngs, count, counters, out);
}

#ifdef RRF_PATH_LANES
void PathTracer::Impl::traceLanes(const PathTracer& t, const Ray* rays, Rng* rngs, int count, TraceCounters& counters,
                                  Radiance* out) {
    using namespace path_lanes;
    constexpr int K = Accel::kPacket;
    const Light& movable = t.movableDefault_;
    const AreaLightShape& shape = t.movableShape_;
    Vertex v[K];
    alignas(64) PathLanes lanes;
    alignas(64) Step step;
    // A lane's state at the vertex enter() has set up in v[i].
    auto load = [&](int i) {
        const Vertex& vi = v[i];
        lanes.p.x[i] = vi.hit.p.x, lanes.p.y[i] = vi.hit.p.y, lanes.p.z[i] = vi.hit.p.z;
        lanes.ng.x[i] = vi.hit.ng.x, lanes.ng.y[i] = vi.hit.ng.y, lanes.ng.z[i] = vi.hit.ng.z;
        lanes.n.x[i] = vi.n.x, lanes.n.y[i] = vi.n.y, lanes.n.z[i] = vi.n.z;
        lanes.kd.x[i] = vi.brdf->kd.x, lanes.kd.y[i] = vi.brdf->kd.y, lanes.kd.z[i] = vi.brdf->kd.z;
        lanes.side[i] = vi.side;
        lanes.smooth = (lanes.smooth & ~(1u << i)) | (vi.hit.ns.isZero() ? 0u : 1u << i);
        lanes.live |= 1u << i;
    };
    // The vertex lane i arrived at along ray r, traced in step.next, as intersect() and arrive() give
    // it (depth: the vertex's); true when enter() lets the path go on there.
    auto arriveAlone = [&](int i, int depth, const Ray& r) {
        Hit next;
        const bool hit = withMovableLight(r, movable, shape, t.movable_, t.accel_.hitOfPacket(step.next, i, next), next);
        if (depth == 0) {
            if (!hit) return false;
            v[i].hit = next;
            v[i].wo = -r.dir;
            emissionSeen(t, v[i], movable);
        } else {
            v[i].depth = depth - 1;
            if (!arrive(t, v[i], movable, r, Vec3(), hit, next)) return false;
        }
        return enter<false>(t, v[i]);
    };
    // Lane i's bounce ray in step.next (from 0 to infinity).
    auto bounceRay = [&](int i) {
        Ray r;
        r.origin = Vec3(step.next.ray.org_x[i], step.next.ray.org_y[i], step.next.ray.org_z[i]);
        r.dir = Vec3(step.next.ray.dir_x[i], step.next.ray.dir_y[i], step.next.ray.dir_z[i]);
        return r;
    };
    for (int i = 0; i < K; ++i) {
        lanes.beta.x[i] = lanes.beta.y[i] = lanes.beta.z[i] = 1.f;
        lanes.direct.x[i] = lanes.direct.y[i] = lanes.direct.z[i] = 0.f;
        lanes.indirect.x[i] = lanes.indirect.y[i] = lanes.indirect.z[i] = 0.f;
        lanes.rng[i] = i < count ? rngs[i].state() : 0;
    }
    RTCIntersectContext bounceContext, cameraContext;
    rtcInitIntersectContext(&bounceContext);
    bounceContext.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    rtcInitIntersectContext(&cameraContext);
    cameraContext.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    const Accel::GeometryTable& geometry = t.accel_.geometryTable();
    Setup setup{t.accel_.handle(),
                &bounceContext,
                t.accel_.sceneScale(),
                t.laneRects_.data(),
                int(t.laneRects_.size()),
                t.lanePoints_.data(),
                int(t.lanePoints_.size()),
                t.movable_ >= 0 && movable.isArea() ? &t.laneMovable_ : nullptr,
                0,
                t.laneGeomMaterial_.data(),
                geometry.normalBase.data(),
                geometry.normals.data(),
                t.laneKd_.data(),
                geometry.light.data(),
                t.laneLightRadiance_.data(),
                t.laneLightNormal_.data(),
                t.laneLightOneSided_.data(),
                &cameraContext};

    // The camera rays as one packet, coherent when they share their origin (Accel::intersectPacket).
    counters.rays += uint64_t(count);
    for (int i = 0; i < K; ++i) {
        const Ray& r = rays[i < count ? i : 0];  // lanes past count repeat ray 0, masked off
        step.next.ray.org_x[i] = r.origin.x, step.next.ray.org_y[i] = r.origin.y, step.next.ray.org_z[i] = r.origin.z;
        step.next.ray.dir_x[i] = r.dir.x, step.next.ray.dir_y[i] = r.dir.y, step.next.ray.dir_z[i] = r.dir.z;
        step.next.ray.tnear[i] = r.tmin;
        step.next.ray.tfar[i] = r.tmax;
        step.next.ray.time[i] = 0.f;
        step.next.ray.mask[i] = 0xFFFFFFFFu;
        step.next.ray.id[i] = unsigned(i);
        step.next.ray.flags[i] = 0;
        if (i < count && !(r.origin == rays[0].origin)) cameraContext.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    }
    lanes.live = (1u << count) - 1u;
    t.laneStart_(setup, lanes, step);
    uint32_t setUp = 0;  // the live lanes whose v[i] holds their vertex, set up by enter()
    for (uint32_t b = step.resolve; b; b &= b - 1) {
        const int i = __builtin_ctz(b);
        const bool goesOn = arriveAlone(i, 0, rays[i]);
        lanes.direct.x[i] = v[i].L.direct.x, lanes.direct.y[i] = v[i].L.direct.y, lanes.direct.z[i] = v[i].L.direct.z;
        if (goesOn) {
            load(i);
            setUp |= 1u << i;
        }
    }

    // Deeper than the portable lockstep: a lane's step costs little, and Russian roulette thins the
    // packets only slowly over the first vertices; sparser still, they cost Embree more than they
    // save (docs/results-history.md, "The tracer's lanes").
    constexpr int kLockstepVertices = 4;
    while (lanes.live && lanes.depth < kLockstepVertices) {
        setup.bounces = lanes.depth + 1 < t.maxDepth_ && t.effects_.indirect;
        t.laneStep_(setup, lanes, step);
        counters.shadowRays += step.shadowRays;
        counters.rays += uint64_t(__builtin_popcount(step.bounced));
        ++lanes.depth;
        setUp = 0;
        for (uint32_t b = step.resolve; b; b &= b - 1) {
            const int i = __builtin_ctz(b);
            if (arriveAlone(i, lanes.depth, bounceRay(i))) {
                load(i);
                setUp |= 1u << i;
            }
        }
    }
    for (int i = 0; i < count; ++i) {
        Vertex& vi = v[i];
        vi.L.direct = Vec3(lanes.direct.x[i], lanes.direct.y[i], lanes.direct.z[i]);
        vi.L.indirect = Vec3(lanes.indirect.x[i], lanes.indirect.y[i], lanes.indirect.z[i]);
        Rng& rng = rngs[i] = Rng::ofState(lanes.rng[i]);
        if ((lanes.live >> i) & 1u) {
            // The lanes set up this vertex themselves: intersect()'s Hit for the ray that got there.
            if (!((setUp >> i) & 1u) && !arriveAlone(i, lanes.depth, bounceRay(i))) {
                out[i] = vi.L;
                continue;
            }
            // The path goes on one by one as in shade(), from the vertex enter() has set up.
            vi.beta = Vec3(lanes.beta.x[i], lanes.beta.y[i], lanes.beta.z[i]);
            directLight<false>(t, vi, movable, rng, counters);
            if (scatter<false>(t, vi, movable, rng, counters)) finish<false>(t, vi, movable, rng, counters);
        }
        out[i] = vi.L;
    }
}
#endif

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
