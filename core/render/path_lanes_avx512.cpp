// AVX-512 build of the path tracer's lanes (render/path_lanes.h); compiled with -mavx512f -mavx512dq
// -ffp-contract=off (CMakeLists.txt). Each function mirrors one step of render/path_steps.h, whose
// comments say why; the expressions keep that file's operations and their order, lane by lane.
#include "core/render/path_lanes.h"

#include <immintrin.h>
#include <math.h>  // the C library's cosf and sinf, as trace() calls them (not <cmath>'s inline wrappers)

namespace rrf::path_lanes::avx512 {
namespace {

using F = __m512;
using M = __mmask16;

struct V3 {
    F x, y, z;
};

inline F bc(float v) { return _mm512_set1_ps(v); }
inline F add(F a, F b) { return _mm512_add_ps(a, b); }
inline F sub(F a, F b) { return _mm512_sub_ps(a, b); }
inline F mul(F a, F b) { return _mm512_mul_ps(a, b); }
inline F div(F a, F b) { return _mm512_div_ps(a, b); }
inline F neg(F a) { return _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(a), _mm512_set1_epi32(int(0x80000000u)))); }
inline F absf(F a) { return _mm512_abs_ps(a); }
/// The C comparisons (false when either side is NaN).
inline M lt(F a, F b) { return _mm512_cmp_ps_mask(a, b, _CMP_LT_OQ); }
inline M le(F a, F b) { return _mm512_cmp_ps_mask(a, b, _CMP_LE_OQ); }
inline M gt(F a, F b) { return _mm512_cmp_ps_mask(a, b, _CMP_GT_OQ); }
inline M ge(F a, F b) { return _mm512_cmp_ps_mask(a, b, _CMP_GE_OQ); }
inline M eq(F a, F b) { return _mm512_cmp_ps_mask(a, b, _CMP_EQ_OQ); }
/// std::max(a, b): a unless a < b.
inline F maxStd(F a, F b) { return _mm512_mask_blend_ps(lt(a, b), a, b); }

inline V3 bc3(const float* v) { return {bc(v[0]), bc(v[1]), bc(v[2])}; }
inline V3 load(const Lanes3& l) { return {_mm512_load_ps(l.x), _mm512_load_ps(l.y), _mm512_load_ps(l.z)}; }
inline void store(Lanes3& l, M m, const V3& v) {
    _mm512_mask_store_ps(l.x, m, v.x);
    _mm512_mask_store_ps(l.y, m, v.y);
    _mm512_mask_store_ps(l.z, m, v.z);
}
inline V3 add(const V3& a, const V3& b) { return {add(a.x, b.x), add(a.y, b.y), add(a.z, b.z)}; }
inline V3 sub(const V3& a, const V3& b) { return {sub(a.x, b.x), sub(a.y, b.y), sub(a.z, b.z)}; }
inline V3 mul(const V3& a, const V3& b) { return {mul(a.x, b.x), mul(a.y, b.y), mul(a.z, b.z)}; }
inline V3 mul(const V3& a, F s) { return {mul(a.x, s), mul(a.y, s), mul(a.z, s)}; }
inline V3 div(const V3& a, F s) { return {div(a.x, s), div(a.y, s), div(a.z, s)}; }
inline F dot(const V3& a, const V3& b) { return add(add(mul(a.x, b.x), mul(a.y, b.y)), mul(a.z, b.z)); }
inline V3 cross(const V3& a, const V3& b) {
    return {sub(mul(a.y, b.z), mul(a.z, b.y)), sub(mul(a.z, b.x), mul(a.x, b.z)), sub(mul(a.x, b.y), mul(a.y, b.x))};
}
inline M isZero(const V3& v) {
    const F z = _mm512_setzero_ps();
    return eq(v.x, z) & eq(v.y, z) & eq(v.z, z);
}
inline V3 select(M m, const V3& a, const V3& b) {  // b where m, else a
    return {_mm512_mask_blend_ps(m, a.x, b.x), _mm512_mask_blend_ps(m, a.y, b.y), _mm512_mask_blend_ps(m, a.z, b.z)};
}

