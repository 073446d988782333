#include "core/render/path_tracer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

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
    }
}

Light PathTracer::movableLightAt(const Vec3& p) const {
    Light l = movableDefault_;
    l.moveTo(p);
    return l;
}

namespace {
/// Ray intersection with an area light (corner + s·e1 + t·e2: s,t ∈ [0,1] for a rect, s,t ≥ 0 and
/// s+t ≤ 1 for a triangle) in (tmin, tmax).
bool intersectAreaLight(const Ray& ray, const Light& l, float tmax, float& t) {
    const Vec3 n = cross(l.edge1, l.edge2);
    const float denom = dot(ray.dir, n);
    if (denom == 0.f) return false;
    t = dot(l.corner - ray.origin, n) / denom;
    if (!(t > ray.tmin && t < tmax)) return false;
    const Vec3 q = ray.origin + ray.dir * t - l.corner;
    const float nn = dot(n, n);
    const float a = dot(cross(q, l.edge2), n) / nn;
    const float b = dot(cross(l.edge1, q), n) / nn;
    if (l.type == Light::Type::Triangle) return a >= 0.f && b >= 0.f && a + b <= 1.f;
    return a >= 0.f && a <= 1.f && b >= 0.f && b <= 1.f;
}

/// Power-heuristic weight (β = 2) of the strategy with pdf `p` against the one with pdf `other`
/// (both in solid angle); 0 when `p` is 0 or either pdf is not finite.
float powerHeuristic(float p, float other) {
    const float p2 = p * p, o2 = other * other;
    const float w = p2 / (p2 + o2);
    return std::isfinite(w) ? w : 0.f;
}
}  // namespace

bool PathTracer::intersect(const Ray& ray, const Light& movable, Hit& hit) const {
    bool found = accel_.intersect(ray, hit);
    float t;
    if (movable_ >= 0 && movable.isArea() && intersectAreaLight(ray, movable, found ? hit.t : ray.tmax, t)) {
        hit = Hit{};
        hit.t = t;
        hit.p = ray.origin + ray.dir * t;
        hit.ng = movable.normal();
        hit.light = movable_;
        found = true;
    }
    return found;
}

bool PathTracer::occluded(const Ray& ray, const Light& movable) const {
    float t;
    if (movable_ >= 0 && movable.isArea() && intersectAreaLight(ray, movable, ray.tmax, t))
        return true;
    return accel_.occluded(ray);
}

void PathTracer::occludedPacket(const Ray* rays, int count, const Light& movable, bool* blocked) const {
    accel_.occludedPacket(rays, count, blocked);
    if (movable_ < 0 || !movable.isArea()) return;
    float t;
    for (int i = 0; i < count; ++i)
        if (!blocked[i] && intersectAreaLight(rays[i], movable, rays[i].tmax, t)) blocked[i] = true;
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
    return effects_.glossy ? shadeImpl<true>(hit, wo, movable, rng, counters)
                           : shadeImpl<false>(hit, wo, movable, rng, counters);
}

template <bool kGlossy>
Radiance PathTracer::shadeImpl(Hit hit, Vec3 wo, const Light& movable, Rng& rng, TraceCounters& counters) const {
    Radiance L;
    // Emission seen directly is always counted.
    if (hit.light >= 0) L.direct += light(hit.light, movable).emittedTowards(wo);
    const bool nee = estimator_ == Estimator::NEE;
    Vec3 beta(1.f);
    for (int depth = 0;; ++depth) {
        const int mat = materialOf(hit);
        if (mat < 0) break;
        const Brdf& brdf = brdfs_[size_t(mat)];
        const float side = dot(wo, hit.ng);
        if (side == 0.f) break;  // exactly grazing: no reflection
        // Two-sided surfaces: shade the side we see (decided by the geometric normal; the shading
        // normal is on ng's side).
        const Vec3 ns = hit.shading();
        const Vec3 n = side > 0.f ? ns : -ns;
        const Frame frame(n);
        const Vec3 woLocal = frame.toLocal(wo);
        Vec3& target = depth == 0 ? L.direct : L.indirect;
        // Bounce: always for the naive estimator's first reflection (that is its direct light), and
        // beyond that only if the scene lets light travel between surfaces. NEE at depth d already
        // accounts for paths of d+1 reflections; the naive estimator needs the bounce at depth d to
        // see them, so for it the depth limit applies after the emission test below.
        const bool bounces = nee ? depth + 1 < maxDepth_ && effects_.indirect : depth == 0 || effects_.indirect;
        const bool mis = kGlossy && nee && bounces;
        if (nee)
            target += beta * sampleDirect<kGlossy>(hit.p, hit.ng, n, frame, woLocal, brdf, movable, mis, rng, counters);
        if (!bounces) break;
        const float uLobe = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
        Vec3 wiLocal, weight;
        bool ok;
        if constexpr (kGlossy) {
            ok = brdf.sample(woLocal, uLobe, u1, u2, wiLocal, weight);
        } else {
            (void)uLobe;
            wiLocal = sampleCosineHemisphere(u1, u2);
            weight = brdf.kd;
            ok = wiLocal.z > 0.f;
        }
        if (!ok) break;
        // With a shading normal a direction above it may point below the geometric surface; such a
        // ray would start on the far side and leak light through the mesh, so the path ends.
        if (!hit.ns.isZero() && dot(frame.toWorld(wiLocal), hit.ng) * side <= 0.f) break;
        beta *= weight;
        if (depth >= 1) {
            // Russian roulette: survive with the path's throughput, bounded away from 0 so that the
            // 1/q weight stays bounded (q never 0).
            const float q = std::clamp(beta.maxComponent(), 0.05f, 1.f);
            if (q < 1.f) {
                if (rng.uniform() >= q) break;
                beta = beta / q;
            }
        }
        if (beta.isZero()) break;
        const Vec3 wi = frame.toWorld(wiLocal);
        Ray r;
        r.origin = accel_.spawnOrigin(hit.p, hit.ng, wi);
        r.dir = wi;
        Hit next;
        ++counters.rays;
        if (counters.rayLog) counters.rayLog->push_back(r);
        if (!intersect(r, movable, next)) break;
        if (next.light >= 0 && (!nee || mis)) {
            const Light& hitLight = light(next.light, movable);
            Vec3 emitted = hitLight.emittedTowards(-wi);
            if (mis && !emitted.isZero()) {
                // The pdf with which this vertex's light sample would have picked the same point, in
                // solid angle: t² / (|cos θ'| A), with A the rect's own area (one sample per rect
                // light) or the total area of the triangle lights (one sample for all of them, the
                // triangle picked by area). Point lights are never hit.
                const float sampledArea =
                    hitLight.type == Light::Type::Triangle ? float(triangleArea_) : hitLight.area();
                const float cosLArea = std::fabs(dot(wi, hitLight.normal())) * sampledArea;
                const float t = length(next.p - hit.p);
                const float pLight = cosLArea > 0.f ? t * t / cosLArea : 0.f;
                emitted *= powerHeuristic(brdf.pdf(woLocal, wiLocal), pLight);
            }
            Vec3& t = depth == 0 ? L.direct : L.indirect;
            t += beta * emitted;
        }
        if (!nee && depth + 1 >= maxDepth_) break;
        hit = next;
        wo = -wi;
    }
    return L;
}

