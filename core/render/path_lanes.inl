// The path tracer's lanes for one instruction set (render/path_lanes.h), included by
// path_lanes_<isa>.cpp with RRF_ISA defined and that set's flags plus -ffp-contract=off
// (CMakeLists.txt). First the set's 16 lanes (float F, int I, a bit mask M), then the steps, each
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

using M = uint32_t;  ///< bit i = lane i
constexpr M kAllLanes = 0xFFFFu;
inline M notm(M m) { return ~m & kAllLanes; }

#if defined(__AVX512F__)
using F = __m512;
using I = __m512i;
inline F bc(float v) { return _mm512_set1_ps(v); }
inline F bcBits(uint32_t v) { return _mm512_castsi512_ps(_mm512_set1_epi32(int(v))); }
inline F zeroF() { return _mm512_setzero_ps(); }
inline F add(F a, F b) { return _mm512_add_ps(a, b); }
inline F sub(F a, F b) { return _mm512_sub_ps(a, b); }
inline F mul(F a, F b) { return _mm512_mul_ps(a, b); }
inline F div(F a, F b) { return _mm512_div_ps(a, b); }
inline F sqrtF(F a) { return _mm512_sqrt_ps(a); }
inline F bitsOr(F a, F b) { return _mm512_castsi512_ps(_mm512_or_si512(_mm512_castps_si512(a), _mm512_castps_si512(b))); }
inline F bitsAnd(F a, F b) { return _mm512_castsi512_ps(_mm512_and_si512(_mm512_castps_si512(a), _mm512_castps_si512(b))); }
inline F bitsXor(F a, F b) { return _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(a), _mm512_castps_si512(b))); }
inline F loadF(const float* p) { return _mm512_load_ps(p); }
inline void storeF(float* p, F v) { _mm512_store_ps(p, v); }
inline void storeF(float* p, M m, F v) { _mm512_mask_store_ps(p, __mmask16(m), v); }
template <int kOp>
inline M cmp(F a, F b) { return M(_mm512_cmp_ps_mask(a, b, kOp)); }
inline F blend(M m, F a, F b) { return _mm512_mask_blend_ps(__mmask16(m), a, b); }  ///< b where m, else a
inline F toFloat(I a) { return _mm512_cvtepi32_ps(a); }
inline I bci(int v) { return _mm512_set1_epi32(v); }
inline I loadI(const void* p) { return _mm512_load_si512(p); }
inline void storeI(void* p, I v) { _mm512_store_si512(p, v); }
inline I addI(I a, I b) { return _mm512_add_epi32(a, b); }
inline I mulI(I a, I b) { return _mm512_mullo_epi32(a, b); }
inline M neI(I a, I b) { return M(_mm512_cmpneq_epi32_mask(a, b)); }
inline M ltI(I a, I b) { return M(_mm512_cmplt_epi32_mask(a, b)); }
inline I gatherI(I src, M m, I index, const int* base) { return _mm512_mask_i32gather_epi32(src, __mmask16(m), index, base, 4); }
inline F gatherF(F src, M m, I index, const float* base) { return _mm512_mask_i32gather_ps(src, __mmask16(m), index, base, 4); }
/// Embree's valid array: -1 in the lanes of m, 0 elsewhere.
inline void storeValid(int* valid, M m) { _mm512_store_si512(valid, _mm512_movm_epi32(__mmask16(m))); }

