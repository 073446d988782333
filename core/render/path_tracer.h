#pragma once
/// Monte Carlo path tracer producing the two training targets separately:
///
///   direct   = emission seen directly + light reaching the eye after exactly one reflection
///   indirect = light reaching the eye after two or more reflections
///   global   = direct + indirect
///
/// Two estimators (docs/design.md §4–§5). `NEE`: direct light by light sampling only (uniform
/// points on each rect light with pdf 1/area — not the seed report's 2/|v1×v2|, which is a
/// triangle's pdf —, one point for all triangle lights together, the triangle picked by area, and
/// point lights), indirect light by BRDF sampling with Russian roulette; emission hit by BRDF rays is
/// ignored because NEE already counted it — except in scenes with glossy materials, where a Phong
/// lobe of exponent 1000 turns light sampling into fireflies: there the light sample and the BRDF ray
/// that hits an area light are combined with the power heuristic (multiple importance sampling,
/// Veach 1997 §9.2), each weighted by p²/(p_light² + p_brdf²) in solid angle, whenever the vertex goes
/// on to bounce (otherwise the light sample keeps weight 1). `Naive`: BRDF sampling only, emission
/// counted when a ray hits an emitter (point lights are invisible to it). Both converge to the same
/// image.

#include <atomic>
#include <cstdint>
#include <vector>

#include "core/scene/accel.h"
#include "core/render/brdf.h"
#include "core/render/path_lanes.h"
#include "core/scene/effects.h"
#include "core/render/render_settings.h"
#include "core/util/rng.h"

namespace rrf {

struct Radiance {
    Vec3 direct{0.f};
    Vec3 indirect{0.f};
    Vec3 global() const { return direct + indirect; }
};

/// Per-thread ray statistics (summed by the caller).
struct TraceCounters {
    uint64_t rays = 0;        ///< closest-hit queries (primary and bounce rays)
    uint64_t shadowRays = 0;  ///< occlusion queries
    /// Optional logs of every query, so a benchmark can replay the tracer's own ray distribution
    /// through plain Embree calls. Null (the default) costs one predictable branch per ray.
    std::vector<Ray>* rayLog = nullptr;
    std::vector<Ray>* shadowRayLog = nullptr;
};

/// An area light's edges and normal as the ray test against the movable light uses them, derived once
/// per light rather than once per ray (the same values the test computed per ray). Moving the light
/// changes only its corner, so one shape serves the light wherever it is moved (shapeOf()).
struct AreaLightShape {
    Vec3 edge1, edge2;
    Vec3 n;          ///< cross(edge1, edge2), not normalised
    float nn = 0.f;  ///< dot(n, n)
    bool triangle = false;

    AreaLightShape() = default;
    explicit AreaLightShape(const Light& l)
        : edge1(l.edge1), edge2(l.edge2), n(cross(l.edge1, l.edge2)), nn(dot(n, n)),
          triangle(l.type == Light::Type::Triangle) {}
    /// Whether this is the shape of `l` (its edges and type), wherever `l`'s corner is.
    bool isShapeOf(const Light& l) const {
        return triangle == (l.type == Light::Type::Triangle) && edge1 == l.edge1 && edge2 == l.edge2;
    }
};

class PathTracer {
public:
    /// `scene` and `accel` must outlive the tracer.
    PathTracer(const Scene& scene, const Accel& accel, Estimator estimator, int maxDepth = 64);

    /// Radiance arriving at ray.origin from direction −ray.dir, with the movable light where the
    /// scene puts it.
    Radiance trace(const Ray& ray, Rng& rng, TraceCounters& counters) const {
        return trace(ray, movableDefault_, rng, counters);
    }
    /// Same, with the movable light replaced by `movable` (from movableLightAt()).
    Radiance trace(const Ray& ray, const Light& movable, Rng& rng, TraceCounters& counters) const;
    /// trace() for `count` ≤ Accel::kPacket camera rays at once, with the movable light where the scene
    /// puts it: out[i] = trace(rays[i], rngs[i], counters). The paths advance in lockstep over their
    /// first vertices, their rays going to Embree as packets (the camera rays as a coherent one, from
    /// one origin), and then one by one; each path keeps its own random numbers and trace()'s
    /// arithmetic, so the results are trace()'s up to the edge cases in which a packet and a single
    /// ray disagree.
    void traceBatch(const Ray* rays, Rng* rngs, int count, TraceCounters& counters, Radiance* out) const;
    /// Radiance leaving the surface point `hit` towards `wo` (unit, pointing away from the surface).
    /// Used by the data generator, which shoots each record's first ray once and estimates many paths.
    Radiance shade(const Hit& hit, const Vec3& wo, Rng& rng, TraceCounters& counters) const {
        return shade(hit, wo, movableDefault_, rng, counters);
    }
    Radiance shade(const Hit& hit, const Vec3& wo, const Light& movable, Rng& rng, TraceCounters& counters) const;
    /// shade() for `count` ≤ Accel::kPacket paths from the same vertex: out[i] = shade(hit, wo,
    /// movable, rngs[i], counters), the data generator's paths of one record. Their first vertices
    /// run in the SIMD lanes where traceBatch()'s do (lanes()), with `movable` a move of the scene's
    /// movable light, for batches large enough to fill them; the results are shade()'s either way.
    void shadeBatch(const Hit& hit, const Vec3& wo, const Light& movable, Rng* rngs, int count, TraceCounters& counters,
                    Radiance* out) const;