/// Accel::offset and Accel::spawnOrigin.
inline F offset(const V3& p, F sceneScale) {
    const F m = maxStd(absf(p.x), maxStd(absf(p.y), absf(p.z)));
    return mul(bc(2e-5f), add(m, sceneScale));
}
inline V3 spawnOrigin(const V3& p, const V3& ng, const V3& dir, F sceneScale) {
    const F e = offset(p, sceneScale);
    const V3 ne = mul(ng, e);
    return select(ge(dot(dir, ng), _mm512_setzero_ps()), sub(p, ne), add(p, ne));
}

/// The 16 paths' Rng counters (Rng::uniform()), lanes 0-7 and 8-15.
struct Rngs {
    __m512i lo, hi;
    static __m512i mix64(__m512i z) {
        z = _mm512_mullo_epi64(_mm512_xor_si512(z, _mm512_srli_epi64(z, 30)), _mm512_set1_epi64(int64_t(0xBF58476D1CE4E5B9ULL)));
        z = _mm512_mullo_epi64(_mm512_xor_si512(z, _mm512_srli_epi64(z, 27)), _mm512_set1_epi64(int64_t(0x94D049BB133111EBULL)));
        return _mm512_xor_si512(z, _mm512_srli_epi64(z, 31));
    }
    /// Rng::uniform() in the lanes of `m`; the other lanes neither draw nor advance.
    F uniform(M m) {
        const __m512i gamma = _mm512_set1_epi64(int64_t(0x9E3779B97F4A7C15ULL));
        lo = _mm512_mask_add_epi64(lo, __mmask8(m), lo, gamma);
        hi = _mm512_mask_add_epi64(hi, __mmask8(m >> 8), hi, gamma);
        // float(nextU32() >> 8) · 2^-24: the top 24 bits of mix64, exact as an int32 and as a float.
        const __m256i a = _mm512_cvtepi64_epi32(_mm512_srli_epi64(mix64(lo), 40));
        const __m256i b = _mm512_cvtepi64_epi32(_mm512_srli_epi64(mix64(hi), 40));
        const __m512i both = _mm512_inserti64x4(_mm512_castsi256_si512(a), b, 1);
        return mul(_mm512_cvtepi32_ps(both), bc(0x1.0p-24f));
    }
};

/// Embree's 16-wide rays from origins, directions and tmax; valid = the lanes of `m`.
inline void packRays(RTCRay16& r, int* valid, M m, const V3& o, const V3& d, F tmax) {
    _mm512_store_ps(r.org_x, o.x);
    _mm512_store_ps(r.org_y, o.y);
    _mm512_store_ps(r.org_z, o.z);
    _mm512_store_ps(r.dir_x, d.x);
    _mm512_store_ps(r.dir_y, d.y);
    _mm512_store_ps(r.dir_z, d.z);
    _mm512_store_ps(r.tnear, _mm512_setzero_ps());
    _mm512_store_ps(r.tfar, tmax);
    _mm512_store_ps(r.time, _mm512_setzero_ps());
    _mm512_store_si512(r.mask, _mm512_set1_epi32(-1));
    _mm512_store_si512(r.id, _mm512_set_epi32(15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0));
    _mm512_store_si512(r.flags, _mm512_setzero_si512());
    _mm512_store_si512(valid, _mm512_movm_epi32(m));
}

/// intersectAreaLight() in the lanes of `m` (origin o, direction d, tmin 0); `t` where it hits.
inline M hitsMovable(const MovableLight& l, M m, const V3& o, const V3& d, F tmax, F& t) {
    const V3 n = bc3(l.n), corner = bc3(l.corner);
    const F zero = _mm512_setzero_ps();
    const F denom = dot(d, n);
    m &= ~eq(denom, zero);
    t = div(dot(sub(corner, o), n), denom);
    m &= gt(t, zero) & lt(t, tmax);
    const V3 q = sub(add(o, mul(d, t)), corner);
    const F nn = bc(l.nn);
    const F a = div(dot(cross(q, bc3(l.edge2)), n), nn);
    m &= ge(a, zero);
    if (!l.triangle) m &= le(a, bc(1.f));
    const F b = div(dot(cross(bc3(l.edge1), q), n), nn);
    if (l.triangle) return m & ge(b, zero) & le(add(a, b), bc(1.f));
    return m & ge(b, zero) & le(b, bc(1.f));
}

