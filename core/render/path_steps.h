#pragma once
/// The steps of PathTracer's path loop (struct PathTracer::Impl): included by path_tracer.cpp only,
/// which runs them one path at a time (trace(), shade()) or for a batch of paths in lockstep
/// (traceBatch()).

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/render/path_tracer.h"

namespace rrf {

namespace {
/// Ray intersection with an area light (corner + s·e1 + t·e2: s,t ∈ [0,1] for a rect, s,t ≥ 0 and
/// s+t ≤ 1 for a triangle) in (tmin, tmax). Every ray of the tracer meets this test, so the shape
/// comes precomputed (AreaLightShape), and the second barycentric is only computed when the first
/// one is inside: the same arithmetic in the same order as computing both, so the same answers.
bool intersectAreaLight(const Ray& ray, const Vec3& corner, const AreaLightShape& l, float tmax, float& t) {
    const float denom = dot(ray.dir, l.n);
    if (denom == 0.f) return false;
    t = dot(corner - ray.origin, l.n) / denom;
    if (!(t > ray.tmin && t < tmax)) return false;
    const Vec3 q = ray.origin + ray.dir * t - corner;
    const float a = dot(cross(q, l.edge2), l.n) / l.nn;
    if (!(a >= 0.f) || (!l.triangle && !(a <= 1.f))) return false;
    const float b = dot(cross(l.edge1, q), l.n) / l.nn;
    if (l.triangle) return b >= 0.f && a + b <= 1.f;
    return b >= 0.f && b <= 1.f;
}

/// Power-heuristic weight (β = 2) of the strategy with pdf `p` against the one with pdf `other`
/// (both in solid angle); 0 when `p` is 0 or either pdf is not finite.
float powerHeuristic(float p, float other) {
    const float p2 = p * p, o2 = other * other;
    const float w = p2 / (p2 + o2);
    return std::isfinite(w) ? w : 0.f;
}


/// The closest hit of `ray` once the movable light (scene light `movableIndex`, -1 for none) joins
/// the static scene's answer (`found`, `hit`); `shape` is the movable light's.
bool withMovableLight(const Ray& ray, const Light& movable, const AreaLightShape& shape, int movableIndex, bool found,
                      Hit& hit) {
    float t;
    if (movableIndex >= 0 && movable.isArea() && intersectAreaLight(ray, movable.corner, shape, found ? hit.t : ray.tmax, t)) {
        hit = Hit{};
        hit.t = t;
        hit.p = ray.origin + ray.dir * t;
        hit.ng = movable.normal();
        hit.light = movableIndex;
        found = true;
    }
    return found;
}
}  // namespace

/// The path-tracing loop of trace() and shade(), cut into the steps that traceBatch() runs for
/// several paths at once. A path carries one Rng, and every step draws its numbers from it in the
/// order of the plain loop, so batching changes no random number.
struct PathTracer::Impl {
    /// A path at a surface vertex: its radiance so far, its throughput, and the vertex's frame.
    struct Vertex {
        Radiance L;
        Vec3 beta{1.f};
        Hit hit;
        Vec3 wo;  ///< towards where the path came from
        int depth = 0;
        // Set by enter():
        const Brdf* brdf = nullptr;
        float side = 0.f;
        Vec3 n;
        Frame frame;
        Vec3 woLocal;
        bool bounces = false, mis = false;
        Vec3& target() { return depth == 0 ? L.direct : L.indirect; }
    };

    /// Sets up the vertex at v.hit; false when the path ends there (black emitter, exactly grazing).
    template <bool kGlossy>
    static bool enter(const PathTracer& t, Vertex& v) {
        const int mat = t.materialOf(v.hit);
        if (mat < 0) return false;
        v.brdf = &t.brdfs_[size_t(mat)];
        v.side = dot(v.wo, v.hit.ng);
        if (v.side == 0.f) return false;  // exactly grazing: no reflection
        // Two-sided surfaces: shade the side we see (decided by the geometric normal; the shading
        // normal is on ng's side).
        const Vec3 ns = v.hit.shading();
        v.n = v.side > 0.f ? ns : -ns;
        v.frame = Frame(v.n);
        v.woLocal = v.frame.toLocal(v.wo);
        // Bounce: always for the naive estimator's first reflection (that is its direct light), and
        // beyond that only if the scene lets light travel between surfaces. NEE at depth d already
        // accounts for paths of d+1 reflections; the naive estimator needs the bounce at depth d to
        // see them, so for it the depth limit applies after the emission test in scatter().
        const bool nee = t.estimator_ == Estimator::NEE;
        v.bounces = nee ? v.depth + 1 < t.maxDepth_ && t.effects_.indirect : v.depth == 0 || t.effects_.indirect;
        v.mis = kGlossy && nee && v.bounces;
        return true;
    }