/// The 16 paths' Rng counters (Rng::uniform()), lanes 0-7 and 8-15.
struct Rngs {
    __m512i lo, hi;
    explicit Rngs(const uint64_t* s) : lo(_mm512_loadu_si512(s)), hi(_mm512_loadu_si512(s + 8)) {}
    void store(uint64_t* s) const {
        _mm512_storeu_si512(s, lo);
        _mm512_storeu_si512(s + 8, hi);
    }
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
        return mul(toFloat(_mm512_inserti64x4(_mm512_castsi256_si512(a), b, 1)), bc(0x1.0p-24f));
    }
};
#elif defined(__AVX2__)
/// Two halves of 8 lanes.
struct F {
    __m256 lo, hi;
};
struct I {
    __m256i lo, hi;
};
/// The lanes of an 8-bit mask as a vector mask (all ones where set).
inline __m256i laneMask(M bits) {
    const __m256i b = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    return _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(bits & 0xFFu)), b), b);
}
inline F bc(float v) { return {_mm256_set1_ps(v), _mm256_set1_ps(v)}; }
inline F bcBits(uint32_t v) {
    const __m256 b = _mm256_castsi256_ps(_mm256_set1_epi32(int(v)));
    return {b, b};
}
inline F zeroF() { return {_mm256_setzero_ps(), _mm256_setzero_ps()}; }
inline F add(F a, F b) { return {_mm256_add_ps(a.lo, b.lo), _mm256_add_ps(a.hi, b.hi)}; }
inline F sub(F a, F b) { return {_mm256_sub_ps(a.lo, b.lo), _mm256_sub_ps(a.hi, b.hi)}; }
inline F mul(F a, F b) { return {_mm256_mul_ps(a.lo, b.lo), _mm256_mul_ps(a.hi, b.hi)}; }
inline F div(F a, F b) { return {_mm256_div_ps(a.lo, b.lo), _mm256_div_ps(a.hi, b.hi)}; }
inline F sqrtF(F a) { return {_mm256_sqrt_ps(a.lo), _mm256_sqrt_ps(a.hi)}; }
inline F bitsOr(F a, F b) { return {_mm256_or_ps(a.lo, b.lo), _mm256_or_ps(a.hi, b.hi)}; }
inline F bitsAnd(F a, F b) { return {_mm256_and_ps(a.lo, b.lo), _mm256_and_ps(a.hi, b.hi)}; }
inline F bitsXor(F a, F b) { return {_mm256_xor_ps(a.lo, b.lo), _mm256_xor_ps(a.hi, b.hi)}; }
inline F loadF(const float* p) { return {_mm256_load_ps(p), _mm256_load_ps(p + 8)}; }
inline void storeF(float* p, F v) {
    _mm256_store_ps(p, v.lo);
    _mm256_store_ps(p + 8, v.hi);
}
inline void storeF(float* p, M m, F v) {
    _mm256_maskstore_ps(p, laneMask(m), v.lo);
    _mm256_maskstore_ps(p + 8, laneMask(m >> 8), v.hi);
}
template <int kOp>
inline M cmp(F a, F b) {
    return M(_mm256_movemask_ps(_mm256_cmp_ps(a.lo, b.lo, kOp))) | M(_mm256_movemask_ps(_mm256_cmp_ps(a.hi, b.hi, kOp))) << 8;
}
inline F blend(M m, F a, F b) {  ///< b where m, else a
    return {_mm256_blendv_ps(a.lo, b.lo, _mm256_castsi256_ps(laneMask(m))),
            _mm256_blendv_ps(a.hi, b.hi, _mm256_castsi256_ps(laneMask(m >> 8)))};
}
inline F toFloat(I a) { return {_mm256_cvtepi32_ps(a.lo), _mm256_cvtepi32_ps(a.hi)}; }
inline I bci(int v) { return {_mm256_set1_epi32(v), _mm256_set1_epi32(v)}; }
inline I loadI(const void* p) {
    const __m256i* q = static_cast<const __m256i*>(p);
    return {_mm256_load_si256(q), _mm256_load_si256(q + 1)};
}
inline void storeI(void* p, I v) {
    __m256i* q = static_cast<__m256i*>(p);
    _mm256_store_si256(q, v.lo);
    _mm256_store_si256(q + 1, v.hi);
}
inline I addI(I a, I b) { return {_mm256_add_epi32(a.lo, b.lo), _mm256_add_epi32(a.hi, b.hi)}; }
inline I mulI(I a, I b) { return {_mm256_mullo_epi32(a.lo, b.lo), _mm256_mullo_epi32(a.hi, b.hi)}; }
inline M maskOf(__m256i lo, __m256i hi) {
    return M(_mm256_movemask_ps(_mm256_castsi256_ps(lo))) | M(_mm256_movemask_ps(_mm256_castsi256_ps(hi))) << 8;
}
inline M neI(I a, I b) { return notm(maskOf(_mm256_cmpeq_epi32(a.lo, b.lo), _mm256_cmpeq_epi32(a.hi, b.hi))); }
inline M ltI(I a, I b) { return maskOf(_mm256_cmpgt_epi32(b.lo, a.lo), _mm256_cmpgt_epi32(b.hi, a.hi)); }
inline I gatherI(I src, M m, I index, const int* base) {
    return {_mm256_mask_i32gather_epi32(src.lo, base, index.lo, laneMask(m), 4),
            _mm256_mask_i32gather_epi32(src.hi, base, index.hi, laneMask(m >> 8), 4)};
}
inline F gatherF(F src, M m, I index, const float* base) {
    return {_mm256_mask_i32gather_ps(src.lo, base, index.lo, _mm256_castsi256_ps(laneMask(m)), 4),
            _mm256_mask_i32gather_ps(src.hi, base, index.hi, _mm256_castsi256_ps(laneMask(m >> 8)), 4)};
}
inline void storeValid(int* valid, M m) {
    __m256i* q = reinterpret_cast<__m256i*>(valid);
    _mm256_store_si256(q, laneMask(m));
    _mm256_store_si256(q + 1, laneMask(m >> 8));
}

