#pragma once
/// Small 3-vector used throughout the renderer and the data generator.
/// Float storage (matches Embree's ray layout); accumulation happens in double elsewhere.

#include <algorithm>
#include <cmath>
#include <ostream>

// These one-line functions are always inlined. An inline function that a translation unit does not
// inline is emitted there out of line, and the linker keeps one such copy for the whole program:
// the test programs compile at -O0 (cmake/TestCode.cmake), so without this a library built with
// little inlining (the sanitizer build at -O1) called their unoptimised copies on its hot paths, and
// a copy from a kernel compiled for AVX2 could likewise end up called by the portable code.
#if defined(__GNUC__)
#define RRF_VEC_INLINE __attribute__((always_inline)) inline
#else
#define RRF_VEC_INLINE inline
#endif

namespace rrf {

struct Vec3 {
    float x = 0, y = 0, z = 0;

    constexpr Vec3() = default;
    RRF_VEC_INLINE constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
    RRF_VEC_INLINE constexpr explicit Vec3(float s) : x(s), y(s), z(s) {}

    RRF_VEC_INLINE constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    RRF_VEC_INLINE float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

    RRF_VEC_INLINE constexpr Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
    RRF_VEC_INLINE constexpr Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
    RRF_VEC_INLINE constexpr Vec3 operator*(const Vec3& o) const { return {x * o.x, y * o.y, z * o.z}; }
    RRF_VEC_INLINE constexpr Vec3 operator/(const Vec3& o) const { return {x / o.x, y / o.y, z / o.z}; }
    RRF_VEC_INLINE constexpr Vec3 operator*(float s) const { return {x * s, y * s, z * s}; }
    RRF_VEC_INLINE constexpr Vec3 operator/(float s) const { return {x / s, y / s, z / s}; }
    RRF_VEC_INLINE constexpr Vec3 operator-() const { return {-x, -y, -z}; }
    RRF_VEC_INLINE Vec3& operator+=(const Vec3& o) { x += o.x; y += o.y; z += o.z; return *this; }
    RRF_VEC_INLINE Vec3& operator-=(const Vec3& o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
    RRF_VEC_INLINE Vec3& operator*=(const Vec3& o) { x *= o.x; y *= o.y; z *= o.z; return *this; }
    RRF_VEC_INLINE Vec3& operator*=(float s) { x *= s; y *= s; z *= s; return *this; }
    RRF_VEC_INLINE constexpr bool operator==(const Vec3& o) const { return x == o.x && y == o.y && z == o.z; }
    RRF_VEC_INLINE constexpr bool operator!=(const Vec3& o) const { return !(*this == o); }

    RRF_VEC_INLINE constexpr float maxComponent() const { return std::max(x, std::max(y, z)); }
    RRF_VEC_INLINE constexpr float minComponent() const { return std::min(x, std::min(y, z)); }
    RRF_VEC_INLINE constexpr float sum() const { return x + y + z; }
    RRF_VEC_INLINE constexpr bool isZero() const { return x == 0 && y == 0 && z == 0; }
    RRF_VEC_INLINE bool isFinite() const { return std::isfinite(x) && std::isfinite(y) && std::isfinite(z); }
};

RRF_VEC_INLINE constexpr Vec3 operator*(float s, const Vec3& v) { return v * s; }
RRF_VEC_INLINE constexpr float dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
RRF_VEC_INLINE constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
RRF_VEC_INLINE float length(const Vec3& v) { return std::sqrt(dot(v, v)); }
RRF_VEC_INLINE constexpr float lengthSquared(const Vec3& v) { return dot(v, v); }
RRF_VEC_INLINE Vec3 normalize(const Vec3& v) { return v / length(v); }
RRF_VEC_INLINE Vec3 vmin(const Vec3& a, const Vec3& b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
RRF_VEC_INLINE Vec3 vmax(const Vec3& a, const Vec3& b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }
RRF_VEC_INLINE Vec3 vabs(const Vec3& a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }
/// Mirror direction of `w` about normal `n` (both pointing away from the surface).
RRF_VEC_INLINE constexpr Vec3 reflect(const Vec3& w, const Vec3& n) { return 2.f * dot(w, n) * n - w; }

inline std::ostream& operator<<(std::ostream& os, const Vec3& v) {
    return os << '(' << v.x << ", " << v.y << ", " << v.z << ')';
}

/// Orthonormal basis around a unit normal (Duff et al. 2017, branchless and robust).
struct Frame {
    Vec3 s, t, n;
    Frame() = default;
    RRF_VEC_INLINE explicit Frame(const Vec3& normal) : n(normal) {
        const float sign = std::copysign(1.0f, n.z);
        const float a = -1.0f / (sign + n.z);
        const float b = n.x * n.y * a;
        s = Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
        t = Vec3(b, sign + n.y * n.y * a, -n.y);
    }
    RRF_VEC_INLINE Vec3 toWorld(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
    RRF_VEC_INLINE Vec3 toLocal(const Vec3& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
};

/// Axis-aligned bounding box.
struct Bounds3 {
    Vec3 lo{INFINITY, INFINITY, INFINITY};
    Vec3 hi{-INFINITY, -INFINITY, -INFINITY};
    void expand(const Vec3& p) { lo = vmin(lo, p); hi = vmax(hi, p); }
    void expand(const Bounds3& b) { lo = vmin(lo, b.lo); hi = vmax(hi, b.hi); }
    bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
    Vec3 extent() const { return hi - lo; }
    Vec3 center() const { return (lo + hi) * 0.5f; }
    bool contains(const Vec3& p) const {
        return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
    }
};

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 0.31830988618379067154f;
constexpr float kInv2Pi = 0.15915494309189533577f;

}  // namespace rrf