    /// Light sampling at vertex `v` (NEE). For each light sample that can contribute, calls
    /// emit(needsRay, shadowRay, contribution): the sample adds contribution() unless needsRay and
    /// shadowRay is occluded. Samples are emitted in the order their sum is taken. When the vertex
    /// goes on to bounce in a glossy scene (v.mis), its light samples share the lights with the BRDF
    /// ray (power heuristic, see path_tracer.h).
    template <bool kGlossy, class Emit>
    static void lightSamples(const PathTracer& t, const Vertex& v, const Light& movable, Rng& rng,
                             TraceCounters& counters, Emit&& emit) {
        const Vec3& p = v.hit.p;
        const Vec3& ng = v.hit.ng;
        const Vec3& n = v.n;
        const Brdf& brdf = *v.brdf;
        const bool brdfRayFollows = v.mis;
        auto evalBrdf = [&](const Vec3& wi) -> Vec3 {
            if constexpr (kGlossy) return brdf.eval(v.woLocal, v.frame.toLocal(wi));
            else return brdf.kd * kInvPi;
        };
        // Same for light samples: below the geometric surface means behind it, whatever the shading
        // normal says (for flat surfaces n = ±ng, and cos θ > 0 already implies this).
        const float ngSide = dot(n, ng);
        // Emits the sample towards light point `target` if it lies above the surface.
        auto visible = [&](const Vec3& wi, const Vec3& target, auto&& contribution) {
            if (dot(wi, ng) * ngSide <= 0.f) return;
            Ray s;
            s.origin = t.accel_.spawnOrigin(p, ng, wi);
            const Vec3 d = target - s.origin;
            const float dist = length(d);
            // Stop short of the target so the light's own quad does not occlude its sample point.
            s.tmax = dist * (1.f - 1e-4f) - t.accel_.offset(target);
            if (!(s.tmax > 0.f)) {  // nothing fits between the point and the light
                emit(false, s, contribution);
                return;
            }
            s.dir = d / dist;
            ++counters.shadowRays;
            if (counters.shadowRayLog) counters.shadowRayLog->push_back(s);
            emit(true, s, contribution);
        };
        for (int li : t.rectLights_) {
            const Light& l = t.light(li, movable);
            const float u1 = rng.uniform(), u2 = rng.uniform();
            const Vec3 x = l.corner + l.edge1 * u1 + l.edge2 * u2;
            const Vec3 d = x - p;
            const float dist2 = lengthSquared(d);
            if (!(dist2 > 0.f)) continue;
            const float dist = std::sqrt(dist2);
            const Vec3 wi = d / dist;
            const float cosTheta = dot(wi, n);
            if (cosTheta <= 0.f) continue;
            const Vec3 nl = cross(l.edge1, l.edge2);  // |nl| = area
            float cosLArea = -dot(wi, nl);            // cos θ' · A
            if (!l.oneSided) cosLArea = std::fabs(cosLArea);
            if (cosLArea <= 0.f) continue;
            const Vec3 f = evalBrdf(wi);
            if (f.isZero()) continue;
            visible(wi, x, [&] {
                // Area sampling with pdf 1/A turned into solid angle: Le f cosθ cosθ' A / d².
                Vec3 c = l.radiance * f * (cosTheta * cosLArea / dist2);
                if constexpr (kGlossy) {
                    if (brdfRayFollows)
                        c *= powerHeuristic(dist2 / cosLArea, brdf.pdf(v.woLocal, v.frame.toLocal(wi)));
                }
                return c;
            });
        }
        if (!t.triangleLights_.empty()) {
            // One sample for all triangle lights together: a triangle picked with probability ∝ its
            // area (areas do not change when the movable light moves), then a uniform point on it, so
            // the point is uniform on the emitters' total area A (pdf 1/A) and a mesh emitter of many
            // triangles costs one shadow ray.
            const float uPick = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
            const double target = double(uPick) * t.triangleArea_;
            const size_t k = std::min(size_t(std::upper_bound(t.triangleCdf_.begin(), t.triangleCdf_.end(), target) -
                                             t.triangleCdf_.begin()),
                                      t.triangleCdf_.size() - 1);
            const Light& l = t.light(t.triangleLights_[k], movable);
            const Vec3 x = l.pointAt(u1, u2);
            const Vec3 d = x - p;
            const float dist2 = lengthSquared(d);
            if (dist2 > 0.f) {
                const float dist = std::sqrt(dist2);
                const Vec3 wi = d / dist;
                const float cosTheta = dot(wi, n);
                float cosL = -dot(wi, l.normal());
                if (!l.oneSided) cosL = std::fabs(cosL);
                if (cosTheta > 0.f && cosL > 0.f) {
                    const Vec3 f = evalBrdf(wi);
                    if (!f.isZero()) {
                        const float area = float(t.triangleArea_);
                        visible(wi, x, [&] {
                            Vec3 c = l.radiance * f * (cosTheta * cosL * area / dist2);
                            if constexpr (kGlossy) {
                                if (brdfRayFollows)
                                    c *= powerHeuristic(dist2 / (cosL * area), brdf.pdf(v.woLocal, v.frame.toLocal(wi)));
                            }
                            return c;
                        });
                    }
                }
            }
        }
        for (int li : t.pointLights_) {
            const Light& l = t.light(li, movable);
            const Vec3 d = l.position - p;
            const float dist2 = lengthSquared(d);
            if (!(dist2 > 0.f)) continue;
            const Vec3 wi = d / std::sqrt(dist2);
            const float cosTheta = dot(wi, n);
            if (cosTheta <= 0.f) continue;
            const Vec3 f = evalBrdf(wi);
            if (f.isZero()) continue;
            visible(wi, l.position, [&] { return l.intensity * f * (cosTheta / dist2); });
        }
    }

