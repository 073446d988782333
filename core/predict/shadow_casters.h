#pragma once
/// The occluders that can shadow one receiver's view of one area light, found once per receiver, so
/// that exact direct light (core/predict/exact_direct.h) traces its shadow rays only where their
/// answers are not known, and against only those occluders.
///
/// Every shadow ray of a receiver runs from one origin o (the receiver point, offset along its
/// normal) to a point of the light above the horizon, the convex polygon B of
/// core/predict/light_polygon.h; all of them lie in the pyramid hull(o, B). Occluders are convex
/// hulls: a closed convex object (a box, a convex mesh) is one hull, a sphere is itself, every other
/// object of at most 64 primitives is its convex primitives (a wall, the faces of an open mesh), a
/// light is its parallelogram or triangle — these are exact —, and what is left (a bigger mesh, a
/// non-convex quad) is bounded by its axis-aligned box (not exact). An occluder is a caster of the
/// receiver when the
/// separating-axis theorem (face normals of both, cross products of their edges; exact for two
/// convex polyhedra, conservative for the sphere) cannot separate it from the pyramid by a margin
/// 1e-5·(|o|∞ + scene scale), far above float rounding, so that every occluder it separates misses
/// every ray. The receiver's own object casts no shadow on it where it cannot: a convex solid or a
/// sphere lies behind the tangent plane when the point looks out of it (its centre behind the
/// normal), a primitive in the receiver's plane lies in it, and the pyramid is in front.
///
/// What the casters settle (Verdict):
///  - Unoccluded: none. Every ray is visible: R = 1 without rays.
///  - Occluded: one caster blocks the segments from o to every vertex of B within a fraction t*
///    of their length, from an origin outside it. For convex O the light points x whose segment
///    (o, x) meets O form a convex set, which then holds all of B, and every sample's segment meets O
///    within t* of its length (x = Σλ_k b_k gives the point o + (x − o)/Σ(λ_k/t_k) of O); t* is set
///    below the shortest fraction a sample ray keeps (stopped short of the light as PathTracer's
///    NEE). R = 0 without sample rays. Exact casters are tested directly; with inexact ones the proof
///    asks Embree for the closest hits, which must then lie on one convex part.
///  - Segments: a few exact casters. A shadow ray is blocked iff it meets one of them, which
///    blocked() answers by clipping the ray against each (slab planes of a solid, plane and edges of
///    a polygon, the sphere's quadratic): the answer Embree would give but for rounding at edges, at
///    a fraction of the cost of a traversal.
///  - Rays: anything else; the rays go to Embree.

#include <cstdint>
#include <vector>

#include "core/predict/light_polygon.h"
#include "core/render/path_tracer.h"

namespace rrf {

class ShadowCasters {
public:
    /// A convex occluder (or the box bounding one) in the form the tests need.
    struct Hull {
        enum class Kind { Solid, Polygon, Sphere, Bounds } kind = Kind::Bounds;
        std::vector<Vec3> vertices;
        std::vector<Vec3> axes;     ///< face normals (unit; either orientation) for the separating-axis test
        std::vector<Vec3> edges;    ///< edge directions (unit, parallel ones once)
        std::vector<Vec3> planeN;   ///< Solid: outward unit face normals; Polygon: [0] its normal, then inward edge normals
        std::vector<float> planeD;  ///< ... and offsets: n·x ≤ d inside a solid; Polygon: n·x = d, edges m·x ≥ d
        Bounds3 box;
        Vec3 center{0.f};  ///< Sphere: centre; Solid: vertex mean
        float radius = 0.f;  ///< Sphere: radius
        /// A sphere holding every vertex (the first, cheapest test against the pyramid's planes).
        Vec3 boundCenter{0.f};
        float boundRadius = 0.f;
        bool exact() const { return kind != Kind::Bounds; }
        /// True when x lies outside the solid or sphere by more than `margin`.
        bool outside(const Vec3& x, float margin) const;
        /// True when the ray meets the occluder within [ray.tmin, ray.tmax] (exact hulls only).
        bool blocks(const Ray& ray) const;
        /// blocks() for kBatch segments origin + s·(dx, dy, dz)_k, s ∈ [0, end_k], at once: the same
        /// tests written lane by lane so that the compiler vectorises them. blocked[k] |= the answer
        /// (−1 = blocked, 0 = not).
        void blocksBatch(const Vec3& origin, const float* dx, const float* dy, const float* dz, const float* end,
                         int32_t* blocked) const;
    };