/// The 16 paths' Rng counters (Rng::uniform()), four lanes per register.
struct Rngs {
    __m256i r[4];
    explicit Rngs(const uint64_t* s) {
        for (int k = 0; k < 4; ++k) r[k] = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(s + 4 * k));
    }
    void store(uint64_t* s) const {
        for (int k = 0; k < 4; ++k) _mm256_storeu_si256(reinterpret_cast<__m256i*>(s + 4 * k), r[k]);
    }
    /// The low 64 bits of a · b per 64-bit lane (AVX2 multiplies 32 × 32 → 64 bits only).
    static __m256i mul64(__m256i a, __m256i b) {
        const __m256i cross = _mm256_add_epi64(_mm256_mul_epu32(a, _mm256_srli_epi64(b, 32)),
                                               _mm256_mul_epu32(_mm256_srli_epi64(a, 32), b));
        return _mm256_add_epi64(_mm256_mul_epu32(a, b), _mm256_slli_epi64(cross, 32));
    }
    static __m256i mix64(__m256i z) {
        z = mul64(_mm256_xor_si256(z, _mm256_srli_epi64(z, 30)), _mm256_set1_epi64x(int64_t(0xBF58476D1CE4E5B9ULL)));
        z = mul64(_mm256_xor_si256(z, _mm256_srli_epi64(z, 27)), _mm256_set1_epi64x(int64_t(0x94D049BB133111EBULL)));
        return _mm256_xor_si256(z, _mm256_srli_epi64(z, 31));
    }
    /// Rng::uniform() in the lanes of `m`; the other lanes neither draw nor advance.
    F uniform(M m) {
        const __m256i gamma = _mm256_set1_epi64x(int64_t(0x9E3779B97F4A7C15ULL));
        const __m256i bit = _mm256_setr_epi64x(1, 2, 4, 8);
        const __m256i low = _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6);
        __m128i top[4];
        for (int k = 0; k < 4; ++k) {
            const __m256i lanes = _mm256_cmpeq_epi64(_mm256_and_si256(_mm256_set1_epi64x(int64_t((m >> (4 * k)) & 0xFu)), bit), bit);
            r[k] = _mm256_add_epi64(r[k], _mm256_and_si256(gamma, lanes));
            // float(nextU32() >> 8) · 2^-24: the top 24 bits of mix64, exact as an int32 and as a float.
            top[k] = _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(_mm256_srli_epi64(mix64(r[k]), 40), low));
        }
        const I both{_mm256_set_m128i(top[1], top[0]), _mm256_set_m128i(top[3], top[2])};
        return mul(toFloat(both), bc(0x1.0p-24f));
    }
};
#else
#error "path_lanes.inl needs AVX2 or AVX-512F"
#endif

