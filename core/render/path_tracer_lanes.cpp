// PathTracer's batches in SIMD lanes (render/path_lanes.h; docs/design.md §5, "The tracer's lanes"):
// the tables the lanes read, and a batch of paths from the camera (traceBatch) or from one vertex
// (shadeBatch: a training record's paths) through the lanes' lockstep and then one by one.
#include "core/render/path_tracer.h"

#include "core/render/path_steps.h"

#include <vector>

namespace rrf {

namespace {
void put(float* out, const Vec3& v) {
    out[0] = v.x;
    out[1] = v.y;
    out[2] = v.z;
}
}  // namespace

void PathTracer::Impl::buildLaneTables(PathTracer& t) {
    for (int li : t.rectLights_) {
        const Light& l = t.light(li, t.movableDefault_);
        path_lanes::RectLight r{};
        put(r.corner, l.corner);
        put(r.edge1, l.edge1);
        put(r.edge2, l.edge2);
        put(r.nl, cross(l.edge1, l.edge2));
        put(r.radiance, l.radiance);
        r.oneSided = l.oneSided ? 1 : 0;
        if (li == t.movable_) t.laneTables_.movableRect = int(t.laneTables_.rects.size());
        t.laneTables_.rects.push_back(r);
    }
    for (int li : t.pointLights_) {
        const Light& l = t.light(li, t.movableDefault_);
        path_lanes::PointLight pl{};
        put(pl.position, l.position);
        put(pl.intensity, l.intensity);
        t.laneTables_.points.push_back(pl);
    }
    put(t.laneTables_.movable.corner, t.movableDefault_.corner);
    put(t.laneTables_.movable.edge1, t.movableShape_.edge1);
    put(t.laneTables_.movable.edge2, t.movableShape_.edge2);
    put(t.laneTables_.movable.n, t.movableShape_.n);
    t.laneTables_.movable.nn = t.movableShape_.nn;
    if (t.movable_ >= 0) {
        put(t.laneTables_.movable.normal, t.movableDefault_.normal());
        t.laneTables_.movable.material = t.movableDefault_.material;
    }
    put(t.laneTables_.movable.radiance, t.movableDefault_.radiance);
    t.laneTables_.movable.oneSided = t.movableDefault_.oneSided ? 1 : 0;
    for (const Brdf& b : t.brdfs_) t.laneTables_.kd.insert(t.laneTables_.kd.end(), {b.kd.x, b.kd.y, b.kd.z});
    for (const Light& l : t.scene_.lights) {
        const Vec3 nl = cross(l.edge1, l.edge2);
        t.laneTables_.lightRadiance.insert(t.laneTables_.lightRadiance.end(), {l.radiance.x, l.radiance.y, l.radiance.z});
        t.laneTables_.lightNormal.insert(t.laneTables_.lightNormal.end(), {nl.x, nl.y, nl.z});
        t.laneTables_.lightOneSided.push_back(l.oneSided ? 1 : 0);
    }
    const Accel::GeometryTable& g = t.accel_.geometryTable();
    for (size_t i = 0; i < g.object.size(); ++i)
        t.laneTables_.geomMaterial.push_back(g.object[i] >= 0 ? t.scene_.objects[size_t(g.object[i])].material
                                                       : t.scene_.lights[size_t(g.light[i])].material);
}

bool PathTracer::Impl::lanesTake(const PathTracer& t, const Light& movable, int count, const TraceCounters& counters) {
    if (!t.lanesKernels_.step || count < kMinLanePaths || counters.rayLog || counters.shadowRayLog) return false;
    // The lanes hold the movable light's shape, emission and material, and take a rect's new corner
    // (LaneBatch); a point light moved elsewhere goes one path at a time.
    const Light& d = t.movableDefault_;
    if (t.movable_ < 0 || &movable == &d) return true;
    if (movable.type != d.type || (movable.type == Light::Type::Point && !(movable.position == d.position))) return false;
    return t.movableShape_.isShapeOf(movable) && movable.radiance == d.radiance && movable.intensity == d.intensity &&
           movable.oneSided == d.oneSided && movable.material == d.material;
}

/// Up to 16 paths in the lanes: their vertices for the code that runs one path at a time, the
/// lanes' state, the packet of the last step and what the lanes read, with the movable light
/// where this batch has it.
struct PathTracer::Impl::LaneBatch {
    static constexpr int K = Accel::kPacket;
    const PathTracer& t;
    const Light& movable;
    AreaLightShape scratch;
    const AreaLightShape& shape;
    Rng* rngs;
    int count;
    TraceCounters& counters;
    Vertex v[K];
    alignas(64) path_lanes::PathLanes lanes;
    alignas(64) path_lanes::Step step;
    RTCIntersectContext bounceContext, cameraContext;
    path_lanes::MovableLight movableLanes;
    path_lanes::Setup setup;
    uint32_t setUp = 0;  ///< the live lanes whose v[i] holds their vertex, set up by enter()

