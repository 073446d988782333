// The path tracer's lanes for one instruction set (render/path_lanes.h), included by
// path_lanes_<isa>.cpp with RRF_ISA defined and that set's flags plus -ffp-contract=off
// (CMakeLists.txt). First the set's 16 lanes (path_lanes_simd.inl), then the steps, each
// mirroring one of render/path_steps.h, whose comments say why; the expressions keep that file's
// operations and their order, lane by lane.
#include "core/render/path_lanes.h"

#include <immintrin.h>
#include <math.h>  // the C library's cosf and sinf, as trace() calls them (not <cmath>'s inline wrappers)

#ifndef RRF_ISA
#error "define RRF_ISA (avx2, avx512) before including path_lanes.inl"
#endif

namespace rrf::path_lanes::RRF_ISA {
namespace {

#include "core/render/path_lanes_simd.inl"

/// Accel::offset and Accel::spawnOrigin.
inline F offset(const V3& p, F sceneScale) {
    const F m = maxStd(absf(p.x), maxStd(absf(p.y), absf(p.z)));
    return mul(bc(2e-5f), add(m, sceneScale));
}
inline V3 spawnOrigin(const V3& p, const V3& ng, const V3& dir, F sceneScale) {
    const F e = offset(p, sceneScale);
    const V3 ne = mul(ng, e);
    return select(ge(dot(dir, ng), zeroF()), sub(p, ne), add(p, ne));
}

/// Embree's 16-wide rays from origins, directions and tmax (tmin 0); valid = the lanes of `m`. The
/// other lanes get an empty interval (tnear +inf, tfar -inf): where Embree has no 16-wide kernels
/// (CPUs without AVX-512) it splits the packet and reads activity from the interval, not `valid`.
inline void packRays(RTCRay16& r, int* valid, M m, const V3& o, const V3& d, F tmax) {
    storeF(r.org_x, o.x);
    storeF(r.org_y, o.y);
    storeF(r.org_z, o.z);
    storeF(r.dir_x, d.x);
    storeF(r.dir_y, d.y);
    storeF(r.dir_z, d.z);
    storeF(r.tnear, blend(m, bc(INFINITY), zeroF()));
    storeF(r.tfar, blend(m, bc(-INFINITY), tmax));
    storeF(r.time, zeroF());
    storeI(r.mask, bci(-1));
    for (int i = 0; i < kLanes; ++i) r.id[i] = unsigned(i);
    storeI(r.flags, bci(0));
    storeValid(valid, m);
}

/// intersectAreaLight() for the rect (the lanes run no scene with triangle lights) in the lanes of
/// `m` (origin o, direction d, from tmin to tmax); `t` where it hits.
inline M hitsMovable(const MovableLight& l, M m, const V3& o, const V3& d, F tmin, F tmax, F& t) {
    const V3 n = bc3(l.n), corner = bc3(l.corner);
    const F zero = zeroF();
    const F denom = dot(d, n);
    m &= notm(eq(denom, zero));
    t = div(dot(sub(corner, o), n), denom);
    m &= gt(t, tmin) & lt(t, tmax);
    const V3 q = sub(add(o, mul(d, t)), corner);
    const F nn = bc(l.nn);
    const F a = div(dot(cross(q, bc3(l.edge2)), n), nn);
    m &= ge(a, zero) & le(a, bc(1.f));
    const F b = div(dot(cross(bc3(l.edge1), q), n), nn);
    return m & ge(b, zero) & le(b, bc(1.f));
}

/// The light samples' common tail (lightSamples' `visible` and the occlusion test): the lanes of
/// `ok` whose sample towards `target` is unoccluded add `c` to `sum`.
inline void addVisible(const Setup& setup, M ok, const V3& p, const V3& ng, F ngSide, const V3& wi, const V3& target,
                       const V3& c, F sceneScale, V3& sum, uint64_t& shadowRays) {
    const F zero = zeroF();
    ok &= notm(le(mul(dot(wi, ng), ngSide), zero));
    if (!ok) return;
    const V3 origin = spawnOrigin(p, ng, wi, sceneScale);
    const V3 d = sub(target, origin);
    const F dist = sqrtF(dot(d, d));
    const F tmax = sub(mul(dist, bc(1.f - 1e-4f)), offset(target, sceneScale));
    const M needsRay = ok & gt(tmax, zero);
    M blocked = 0;
    if (needsRay) {
        const V3 dir = div(d, dist);
        alignas(64) RTCRay16 ray;
        alignas(64) int valid[kLanes];
        packRays(ray, valid, needsRay, origin, dir, tmax);
        RTCIntersectContext ctx = *setup.context;
        rtcOccluded16(valid, setup.scene, &ctx, &ray);
        blocked = needsRay & lt(loadF(ray.tfar), zero);  // Embree sets tfar = -inf on a hit
        F t;
        if (setup.movable) blocked |= hitsMovable(*setup.movable, needsRay & notm(blocked), origin, dir, zero, tmax, t);
        shadowRays += uint64_t(__builtin_popcount(needsRay));
    }
    const M adds = ok & notm(blocked);
    sum = select(adds, sum, add(sum, c));
}

/// withMovableLight(), Accel::fillHit(), arrive() and enter() for the bounce rays of `bounced`
/// (origin o, direction d, from tmin to tmax) that Embree traced into out.next; returns the lanes
/// live at the new vertex, whose state it stores in L. With kEmission, emissionSeen() too.
template <bool kEmission>
inline M arrive(const Setup& setup, M bounced, const V3& o, const V3& d, F tmin, F tmax, Step& out, PathLanes& lanes) {
    const F zero = zeroF();
    const I geom = loadI(out.next.hit.geomID);
    const M found = bounced & neI(geom, bci(int(RTC_INVALID_GEOMETRY_ID)));
    const F tfar = loadF(out.next.ray.tfar);
    F tMovable = zero;
    const M movable = setup.movable ? hitsMovable(*setup.movable, bounced, o, d, tmin, blend(found, tmax, tfar), tMovable) : M(0);
    const I base = gatherI(bci(0), found, geom, setup.geomNormalBase);
    out.resolve = found & notm(movable) & ltI(base, bci(0));
    const M flat = found & notm(movable) & notm(out.resolve);
    const F t = blend(movable, tfar, tMovable);
    const V3 p = add(o, mul(d, t));
    const I prim3 = mulI(addI(base, loadI(out.next.hit.primID)), bci(3));
    static const float kNone[3] = {0.f, 0.f, 0.f};
    V3 ng = bc3(setup.movable ? setup.movable->normal : kNone);  // the movable light's lanes keep it
    ng.x = gatherF(ng.x, flat, prim3, setup.normals);
    ng.y = gatherF(ng.y, flat, addI(prim3, bci(1)), setup.normals);
    ng.z = gatherF(ng.z, flat, addI(prim3, bci(2)), setup.normals);
    const I material = gatherI(bci(setup.movable ? setup.movable->material : -1), flat, geom, setup.geomMaterial);
    M live = (flat | movable) & notm(ltI(material, bci(0)));
    const F side = dot(V3{neg(d.x), neg(d.y), neg(d.z)}, ng);
    live &= notm(eq(side, zero));
    const M front = gt(side, zero);
    const V3 n = select(front, V3{neg(ng.x), neg(ng.y), neg(ng.z)}, ng);
    if constexpr (kEmission) {
        // Light::emittedTowards(wo), wo = -d, for the lanes that see an emitter.
        const I light = gatherI(bci(-1), flat, geom, setup.geomLight);
        const M fromTable = flat & notm(ltI(light, bci(0)));
        if (fromTable | movable) {
            const I l3 = mulI(light, bci(3));
            const V3 wo{neg(d.x), neg(d.y), neg(d.z)};
            const float* mr = setup.movable ? setup.movable->radiance : kNone;
            const float* mn = setup.movable ? setup.movable->n : kNone;
            const V3 radiance{gatherF(bc(mr[0]), fromTable, l3, setup.lightRadiance),
                              gatherF(bc(mr[1]), fromTable, addI(l3, bci(1)), setup.lightRadiance),
                              gatherF(bc(mr[2]), fromTable, addI(l3, bci(2)), setup.lightRadiance)};
            const V3 nl{gatherF(bc(mn[0]), fromTable, l3, setup.lightNormal),
                        gatherF(bc(mn[1]), fromTable, addI(l3, bci(1)), setup.lightNormal),
                        gatherF(bc(mn[2]), fromTable, addI(l3, bci(2)), setup.lightNormal)};
            const I oneSided = gatherI(bci(setup.movable ? setup.movable->oneSided : 0), fromTable, light, setup.lightOneSided);
            const M dark = ltI(bci(0), oneSided) & le(dot(wo, nl), zero);
            const M seen = (fromTable | movable) & notm(dark);
            store(lanes.direct, seen, add(load(lanes.direct), radiance));
        }
    }
    const I m3 = mulI(material, bci(3));
    const V3 kd{gatherF(zero, live, m3, setup.materialKd), gatherF(zero, live, addI(m3, bci(1)), setup.materialKd),
                gatherF(zero, live, addI(m3, bci(2)), setup.materialKd)};
    store(lanes.p, live, p);
    store(lanes.ng, live, ng);
    store(lanes.n, live, n);
    store(lanes.kd, live, kd);
    storeF(lanes.side, live, side);
    lanes.smooth &= notm(live);
    return live;
}

}  // namespace

void step(const Setup& setup, PathLanes& lanes, Step& out) {
    const M live = M(lanes.live) & kAllLanes;
    const F zero = zeroF();
    const F sceneScale = bc(setup.sceneScale);
    const V3 p = load(lanes.p), ng = load(lanes.ng), n = load(lanes.n), kd = load(lanes.kd);
    Rngs rng(lanes.rng);

    // NEE (lightSamples() of a diffuse vertex, then directLight()'s sum).
    const F ngSide = dot(n, ng);
    const V3 f = mul(kd, bc(0.31830988618379067154f));  // kd · kInvPi
    const M fNonZero = notm(isZero(f));
    V3 sum{zero, zero, zero};
    uint64_t shadowRays = 0;
    for (int k = 0; k < setup.rectCount; ++k) {
        const RectLight& l = setup.rect[k];
        const F u1 = rng.uniform(live), u2 = rng.uniform(live);
        const V3 x = add(add(bc3(l.corner), mul(bc3(l.edge1), u1)), mul(bc3(l.edge2), u2));
        const V3 d = sub(x, p);
        const F dist2 = dot(d, d);
        M ok = live & gt(dist2, zero);
        const F dist = sqrtF(dist2);
        const V3 wi = div(d, dist);
        const F cosTheta = dot(wi, n);
        ok &= notm(le(cosTheta, zero));
        F cosLArea = neg(dot(wi, bc3(l.nl)));
        if (!l.oneSided) cosLArea = absf(cosLArea);
        ok &= notm(le(cosLArea, zero)) & fNonZero;
        if (!ok) continue;
        const F w = div(mul(cosTheta, cosLArea), dist2);
        const V3 c = mul(mul(bc3(l.radiance), f), w);
        addVisible(setup, ok, p, ng, ngSide, wi, x, c, sceneScale, sum, shadowRays);
    }
    for (int k = 0; k < setup.pointCount; ++k) {
        const PointLight& l = setup.point[k];
        const V3 pos = bc3(l.position);
        const V3 d = sub(pos, p);
        const F dist2 = dot(d, d);
        M ok = live & gt(dist2, zero);
        const V3 wi = div(d, sqrtF(dist2));
        const F cosTheta = dot(wi, n);
        ok &= notm(le(cosTheta, zero)) & fNonZero;
        if (!ok) continue;
        const V3 c = mul(mul(bc3(l.intensity), f), div(cosTheta, dist2));
        addVisible(setup, ok, p, ng, ngSide, wi, pos, c, sceneScale, sum, shadowRays);
    }
    Lanes3& target = lanes.depth == 0 ? lanes.direct : lanes.indirect;
    store(target, live, add(load(target), mul(load(lanes.beta), sum)));
    out.shadowRays = shadowRays;

    // The bounce (bounceRay() of a diffuse vertex).
    out.bounced = out.resolve = 0;
    M next = 0;
    if (setup.bounces && live) {
        (void)rng.uniform(live);  // the lobe choice, drawn for every BRDF
        const F u1 = rng.uniform(live), u2 = rng.uniform(live);
        const F cosT = sqrtF(sub(bc(1.f), u1));
        const F sinT = sqrtF(u1);
        alignas(64) float phi[kLanes], cosPhi[kLanes], sinPhi[kLanes];
        storeF(phi, mul(bc(2.f * 3.14159265358979323846f), u2));
        for (int i = 0; i < kLanes; ++i) {
            if (!((live >> i) & 1u)) {
                cosPhi[i] = sinPhi[i] = 0.f;
                continue;
            }
            cosPhi[i] = cosf(phi[i]);
            sinPhi[i] = sinf(phi[i]);
        }
        const V3 wl{mul(sinT, loadF(cosPhi)), mul(sinT, loadF(sinPhi)), cosT};
        M ok = live & gt(wl.z, zero);
        // Frame(n) (Duff et al.) and toWorld().
        const F sign = bitsOr(bitsAnd(n.z, bc(-0.f)), bc(1.f));  // copysign(1, n.z)
        const F a = div(bc(-1.f), add(sign, n.z));
        const F b = mul(mul(n.x, n.y), a);
        const V3 fs{add(bc(1.f), mul(mul(mul(sign, n.x), n.x), a)), mul(sign, b), mul(neg(sign), n.x)};
        const V3 ft{b, add(sign, mul(mul(n.y, n.y), a)), neg(n.y)};
        const V3 wi = add(add(mul(fs, wl.x), mul(ft, wl.y)), mul(n, wl.z));
        ok &= notm(M(lanes.smooth) & le(mul(dot(wi, ng), loadF(lanes.side)), zero));
        V3 beta = mul(load(lanes.beta), kd);
        if (lanes.depth >= 1) {
            const F q0 = maxStd(beta.x, maxStd(beta.y, beta.z));
            const F q = blend(lt(q0, bc(0.05f)), blend(lt(bc(1.f), q0), q0, bc(1.f)), bc(0.05f));  // std::clamp
            const M roulette = ok & lt(q, bc(1.f));
            const F u = rng.uniform(roulette);
            ok &= notm(roulette & ge(u, q));
            beta = select(roulette, beta, div(beta, q));
        }
        ok &= notm(isZero(beta));
        store(lanes.beta, live, beta);
        if (ok) {
            const V3 origin = spawnOrigin(p, ng, wi, sceneScale);
            alignas(64) int valid[kLanes];
            packRays(out.next.ray, valid, ok, origin, wi, bc(INFINITY));
            storeI(out.next.hit.geomID, bci(int(RTC_INVALID_GEOMETRY_ID)));
            storeI(out.next.hit.instID[0], bci(int(RTC_INVALID_GEOMETRY_ID)));
            RTCIntersectContext ctx = *setup.context;
            rtcIntersect16(valid, setup.scene, &ctx, &out.next);
            out.bounced = ok;
            next = arrive<false>(setup, ok, origin, wi, zero, bc(INFINITY), out, lanes);
        }
    }
    lanes.live = next;
    rng.store(lanes.rng);
}

void start(const Setup& setup, PathLanes& lanes, Step& out) {
    const M live = M(lanes.live) & kAllLanes;
    alignas(64) int valid[kLanes];
    storeValid(valid, live);
    const V3 o{loadF(out.next.ray.org_x), loadF(out.next.ray.org_y), loadF(out.next.ray.org_z)};
    const V3 d{loadF(out.next.ray.dir_x), loadF(out.next.ray.dir_y), loadF(out.next.ray.dir_z)};
    const F tmin = loadF(out.next.ray.tnear), tmax = loadF(out.next.ray.tfar);  // Embree changes tfar
    storeF(out.next.ray.tnear, blend(live, bc(INFINITY), tmin));  // packRays()'s empty lanes
    storeF(out.next.ray.tfar, blend(live, bc(-INFINITY), tmax));
    storeI(out.next.hit.geomID, bci(int(RTC_INVALID_GEOMETRY_ID)));
    storeI(out.next.hit.instID[0], bci(int(RTC_INVALID_GEOMETRY_ID)));
    RTCIntersectContext ctx = *setup.cameraContext;
    rtcIntersect16(valid, setup.scene, &ctx, &out.next);
    out.bounced = live;
    out.resolve = 0;
    out.shadowRays = 0;
    lanes.live = arrive<true>(setup, live, o, d, tmin, tmax, out, lanes);
}

}  // namespace rrf::path_lanes::RRF_ISA