    /// NEE at vertex `v` with its shadow rays traced one by one.
    template <bool kGlossy>
    static void directLight(const PathTracer& t, Vertex& v, const Light& movable, Rng& rng, TraceCounters& counters) {
        Vec3 sum(0.f);
        lightSamples<kGlossy>(t, v, movable, rng, counters, [&](bool needsRay, const Ray& s, auto&& contribution) {
            if (!needsRay || !t.occluded(s, movable)) sum += contribution();
        });
        v.target() += v.beta * sum;
    }

    /// The BRDF bounce from the vertex set up by enter(): samples a direction and plays Russian
    /// roulette. False when the path ends here; otherwise `r` is the bounce ray and `wiLocal` its
    /// direction in the vertex's frame.
    template <bool kGlossy>
    static bool bounceRay(const PathTracer& t, Vertex& v, Rng& rng, TraceCounters& counters, Ray& r, Vec3& wiLocal) {
        if (!v.bounces) return false;
        const Brdf& brdf = *v.brdf;
        const float uLobe = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
        Vec3 weight;
        bool ok;
        if constexpr (kGlossy) {
            ok = brdf.sample(v.woLocal, uLobe, u1, u2, wiLocal, weight);
        } else {
            (void)uLobe;
            wiLocal = sampleCosineHemisphere(u1, u2);
            weight = brdf.kd;
            ok = wiLocal.z > 0.f;
        }
        if (!ok) return false;
        // With a shading normal a direction above it may point below the geometric surface; such a
        // ray would start on the far side and leak light through the mesh, so the path ends.
        if (!v.hit.ns.isZero() && dot(v.frame.toWorld(wiLocal), v.hit.ng) * v.side <= 0.f) return false;
        v.beta *= weight;
        if (v.depth >= 1) {
            // Russian roulette: survive with the path's throughput, bounded away from 0 so that the
            // 1/q weight stays bounded (q never 0).
            const float q = std::clamp(v.beta.maxComponent(), 0.05f, 1.f);
            if (q < 1.f) {
                if (rng.uniform() >= q) return false;
                v.beta = v.beta / q;
            }
        }
        if (v.beta.isZero()) return false;
        const Vec3 wi = v.frame.toWorld(wiLocal);
        r = Ray{};
        r.origin = t.accel_.spawnOrigin(v.hit.p, v.hit.ng, wi);
        r.dir = wi;
        ++counters.rays;
        if (counters.rayLog) counters.rayLog->push_back(r);
        return true;
    }