/// The light samples' common tail (lightSamples' `visible` and the occlusion test): the lanes of
/// `ok` whose sample towards `target` is unoccluded add `c` to `sum`.
inline void addVisible(const Setup& s, M ok, const V3& p, const V3& ng, F ngSide, const V3& wi, const V3& target,
                       const V3& c, F sceneScale, V3& sum, uint64_t& shadowRays) {
    const F zero = _mm512_setzero_ps();
    ok &= ~le(mul(dot(wi, ng), ngSide), zero);
    if (!ok) return;
    const V3 origin = spawnOrigin(p, ng, wi, sceneScale);
    const V3 d = sub(target, origin);
    const F dist = _mm512_sqrt_ps(dot(d, d));
    const F tmax = sub(mul(dist, bc(1.f - 1e-4f)), offset(target, sceneScale));
    const M needsRay = ok & gt(tmax, zero);
    M blocked = 0;
    if (needsRay) {
        const V3 dir = div(d, dist);
        alignas(64) RTCRay16 ray;
        alignas(64) int valid[kLanes];
        packRays(ray, valid, needsRay, origin, dir, tmax);
        RTCIntersectContext ctx = *s.context;
        rtcOccluded16(valid, s.scene, &ctx, &ray);
        blocked = needsRay & lt(_mm512_load_ps(ray.tfar), zero);  // Embree sets tfar = -inf on a hit
        F t;
        if (s.movable) blocked |= hitsMovable(*s.movable, needsRay & ~blocked, origin, dir, tmax, t);
        shadowRays += uint64_t(__builtin_popcount(unsigned(needsRay)));
    }
    const M adds = ok & ~blocked;
    sum = {_mm512_mask_add_ps(sum.x, adds, sum.x, c.x), _mm512_mask_add_ps(sum.y, adds, sum.y, c.y),
           _mm512_mask_add_ps(sum.z, adds, sum.z, c.z)};
}

/// withMovableLight(), Accel::fillHit(), arrive() and enter() for the bounce rays of `bounced`
/// (origin o, direction d) that Embree traced into out.next.
inline uint32_t arrive(const Setup& s, M bounced, const V3& o, const V3& d, Step& out, PathLanes& L) {
    const F zero = _mm512_setzero_ps();
    const __m512i invalid = _mm512_set1_epi32(int(RTC_INVALID_GEOMETRY_ID));
    const __m512i geom = _mm512_load_si512(out.next.hit.geomID);
    const M found = bounced & _mm512_cmpneq_epi32_mask(geom, invalid);
    const F tfar = _mm512_load_ps(out.next.ray.tfar);
    F tMovable = zero;
    const M movable = s.movable ? hitsMovable(*s.movable, bounced, o, d, _mm512_mask_blend_ps(found, bc(INFINITY), tfar), tMovable) : M(0);
    const __m512i base = _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), found, geom, s.geomNormalBase, 4);
    out.resolve = found & ~movable & _mm512_cmplt_epi32_mask(base, _mm512_setzero_si512());
    const M flat = (found & ~movable & ~out.resolve);
    const F t = _mm512_mask_blend_ps(movable, tfar, tMovable);
    const V3 p = add(o, mul(d, t));
    const __m512i prim3 = _mm512_mullo_epi32(_mm512_add_epi32(base, _mm512_load_si512(out.next.hit.primID)), _mm512_set1_epi32(3));
    static const float kNone[3] = {0.f, 0.f, 0.f};
    V3 ng = bc3(s.movable ? s.movable->normal : kNone);  // the movable light's lanes keep it
    ng.x = _mm512_mask_i32gather_ps(ng.x, flat, prim3, s.normals, 4);
    ng.y = _mm512_mask_i32gather_ps(ng.y, flat, _mm512_add_epi32(prim3, _mm512_set1_epi32(1)), s.normals, 4);
    ng.z = _mm512_mask_i32gather_ps(ng.z, flat, _mm512_add_epi32(prim3, _mm512_set1_epi32(2)), s.normals, 4);
    __m512i material = _mm512_set1_epi32(s.movable ? s.movable->material : -1);
    material = _mm512_mask_i32gather_epi32(material, flat, geom, s.geomMaterial, 4);
    M live = (flat | movable) & _mm512_cmpge_epi32_mask(material, _mm512_setzero_si512());
    const F side = dot(V3{neg(d.x), neg(d.y), neg(d.z)}, ng);
    live &= ~eq(side, zero);
    const M front = gt(side, zero);
    const V3 n{_mm512_mask_blend_ps(front, neg(ng.x), ng.x), _mm512_mask_blend_ps(front, neg(ng.y), ng.y),
               _mm512_mask_blend_ps(front, neg(ng.z), ng.z)};
    const __m512i m3 = _mm512_mullo_epi32(material, _mm512_set1_epi32(3));
    V3 kd{zero, zero, zero};
    kd.x = _mm512_mask_i32gather_ps(zero, live, m3, s.materialKd, 4);
    kd.y = _mm512_mask_i32gather_ps(zero, live, _mm512_add_epi32(m3, _mm512_set1_epi32(1)), s.materialKd, 4);
    kd.z = _mm512_mask_i32gather_ps(zero, live, _mm512_add_epi32(m3, _mm512_set1_epi32(2)), s.materialKd, 4);
    store(L.p, live, p);
    store(L.ng, live, ng);
    store(L.n, live, n);
    store(L.kd, live, kd);
    _mm512_mask_store_ps(L.side, live, side);
    L.smooth &= ~uint32_t(live);
    return uint32_t(live);
}

}  // namespace

