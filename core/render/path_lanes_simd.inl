// The 16 lanes of one instruction set for the path tracer's lanes (path_lanes.inl, which includes
// this inside its namespace): float lanes F, int lanes I, a bit mask M (bit i = lane i), and on top
// of them the 3-vectors V3. AVX-512 holds 16 lanes in one register; AVX2 in two halves of 8, its
// masks expanded to vectors where an instruction needs one and a 64-bit multiply built from 32-bit
// ones. Every operation is one IEEE operation per lane, so lanes compute what scalar code does.
// Included only by path_lanes.inl.

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