    LaneBatch(const PathTracer& t_, const Light& movable_, Rng* rngs_, int count_, TraceCounters& counters_)
        : t(t_), movable(movable_), shape(t_.shapeOf(movable_, scratch)), rngs(rngs_), count(count_), counters(counters_),
          movableLanes(t_.laneTables_.movable) {
        using namespace path_lanes;
        for (int i = 0; i < K; ++i) {
            lanes.beta.x[i] = lanes.beta.y[i] = lanes.beta.z[i] = 1.f;
            lanes.direct.x[i] = lanes.direct.y[i] = lanes.direct.z[i] = 0.f;
            lanes.indirect.x[i] = lanes.indirect.y[i] = lanes.indirect.z[i] = 0.f;
            lanes.rng[i] = i < count ? rngs[i].state() : 0;
        }
        rtcInitIntersectContext(&bounceContext);
        bounceContext.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
        rtcInitIntersectContext(&cameraContext);
        const RectLight* rects = t.laneTables_.rects.data();
        if (t.movable_ >= 0 && !(movable.corner == t.movableDefault_.corner)) {
            put(movableLanes.corner, movable.corner);
            if (t.laneTables_.movableRect >= 0) {
                // The rect lights with the movable one moved, for this batch only (a batch never
                // outlives its call, nor does another start on the thread meanwhile).
                thread_local std::vector<path_lanes::RectLight> moved;
                moved.assign(t.laneTables_.rects.begin(), t.laneTables_.rects.end());
                put(moved[size_t(t.laneTables_.movableRect)].corner, movable.corner);
                rects = moved.data();
            }
        }
        const Accel::GeometryTable& geometry = t.accel_.geometryTable();
        setup = Setup{t.accel_.handle(),
                      &bounceContext,
                      t.accel_.sceneScale(),
                      rects,
                      int(t.laneTables_.rects.size()),
                      t.laneTables_.points.data(),
                      int(t.laneTables_.points.size()),
                      t.movable_ >= 0 && movable.isArea() ? &movableLanes : nullptr,
                      0,
                      t.laneTables_.geomMaterial.data(),
                      geometry.normalBase.data(),
                      geometry.normals.data(),
                      t.laneTables_.kd.data(),
                      geometry.light.data(),
                      t.laneTables_.lightRadiance.data(),
                      t.laneTables_.lightNormal.data(),
                      t.laneTables_.lightOneSided.data(),
                      &cameraContext};
    }

    /// A lane's state at the vertex enter() has set up in v[i].
    void load(int i) {
        const Vertex& vi = v[i];
        lanes.p.x[i] = vi.hit.p.x, lanes.p.y[i] = vi.hit.p.y, lanes.p.z[i] = vi.hit.p.z;
        lanes.ng.x[i] = vi.hit.ng.x, lanes.ng.y[i] = vi.hit.ng.y, lanes.ng.z[i] = vi.hit.ng.z;
        lanes.n.x[i] = vi.n.x, lanes.n.y[i] = vi.n.y, lanes.n.z[i] = vi.n.z;
        lanes.kd.x[i] = vi.brdf->kd.x, lanes.kd.y[i] = vi.brdf->kd.y, lanes.kd.z[i] = vi.brdf->kd.z;
        lanes.side[i] = vi.side;
        lanes.smooth = (lanes.smooth & ~(1u << i)) | (vi.hit.ns.isZero() ? 0u : 1u << i);
        lanes.live |= 1u << i;
        setUp |= 1u << i;
    }
    void loadDirect(int i) {
        lanes.direct.x[i] = v[i].L.direct.x, lanes.direct.y[i] = v[i].L.direct.y, lanes.direct.z[i] = v[i].L.direct.z;
    }

    /// Lane i's bounce ray in step.next.
    Ray rayOf(int i) const {
        Ray r;
        r.origin = Vec3(step.next.ray.org_x[i], step.next.ray.org_y[i], step.next.ray.org_z[i]);
        r.dir = Vec3(step.next.ray.dir_x[i], step.next.ray.dir_y[i], step.next.ray.dir_z[i]);
        return r;  // from 0 to infinity, as bounceRay() makes it
    }