    /// Closest hit against the static BVH and the movable light (if it is an area light).
    bool intersect(const Ray& ray, const Light& movable, Hit& hit) const;
    bool intersect(const Ray& ray, Hit& hit) const { return intersect(ray, movableDefault_, hit); }
    /// True if anything (static geometry or the movable area light) lies along `ray` in
    /// [tmin, tmax]: the shadow-ray test of NEE, also used by exact direct light in prediction.
    bool occluded(const Ray& ray, const Light& movable) const;
    /// occluded() for `count` ≤ Accel::kPacket rays at once, the static scene as one Embree packet
    /// (Accel::occludedPacket): blocked[i] = occluded(rays[i], movable).
    void occludedPacket(const Ray* rays, int count, const Light& movable, bool* blocked) const;
    /// Copy of the movable light with its centre at `p` (shape and emission unchanged).
    Light movableLightAt(const Vec3& p) const;

    const Effects& effects() const { return effects_; }
    Estimator estimator() const { return estimator_; }
    /// The BRDF of material `material` (an index into Scene::materials).
    const Brdf& brdf(int material) const { return brdfs_[size_t(material)]; }
    /// Material of what `hit` hit (an object's, or an emitter's: -1 for a black emitter).
    int materialOf(const Hit& hit) const;
    /// Light `index` of the scene, with the movable one replaced by `movable`.
    const Light& light(int index, const Light& movable) const {
        return index == movable_ ? movable : scene_.lights[size_t(index)];
    }
    const Accel& accel() const { return accel_; }
    const Scene& scene() const { return scene_; }
    /// The SIMD lanes traceBatch() runs its lockstep vertices as (render/path_lanes.h): the widest the
    /// build and CPU have, for NEE in a scene without glossy materials or triangle lights; None (the
    /// portable lockstep) otherwise. Either way the results are trace()'s.
    path_lanes::Isa lanes() const { return lanes_; }
    /// Chooses the lanes (None: the portable lockstep) where this tracer can run them; otherwise
    /// the portable lockstep stays. For comparing them (tests, bench_render).
    void setLanes(path_lanes::Isa isa);

private:
    /// The path-tracing loop in steps (one vertex's setup, its light samples, its bounce), so that
    /// trace(), shade() and traceBatch() share them (path_tracer.cpp).
    struct Impl;

    const Scene& scene_;
    const Accel& accel_;
    Estimator estimator_;
    int maxDepth_;
    Effects effects_;
    std::vector<Brdf> brdfs_;
    std::vector<int> rectLights_, pointLights_, triangleLights_;
    std::vector<double> triangleCdf_;  ///< running sum of the triangle lights' areas
    double triangleArea_ = 0.0;        ///< total area of the triangle lights
    int movable_ = -1;       ///< index of the movable light, -1 if the scene has none
    Light movableDefault_;   ///< the movable light where the scene puts it
    AreaLightShape movableShape_;  ///< movableDefault_'s shape (the same wherever it is moved)
    path_lanes::Isa lanes_ = path_lanes::Isa::None;  ///< lanes()
    path_lanes::Kernels lanesKernels_;               ///< lanes_'s, null for the portable lockstep
    bool lanesPossible_ = false;  ///< whether the scene and estimator allow the lanes
    /// What the lanes read (path_tracer_lanes.cpp): lights, materials and geometry as plain arrays,
    /// the movable light where the scene puts it.
    struct LaneTables {
        std::vector<path_lanes::RectLight> rects;       ///< rectLights_, in order
        std::vector<path_lanes::PointLight> points;     ///< pointLights_, in order
        path_lanes::MovableLight movable{};             ///< movableDefault_ and its shape
        int movableRect = -1;                           ///< the movable light's entry in rects
        std::vector<float> kd;                          ///< kd of brdfs_, x, y, z per material
        std::vector<int> geomMaterial;                  ///< material by Embree geomID (Accel::GeometryTable)
        std::vector<float> lightRadiance, lightNormal;  ///< x, y, z per Scene light (normal: e1 × e2)
        std::vector<int> lightOneSided;                 ///< per Scene light
    };
    LaneTables laneTables_;

    /// The shape of `movable` for the ray test: movableShape_ for the movable light wherever it was
    /// moved (movableLightAt: same edges), derived into `scratch` for any other light. Every ray of
    /// a training record and of a BDPT render asks, so the common case neither derives the shape
    /// again nor copies it (a struct built per ray and read back at once stalls on the store).
    const AreaLightShape& shapeOf(const Light& movable, AreaLightShape& scratch) const {
        if (&movable == &movableDefault_ || movableShape_.isShapeOf(movable)) return movableShape_;
        scratch = AreaLightShape(movable);
        return scratch;
    }
};

}  // namespace rrf