template <bool kGlossy>
Vec3 PathTracer::sampleDirect(const Vec3& p, const Vec3& ng, const Vec3& n, const Frame& frame, const Vec3& woLocal,
                              const Brdf& brdf, const Light& movable, bool brdfRayFollows, Rng& rng,
                              TraceCounters& counters) const {
    Vec3 sum(0.f);
    auto evalBrdf = [&](const Vec3& wi) -> Vec3 {
        if constexpr (kGlossy) return brdf.eval(woLocal, frame.toLocal(wi));
        else return brdf.kd * kInvPi;
    };
    // Same for light samples: below the geometric surface means behind it, whatever the shading
    // normal says (for flat surfaces n = ±ng, and cos θ > 0 already implies this).
    const float ngSide = dot(n, ng);
    auto visible = [&](const Vec3& wi, const Vec3& target) {
        if (dot(wi, ng) * ngSide <= 0.f) return false;
        Ray s;
        s.origin = accel_.spawnOrigin(p, ng, wi);
        const Vec3 d = target - s.origin;
        const float dist = length(d);
        // Stop short of the target so the light's own quad does not occlude its sample point.
        s.tmax = dist * (1.f - 1e-4f) - accel_.offset(target);
        if (!(s.tmax > 0.f)) return true;  // nothing fits between the point and the light
        s.dir = d / dist;
        ++counters.shadowRays;
        if (counters.shadowRayLog) counters.shadowRayLog->push_back(s);
        return !occluded(s, movable);
    };
    for (int li : rectLights_) {
        const Light& l = light(li, movable);
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
        if (f.isZero() || !visible(wi, x)) continue;
        // Area sampling with pdf 1/A turned into solid angle: Le f cosθ cosθ' A / d².
        Vec3 contribution = l.radiance * f * (cosTheta * cosLArea / dist2);
        if constexpr (kGlossy) {
            if (brdfRayFollows) contribution *= powerHeuristic(dist2 / cosLArea, brdf.pdf(woLocal, frame.toLocal(wi)));
        } else {
            (void)brdfRayFollows;
        }
        sum += contribution;
    }
    if (!triangleLights_.empty()) {
        // One sample for all triangle lights together: a triangle picked with probability ∝ its area
        // (areas do not change when the movable light moves), then a uniform point on it, so the
        // point is uniform on the emitters' total area A (pdf 1/A) and a mesh emitter of many
        // triangles costs one shadow ray.
        const float uPick = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
        const double target = double(uPick) * triangleArea_;
        const size_t k = std::min(size_t(std::upper_bound(triangleCdf_.begin(), triangleCdf_.end(), target) -
                                         triangleCdf_.begin()),
                                  triangleCdf_.size() - 1);
        const Light& l = light(triangleLights_[k], movable);
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
                if (!f.isZero() && visible(wi, x)) {
                    Vec3 contribution = l.radiance * f * (cosTheta * cosL * float(triangleArea_) / dist2);
                    if constexpr (kGlossy) {
                        if (brdfRayFollows)
                            contribution *= powerHeuristic(dist2 / (cosL * float(triangleArea_)),
                                                           brdf.pdf(woLocal, frame.toLocal(wi)));
                    }
                    sum += contribution;
                }
            }
        }
    }
    for (int li : pointLights_) {
        const Light& l = light(li, movable);
        const Vec3 d = l.position - p;
        const float dist2 = lengthSquared(d);
        if (!(dist2 > 0.f)) continue;
        const Vec3 wi = d / std::sqrt(dist2);
        const float cosTheta = dot(wi, n);
        if (cosTheta <= 0.f) continue;
        const Vec3 f = evalBrdf(wi);
        if (f.isZero() || !visible(wi, l.position)) continue;
        sum += l.intensity * f * (cosTheta / dist2);
    }
    return sum;
}

}  // namespace rrf
