#include "core/path_tracer.h"

#include <algorithm>

namespace rrf {

PathTracer::PathTracer(const Scene& scene, const Accel& accel, Estimator estimator, int maxDepth)
    : scene_(scene), accel_(accel), estimator_(estimator), maxDepth_(std::max(1, maxDepth)) {
    effects_ = Effects::derive(scene);
    for (const Material& m : scene.materials) brdfs_.emplace_back(m);
    for (size_t i = 0; i < scene.lights.size(); ++i)
        (scene.lights[i].type == Light::Type::Rect ? rectLights_ : pointLights_).push_back(int(i));
}

Vec3 PathTracer::emitted(int light, const Vec3& w) const {
    const Light& l = scene_.lights[size_t(light)];
    if (l.oneSided && dot(w, cross(l.edge1, l.edge2)) <= 0.f) return Vec3(0.f);
    return l.radiance;
}

int PathTracer::materialOf(const Hit& hit) const {
    return hit.object >= 0 ? scene_.objects[size_t(hit.object)].material : scene_.lights[size_t(hit.light)].material;
}

Radiance PathTracer::trace(const Ray& ray, Rng& rng, TraceCounters& counters) const {
    Hit hit;
    ++counters.rays;
    if (counters.rayLog) counters.rayLog->push_back(ray);
    if (!accel_.intersect(ray, hit)) return {};
    return shade(hit, -ray.dir, rng, counters);
}

Radiance PathTracer::shade(const Hit& hit, const Vec3& wo, Rng& rng, TraceCounters& counters) const {
    return effects_.glossy ? shadeImpl<true>(hit, wo, rng, counters) : shadeImpl<false>(hit, wo, rng, counters);
}

template <bool kGlossy>
Radiance PathTracer::shadeImpl(Hit hit, Vec3 wo, Rng& rng, TraceCounters& counters) const {
    Radiance L;
    if (hit.light >= 0) L.direct += emitted(hit.light, wo);  // emission seen directly is always counted
    const bool nee = estimator_ == Estimator::NEE;
    Vec3 beta(1.f);
    for (int depth = 0;; ++depth) {
        const int mat = materialOf(hit);
        if (mat < 0) break;
        const Brdf& brdf = brdfs_[size_t(mat)];
        const float side = dot(wo, hit.ng);
        if (side == 0.f) break;  // exactly grazing: no reflection
        const Vec3 n = side > 0.f ? hit.ng : -hit.ng;  // two-sided surfaces: shade the side we see
        const Frame frame(n);
        const Vec3 woLocal = frame.toLocal(wo);
        Vec3& target = depth == 0 ? L.direct : L.indirect;
        if (nee) target += beta * sampleDirect<kGlossy>(hit.p, hit.ng, n, frame, woLocal, brdf, rng, counters);

        // Bounce: always for the naive estimator's first reflection (that is its direct light), and
        // beyond that only if the scene lets light travel between surfaces.
        if (depth + 1 >= maxDepth_) break;
        if ((nee || depth >= 1) && !effects_.indirect) break;
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
        if (!accel_.intersect(r, next)) break;
        if (next.light >= 0 && !nee) {
            Vec3& t = depth == 0 ? L.direct : L.indirect;
            t += beta * emitted(next.light, -wi);
        }
        hit = next;
        wo = -wi;
    }
    return L;
}

template <bool kGlossy>
Vec3 PathTracer::sampleDirect(const Vec3& p, const Vec3& ng, const Vec3& n, const Frame& frame, const Vec3& woLocal,
                              const Brdf& brdf, Rng& rng, TraceCounters& counters) const {
    Vec3 sum(0.f);
    auto evalBrdf = [&](const Vec3& wi) -> Vec3 {
        if constexpr (kGlossy) return brdf.eval(woLocal, frame.toLocal(wi));
        else return brdf.kd * kInvPi;
    };
    auto visible = [&](const Vec3& wi, const Vec3& target) {
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
        return !accel_.occluded(s);
    };
    for (int li : rectLights_) {
        const Light& l = scene_.lights[size_t(li)];
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
        sum += l.radiance * f * (cosTheta * cosLArea / dist2);
    }
    for (int li : pointLights_) {
        const Light& l = scene_.lights[size_t(li)];
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