    /// Segments per blocksBatch() call (ExactDirect's chunk of samples).
    static constexpr int kBatch = 16;

    static constexpr int kMaxSegmentCasters = 4;

    /// How one receiver's rays to one light are settled.
    /// Not copyable: hull[] may point at its own `movable`.
    struct Casters {
        Casters() = default;
        Casters(const Casters&) = delete;
        Casters& operator=(const Casters&) = delete;
        enum class Verdict { Unoccluded, Occluded, Segments, Rays } verdict = Verdict::Rays;
        int count = 0;                                ///< Segments: the casters in hull[0..count)
        const Hull* hull[kMaxSegmentCasters] = {};
        Hull movable;  ///< the movable light's hull when it is a caster of another light
    };

    /// Per verdict, how many (receiver, light) pairs got it (the benchmark's counts).
    struct Counts {
        uint64_t unoccluded = 0, occluded = 0, segments = 0, rays = 0;
        void add(const Counts& o);
    };

    /// Hulls of every object and every light of the tracer's scene. `tracer` must outlive this.
    explicit ShadowCasters(const PathTracer& tracer);

    /// The casters of the receiver on object `receiver` (normal `normal` on the side its rays leave
    /// from, rays from `origin`) for the light `light`, its part above the horizon being `base`
    /// (not empty), and the verdict above. `movable` is the movable light where it is now. Rays the
    /// proof asks Embree are counted in counters.shadowRays.
    void find(const Vec3& origin, const Vec3& normal, const ClippedLight& base, int receiver, int light,
              const Light& movable, TraceCounters& counters, Casters& out) const;

    /// Verdict Segments: blocked[k] = −1 where segment k (as Hull::blocksBatch) meets one of the
    /// casters, else 0.
    static void blocked(const Casters& c, const Vec3& origin, const float* dx, const float* dy, const float* dz,
                        const float* end, int32_t* blocked) {
        for (int k = 0; k < kBatch; ++k) blocked[k] = 0;
        for (int h = 0; h < c.count; ++h) c.hull[h]->blocksBatch(origin, dx, dy, dz, end, blocked);
    }

private:
    static Hull polygonHull(const Vec3* v, int count);
    static Hull boundsHull(const Bounds3& b);
    static void setBound(Hull& h);
    static bool separated(const Hull& h, const Vec3* pyramid, int count, const Vec3* faces, const Bounds3& pyramidBox,
                          float margin);
    /// Id of the convex part `hit` lies on, or −1 when it lies on a part that is not convex or is a
    /// solid the ray started inside.
    int64_t convexPart(const Hit& hit, const Vec3& origin, float margin) const;
    bool occludedByEmbree(const Vec3& origin, const ClippedLight& base, float tStar, float margin,
                          const Light& movable, TraceCounters& counters) const;

    struct Entry {
        Hull hull;
        int object;
    };

    const PathTracer& tracer_;
    float sceneScale_;
    std::vector<Entry> hulls_;                   ///< every object's hulls
    std::vector<Hull> lightHulls_;               ///< per light (empty for point lights)
    std::vector<int> solidIndex_;                ///< per object: its Solid or Sphere hull in hulls_, or −1
    std::vector<std::vector<char>> convexPrim_;  ///< per object and primitive: a convex polygon
};

}  // namespace rrf