    /// The vertex lane i arrived at along ray r, traced in step.next, as intersect() and arrive()
    /// give it (depth: the vertex's); true when enter() lets the path go on there.
    bool arriveAlone(int i, int depth, const Ray& r) {
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
    }

    /// The first vertices: where the camera rays hit (one packet, as Accel::intersectPacket packs
    /// it), with the emission seen there.
    void fromCamera(const Ray* rays) {
        counters.rays += uint64_t(count);
        alignas(64) int valid[K];  // start() takes the lanes from lanes.live
        Accel::packRays(rays, count, step.next.ray, valid);
        cameraContext.flags = Accel::packetFlags(rays, count);
        lanes.live = (1u << count) - 1u;
        t.lanesKernels_.start(setup, lanes, step);
        for (uint32_t b = step.resolve; b; b &= b - 1) {
            const int i = __builtin_ctz(b);
            const bool goesOn = arriveAlone(i, 0, rays[i]);
            loadDirect(i);
            if (goesOn) load(i);
        }
    }

    /// The first vertices: every path at `hit`, seen from `wo` (shade()), set up once.
    void fromVertex(const Hit& hit, const Vec3& wo) {
        v[0].hit = hit;
        v[0].wo = wo;
        emissionSeen(t, v[0], movable);
        const bool goesOn = enter<false>(t, v[0]);
        for (int i = 0; i < count; ++i) {
            v[i] = v[0];
            loadDirect(i);
            if (goesOn) load(i);
        }
    }

    /// The lanes' lockstep, deeper than the portable one: a lane's step costs little, and Russian
    /// roulette thins the packets only slowly over the first vertices; sparser still, they cost
    /// Embree more than they save (docs/results-history.md, "The tracer's lanes").
    void lockstep() {
        constexpr int kLockstepVertices = 4;
        while (lanes.live && lanes.depth < kLockstepVertices) {
            setup.bounces = lanes.depth + 1 < t.maxDepth_ && t.effects_.indirect;
            t.lanesKernels_.step(setup, lanes, step);
            counters.shadowRays += step.shadowRays;
            counters.rays += uint64_t(__builtin_popcount(step.bounced));
            ++lanes.depth;
            setUp = 0;
            for (uint32_t b = step.resolve; b; b &= b - 1) {
                const int i = __builtin_ctz(b);
                if (arriveAlone(i, lanes.depth, rayOf(i))) load(i);
            }
        }
    }

    /// The paths still alive go on one by one as in shade(); out[i] = path i's radiance, rngs[i]
    /// where it ended.
    void finish(Radiance* out) {
        for (int i = 0; i < count; ++i) {
            Vertex& vi = v[i];
            vi.L.direct = Vec3(lanes.direct.x[i], lanes.direct.y[i], lanes.direct.z[i]);
            vi.L.indirect = Vec3(lanes.indirect.x[i], lanes.indirect.y[i], lanes.indirect.z[i]);
            Rng& rng = rngs[i] = Rng::ofState(lanes.rng[i]);
            if ((lanes.live >> i) & 1u) {
                // A vertex the lanes set up themselves: intersect()'s Hit for the ray that got there.
                const bool ready = ((setUp >> i) & 1u) || arriveAlone(i, lanes.depth, rayOf(i));
                if (ready) {
                    vi.beta = Vec3(lanes.beta.x[i], lanes.beta.y[i], lanes.beta.z[i]);
                    directLight<false>(t, vi, movable, rng, counters);
                    if (scatter<false>(t, vi, movable, rng, counters)) PathTracer::Impl::finish<false>(t, vi, movable, rng, counters);
                }
            }
            out[i] = vi.L;
        }
    }
};

void PathTracer::Impl::traceLanes(const PathTracer& t, const Ray* rays, Rng* rngs, int count, TraceCounters& counters,
                                  Radiance* out) {
    LaneBatch batch(t, t.movableDefault_, rngs, count, counters);
    batch.fromCamera(rays);
    batch.lockstep();
    batch.finish(out);
}

void PathTracer::Impl::shadeLanes(const PathTracer& t, const Hit& hit, const Vec3& wo, const Light& movable, Rng* rngs,
                                  int count, TraceCounters& counters, Radiance* out) {
    LaneBatch batch(t, movable, rngs, count, counters);
    batch.fromVertex(hit, wo);
    batch.lockstep();
    batch.finish(out);
}

}  // namespace rrf