void step(const Setup& s, PathLanes& L, Step& out) {
    const M live = M(L.live);
    const F zero = _mm512_setzero_ps();
    const F sceneScale = bc(s.sceneScale);
    const V3 p = load(L.p), ng = load(L.ng), n = load(L.n), kd = load(L.kd);
    Rngs rng{_mm512_loadu_si512(L.rng), _mm512_loadu_si512(L.rng + 8)};

    // NEE (lightSamples() of a diffuse vertex, then directLight()'s sum).
    const F ngSide = dot(n, ng);
    const V3 f = mul(kd, bc(0.31830988618379067154f));  // kd · kInvPi
    const M fNonZero = ~isZero(f);
    V3 sum{zero, zero, zero};
    uint64_t shadowRays = 0;
    for (int k = 0; k < s.rectCount; ++k) {
        const RectLight& l = s.rect[k];
        const F u1 = rng.uniform(live), u2 = rng.uniform(live);
        const V3 x = add(add(bc3(l.corner), mul(bc3(l.edge1), u1)), mul(bc3(l.edge2), u2));
        const V3 d = sub(x, p);
        const F dist2 = dot(d, d);
        M ok = live & gt(dist2, zero);
        const F dist = _mm512_sqrt_ps(dist2);
        const V3 wi = div(d, dist);
        const F cosTheta = dot(wi, n);
        ok &= ~le(cosTheta, zero);
        F cosLArea = neg(dot(wi, bc3(l.nl)));
        if (!l.oneSided) cosLArea = absf(cosLArea);
        ok &= ~le(cosLArea, zero) & fNonZero;
        if (!ok) continue;
        const F w = div(mul(cosTheta, cosLArea), dist2);
        const V3 c = mul(mul(bc3(l.radiance), f), w);
        addVisible(s, ok, p, ng, ngSide, wi, x, c, sceneScale, sum, shadowRays);
    }
    for (int k = 0; k < s.pointCount; ++k) {
        const PointLight& l = s.point[k];
        const V3 pos = bc3(l.position);
        const V3 d = sub(pos, p);
        const F dist2 = dot(d, d);
        M ok = live & gt(dist2, zero);
        const V3 wi = div(d, _mm512_sqrt_ps(dist2));
        const F cosTheta = dot(wi, n);
        ok &= ~le(cosTheta, zero) & fNonZero;
        if (!ok) continue;
        const V3 c = mul(mul(bc3(l.intensity), f), div(cosTheta, dist2));
        addVisible(s, ok, p, ng, ngSide, wi, pos, c, sceneScale, sum, shadowRays);
    }
    Lanes3& target = L.depth == 0 ? L.direct : L.indirect;
    store(target, live, add(load(target), mul(load(L.beta), sum)));
    out.shadowRays = shadowRays;

    // The bounce (bounceRay() of a diffuse vertex).
    out.bounced = out.resolve = 0;
    uint32_t next = 0;
    if (s.bounces && live) {
        (void)rng.uniform(live);  // the lobe choice, drawn for every BRDF
        const F u1 = rng.uniform(live), u2 = rng.uniform(live);
        const F cosT = _mm512_sqrt_ps(sub(bc(1.f), u1));
        const F sinT = _mm512_sqrt_ps(u1);
        alignas(64) float phi[kLanes], cosPhi[kLanes], sinPhi[kLanes];
        _mm512_store_ps(phi, mul(bc(2.f * 3.14159265358979323846f), u2));
        for (int i = 0; i < kLanes; ++i) {
            if (!((live >> i) & 1u)) {
                cosPhi[i] = sinPhi[i] = 0.f;
                continue;
            }
            cosPhi[i] = cosf(phi[i]);
            sinPhi[i] = sinf(phi[i]);
        }
        const V3 wl{mul(sinT, _mm512_load_ps(cosPhi)), mul(sinT, _mm512_load_ps(sinPhi)), cosT};
        M ok = live & gt(wl.z, zero);
        // Frame(n) (Duff et al.) and toWorld().
        const F sign = _mm512_castsi512_ps(_mm512_or_si512(
            _mm512_and_si512(_mm512_castps_si512(n.z), _mm512_set1_epi32(int(0x80000000u))), _mm512_castps_si512(bc(1.f))));
        const F a = div(bc(-1.f), add(sign, n.z));
        const F b = mul(mul(n.x, n.y), a);
        const V3 fs{add(bc(1.f), mul(mul(mul(sign, n.x), n.x), a)), mul(sign, b), mul(neg(sign), n.x)};
        const V3 ft{b, add(sign, mul(mul(n.y, n.y), a)), neg(n.y)};
        const V3 wi = add(add(mul(fs, wl.x), mul(ft, wl.y)), mul(n, wl.z));
        ok &= ~(M(L.smooth) & le(mul(dot(wi, ng), _mm512_load_ps(L.side)), zero));
        V3 beta = mul(load(L.beta), kd);
        if (L.depth >= 1) {
            const F q0 = maxStd(beta.x, maxStd(beta.y, beta.z));
            // std::clamp(q0, 0.05f, 1.f)
            const F q = _mm512_mask_blend_ps(lt(q0, bc(0.05f)), _mm512_mask_blend_ps(lt(bc(1.f), q0), q0, bc(1.f)), bc(0.05f));
            const M roulette = ok & lt(q, bc(1.f));
            const F u = rng.uniform(roulette);
            ok &= ~(roulette & ge(u, q));
            beta = select(roulette, beta, div(beta, q));
        }
        ok &= ~isZero(beta);
        store(L.beta, live, beta);
        if (ok) {
            const V3 origin = spawnOrigin(p, ng, wi, sceneScale);
            alignas(64) int valid[kLanes];
            packRays(out.next.ray, valid, ok, origin, wi, bc(INFINITY));
            _mm512_store_si512(out.next.hit.geomID, _mm512_set1_epi32(int(RTC_INVALID_GEOMETRY_ID)));
            _mm512_store_si512(out.next.hit.instID[0], _mm512_set1_epi32(int(RTC_INVALID_GEOMETRY_ID)));
            RTCIntersectContext ctx = *s.context;
            rtcIntersect16(valid, s.scene, &ctx, &out.next);
            out.bounced = ok;
            next = arrive(s, ok, origin, wi, out, L);
        }
    }
    L.live = next;
    _mm512_storeu_si512(L.rng, rng.lo);
    _mm512_storeu_si512(L.rng + 8, rng.hi);
}

}  // namespace rrf::path_lanes::avx512