inline F neg(F a) { return bitsXor(a, bc(-0.f)); }
inline F absf(F a) { return bitsAnd(a, bcBits(0x7FFFFFFFu)); }
/// The C comparisons (false when either side is NaN).
inline M lt(F a, F b) { return cmp<_CMP_LT_OQ>(a, b); }
inline M le(F a, F b) { return cmp<_CMP_LE_OQ>(a, b); }
inline M gt(F a, F b) { return cmp<_CMP_GT_OQ>(a, b); }
inline M ge(F a, F b) { return cmp<_CMP_GE_OQ>(a, b); }
inline M eq(F a, F b) { return cmp<_CMP_EQ_OQ>(a, b); }
/// std::max(a, b): a unless a < b.
inline F maxStd(F a, F b) { return blend(lt(a, b), a, b); }

struct V3 {
    F x, y, z;
};
inline V3 bc3(const float* v) { return {bc(v[0]), bc(v[1]), bc(v[2])}; }
inline V3 load(const Lanes3& l) { return {loadF(l.x), loadF(l.y), loadF(l.z)}; }
inline void store(Lanes3& l, M m, const V3& v) {
    storeF(l.x, m, v.x);
    storeF(l.y, m, v.y);
    storeF(l.z, m, v.z);
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
    const F z = zeroF();
    return eq(v.x, z) & eq(v.y, z) & eq(v.z, z);
}
inline V3 select(M m, const V3& a, const V3& b) { return {blend(m, a.x, b.x), blend(m, a.y, b.y), blend(m, a.z, b.z)}; }

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

/// Embree's 16-wide rays from origins, directions and tmax (tmin 0); valid = the lanes of `m`.
inline void packRays(RTCRay16& r, int* valid, M m, const V3& o, const V3& d, F tmax) {
    storeF(r.org_x, o.x);
    storeF(r.org_y, o.y);
    storeF(r.org_z, o.z);
    storeF(r.dir_x, d.x);
    storeF(r.dir_y, d.y);
    storeF(r.dir_z, d.z);
    storeF(r.tnear, zeroF());
    storeF(r.tfar, tmax);
    storeF(r.time, zeroF());
    storeI(r.mask, bci(-1));
    for (int i = 0; i < kLanes; ++i) r.id[i] = unsigned(i);
    storeI(r.flags, bci(0));
    storeValid(valid, m);
}

/// intersectAreaLight() in the lanes of `m` (origin o, direction d, from tmin to tmax); `t` where it
/// hits.
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
        RTCIntersectContext ctx = *s.context;
        rtcOccluded16(valid, s.scene, &ctx, &ray);
        blocked = needsRay & lt(loadF(ray.tfar), zero);  // Embree sets tfar = -inf on a hit
        F t;
        if (s.movable) blocked |= hitsMovable(*s.movable, needsRay & notm(blocked), origin, dir, zero, tmax, t);
        shadowRays += uint64_t(__builtin_popcount(needsRay));
    }
    const M adds = ok & notm(blocked);
    sum = select(adds, sum, add(sum, c));
}