    /// Takes the path along its bounce ray `r` to what the ray hit (`found`, `next`), counting the
    /// emission there where the estimator wants it. True when the path goes on at the new v.hit.
    static bool arrive(const PathTracer& t, Vertex& v, const Light& movable, const Ray& r, const Vec3& wiLocal,
                       bool found, const Hit& next) {
        if (!found) return false;
        const bool nee = t.estimator_ == Estimator::NEE;
        const Vec3& wi = r.dir;
        if (next.light >= 0 && (!nee || v.mis)) {
            const Light& hitLight = t.light(next.light, movable);
            Vec3 emitted = hitLight.emittedTowards(-wi);
            if (v.mis && !emitted.isZero()) {
                // The pdf with which this vertex's light sample would have picked the same point, in
                // solid angle: t² / (|cos θ'| A), with A the rect's own area (one sample per rect
                // light) or the total area of the triangle lights (one sample for all of them, the
                // triangle picked by area). Point lights are never hit.
                const float sampledArea =
                    hitLight.type == Light::Type::Triangle ? float(t.triangleArea_) : hitLight.area();
                const float cosLArea = std::fabs(dot(wi, hitLight.normal())) * sampledArea;
                const float dist = length(next.p - v.hit.p);
                const float pLight = cosLArea > 0.f ? dist * dist / cosLArea : 0.f;
                emitted *= powerHeuristic(v.brdf->pdf(v.woLocal, wiLocal), pLight);
            }
            v.target() += v.beta * emitted;
        }
        if (!nee && v.depth + 1 >= t.maxDepth_) return false;
        v.hit = next;
        v.wo = -wi;
        ++v.depth;
        return true;
    }

    /// bounceRay(), the ray traced alone, arrive().
    template <bool kGlossy>
    static bool scatter(const PathTracer& t, Vertex& v, const Light& movable, Rng& rng, TraceCounters& counters) {
        Ray r;
        Vec3 wiLocal;
        if (!bounceRay<kGlossy>(t, v, rng, counters, r, wiLocal)) return false;
        Hit next;
        const bool found = t.intersect(r, movable, next);
        return arrive(t, v, movable, r, wiLocal, found, next);
    }

    /// Emission seen directly at the path's first hit: always counted.
    static void emissionSeen(const PathTracer& t, Vertex& v, const Light& movable) {
        if (v.hit.light >= 0) v.L.direct += t.light(v.hit.light, movable).emittedTowards(v.wo);
    }

    /// The rest of the path from vertex `v`, one vertex after the other (shade()'s loop).
    template <bool kGlossy>
    static void finish(const PathTracer& t, Vertex& v, const Light& movable, Rng& rng, TraceCounters& counters) {
        const bool nee = t.estimator_ == Estimator::NEE;
        while (enter<kGlossy>(t, v)) {
            if (nee) directLight<kGlossy>(t, v, movable, rng, counters);
            if (!scatter<kGlossy>(t, v, movable, rng, counters)) break;
        }
    }

    /// NEE at the vertices v[live[j]], j < count, their shadow rays traced in packets.
    template <bool kGlossy>
    static void directLightBatch(const PathTracer& t, Vertex* v, const int* live, int count, const Light& movable,
                                 Rng* rngs, TraceCounters& counters);
    template <bool kGlossy>
    static void traceBatch(const PathTracer& t, const Ray* rays, Rng* rngs, int count, TraceCounters& counters,
                           Radiance* out);
    // The SIMD lanes (render/path_lanes.h; path_tracer_lanes.cpp).
    /// Fewer paths than this run faster one by one (or in the portable lockstep) than in 16 lanes
    /// (docs/results-history.md, "The tracer's lanes").
    static constexpr int kMinLanePaths = 6;
    /// The tables the lanes read (PathTracer::laneTables_).
    static void buildLaneTables(PathTracer& t);
    /// Whether the lanes run `count` paths with the movable light at `movable` (a move of the
    /// scene's): the tracer has lanes, the batch fills them, no ray is logged.
    static bool lanesTake(const PathTracer& t, const Light& movable, int count, const TraceCounters& counters);
    struct LaneBatch;
    /// traceBatch<false>() with the lockstep vertices as SIMD lanes.
    static void traceLanes(const PathTracer& t, const Ray* rays, Rng* rngs, int count, TraceCounters& counters,
                           Radiance* out);
    /// shade() of `count` paths from one vertex, their lockstep vertices as SIMD lanes.
    static void shadeLanes(const PathTracer& t, const Hit& hit, const Vec3& wo, const Light& movable, Rng* rngs,
                           int count, TraceCounters& counters, Radiance* out);
};

}  // namespace rrf