/// withMovableLight(), Accel::fillHit(), arrive() and enter() for the bounce rays of `bounced`
/// (origin o, direction d, from tmin to tmax) that Embree traced into out.next; returns the lanes
/// live at the new vertex, whose state it stores in L. With kEmission, emissionSeen() too.
template <bool kEmission>
inline M arrive(const Setup& s, M bounced, const V3& o, const V3& d, F tmin, F tmax, Step& out, PathLanes& L) {
    const F zero = zeroF();
    const I geom = loadI(out.next.hit.geomID);
    const M found = bounced & neI(geom, bci(int(RTC_INVALID_GEOMETRY_ID)));
    const F tfar = loadF(out.next.ray.tfar);
    F tMovable = zero;
    const M movable = s.movable ? hitsMovable(*s.movable, bounced, o, d, tmin, blend(found, tmax, tfar), tMovable) : M(0);
    const I base = gatherI(bci(0), found, geom, s.geomNormalBase);
    out.resolve = found & notm(movable) & ltI(base, bci(0));
    const M flat = found & notm(movable) & notm(out.resolve);
    const F t = blend(movable, tfar, tMovable);
    const V3 p = add(o, mul(d, t));
    const I prim3 = mulI(addI(base, loadI(out.next.hit.primID)), bci(3));
    static const float kNone[3] = {0.f, 0.f, 0.f};
    V3 ng = bc3(s.movable ? s.movable->normal : kNone);  // the movable light's lanes keep it
    ng.x = gatherF(ng.x, flat, prim3, s.normals);
    ng.y = gatherF(ng.y, flat, addI(prim3, bci(1)), s.normals);
    ng.z = gatherF(ng.z, flat, addI(prim3, bci(2)), s.normals);
    const I material = gatherI(bci(s.movable ? s.movable->material : -1), flat, geom, s.geomMaterial);
    M live = (flat | movable) & notm(ltI(material, bci(0)));
    const F side = dot(V3{neg(d.x), neg(d.y), neg(d.z)}, ng);
    live &= notm(eq(side, zero));
    const M front = gt(side, zero);
    const V3 n = select(front, V3{neg(ng.x), neg(ng.y), neg(ng.z)}, ng);
    if constexpr (kEmission) {
        // Light::emittedTowards(wo), wo = -d, for the lanes that see an emitter.
        const I light = gatherI(bci(-1), flat, geom, s.geomLight);
        const M fromTable = flat & notm(ltI(light, bci(0)));
        if (fromTable | movable) {
            const I l3 = mulI(light, bci(3));
            const V3 wo{neg(d.x), neg(d.y), neg(d.z)};
            const float* mr = s.movable ? s.movable->radiance : kNone;
            const float* mn = s.movable ? s.movable->n : kNone;
            const V3 radiance{gatherF(bc(mr[0]), fromTable, l3, s.lightRadiance),
                              gatherF(bc(mr[1]), fromTable, addI(l3, bci(1)), s.lightRadiance),
                              gatherF(bc(mr[2]), fromTable, addI(l3, bci(2)), s.lightRadiance)};
            const V3 nl{gatherF(bc(mn[0]), fromTable, l3, s.lightNormal),
                        gatherF(bc(mn[1]), fromTable, addI(l3, bci(1)), s.lightNormal),
                        gatherF(bc(mn[2]), fromTable, addI(l3, bci(2)), s.lightNormal)};
            const I oneSided = gatherI(bci(s.movable ? s.movable->oneSided : 0), fromTable, light, s.lightOneSided);
            const M dark = ltI(bci(0), oneSided) & le(dot(wo, nl), zero);
            const M seen = (fromTable | movable) & notm(dark);
            store(L.direct, seen, add(load(L.direct), radiance));
        }
    }
    const I m3 = mulI(material, bci(3));
    const V3 kd{gatherF(zero, live, m3, s.materialKd), gatherF(zero, live, addI(m3, bci(1)), s.materialKd),
                gatherF(zero, live, addI(m3, bci(2)), s.materialKd)};
    store(L.p, live, p);
    store(L.ng, live, ng);
    store(L.n, live, n);
    store(L.kd, live, kd);
    storeF(L.side, live, side);
    L.smooth &= notm(live);
    return live;
}

}  // namespace

void step(const Setup& s, PathLanes& L, Step& out) {
    const M live = M(L.live) & kAllLanes;
    const F zero = zeroF();
    const F sceneScale = bc(s.sceneScale);
    const V3 p = load(L.p), ng = load(L.ng), n = load(L.n), kd = load(L.kd);
    Rngs rng(L.rng);

    // NEE (lightSamples() of a diffuse vertex, then directLight()'s sum).
    const F ngSide = dot(n, ng);
    const V3 f = mul(kd, bc(0.31830988618379067154f));  // kd · kInvPi
    const M fNonZero = notm(isZero(f));
    V3 sum{zero, zero, zero};
    uint64_t shadowRays = 0;
    for (int k = 0; k < s.rectCount; ++k) {
        const RectLight& l = s.rect[k];
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
        addVisible(s, ok, p, ng, ngSide, wi, x, c, sceneScale, sum, shadowRays);
    }
    for (int k = 0; k < s.pointCount; ++k) {
        const PointLight& l = s.point[k];
        const V3 pos = bc3(l.position);
        const V3 d = sub(pos, p);
        const F dist2 = dot(d, d);
        M ok = live & gt(dist2, zero);
        const V3 wi = div(d, sqrtF(dist2));
        const F cosTheta = dot(wi, n);
        ok &= notm(le(cosTheta, zero)) & fNonZero;
        if (!ok) continue;
        const V3 c = mul(mul(bc3(l.intensity), f), div(cosTheta, dist2));
        addVisible(s, ok, p, ng, ngSide, wi, pos, c, sceneScale, sum, shadowRays);
    }
    Lanes3& target = L.depth == 0 ? L.direct : L.indirect;
    store(target, live, add(load(target), mul(load(L.beta), sum)));
    out.shadowRays = shadowRays;

    // The bounce (bounceRay() of a diffuse vertex).
    out.bounced = out.resolve = 0;
    M next = 0;
    if (s.bounces && live) {
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
        ok &= notm(M(L.smooth) & le(mul(dot(wi, ng), loadF(L.side)), zero));
        V3 beta = mul(load(L.beta), kd);
        if (L.depth >= 1) {
            const F q0 = maxStd(beta.x, maxStd(beta.y, beta.z));
            const F q = blend(lt(q0, bc(0.05f)), blend(lt(bc(1.f), q0), q0, bc(1.f)), bc(0.05f));  // std::clamp
            const M roulette = ok & lt(q, bc(1.f));
            const F u = rng.uniform(roulette);
            ok &= notm(roulette & ge(u, q));
            beta = select(roulette, beta, div(beta, q));
        }
        ok &= notm(isZero(beta));
        store(L.beta, live, beta);
        if (ok) {
            const V3 origin = spawnOrigin(p, ng, wi, sceneScale);
            alignas(64) int valid[kLanes];
            packRays(out.next.ray, valid, ok, origin, wi, bc(INFINITY));
            storeI(out.next.hit.geomID, bci(int(RTC_INVALID_GEOMETRY_ID)));
            storeI(out.next.hit.instID[0], bci(int(RTC_INVALID_GEOMETRY_ID)));
            RTCIntersectContext ctx = *s.context;
            rtcIntersect16(valid, s.scene, &ctx, &out.next);
            out.bounced = ok;
            next = arrive<false>(s, ok, origin, wi, zero, bc(INFINITY), out, L);
        }
    }
    L.live = next;
    rng.store(L.rng);
}

void start(const Setup& s, PathLanes& L, Step& out) {
    const M live = M(L.live) & kAllLanes;
    alignas(64) int valid[kLanes];
    storeValid(valid, live);
    const V3 o{loadF(out.next.ray.org_x), loadF(out.next.ray.org_y), loadF(out.next.ray.org_z)};
    const V3 d{loadF(out.next.ray.dir_x), loadF(out.next.ray.dir_y), loadF(out.next.ray.dir_z)};
    const F tmin = loadF(out.next.ray.tnear), tmax = loadF(out.next.ray.tfar);  // Embree changes tfar
    storeI(out.next.hit.geomID, bci(int(RTC_INVALID_GEOMETRY_ID)));
    storeI(out.next.hit.instID[0], bci(int(RTC_INVALID_GEOMETRY_ID)));
    RTCIntersectContext ctx = *s.cameraContext;
    rtcIntersect16(valid, s.scene, &ctx, &out.next);
    out.bounced = live;
    out.resolve = 0;
    out.shadowRays = 0;
    L.live = arrive<true>(s, live, o, d, tmin, tmax, out, L);
}

}  // namespace rrf::path_lanes::RRF_ISA
