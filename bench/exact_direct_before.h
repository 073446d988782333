#pragma once
/// The exact direct light estimator this session replaced (core/predict/exact_direct.cpp at main
/// 6800244), kept verbatim so that bench_direct times it and measures its error in the same run as
/// the estimator that replaced it: every light sample's shadow ray traced one by one through Embree
/// (PathTracer::occluded), glossy light by next-event estimation over the same samples
/// (1/N) Σ_j Le f_s(ω_j) f_j A V_j. Same samples, random numbers and diffuse ratio as ExactDirect.
/// Also the benchmark's reference: an unbiased glossy estimator independent of the lobe quadrature.

#include <cmath>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/predict/exact_direct.h"

namespace rrf::bench {

class ExactDirectBefore {
public:
    ExactDirectBefore(const PathTracer& tracer, int samples, uint64_t seed)
        : tracer_(tracer), samples_(std::max(1, samples)), seed_(exactDirectSeed(seed)), grid_(samples_) {
        for (const Material& m : tracer.scene().materials) brdfs_.emplace_back(m);
    }

    /// As ExactDirect::image (the loop Predictor ran before).
    Image image(const GBuffer& gb, const Light& movable, uint64_t& shadowRays) const {
        Image out(gb.width, gb.height);
        std::vector<uint64_t> rays(size_t(gb.height), 0);
        tbb::parallel_for(0, gb.height, [&](int y) {
            TraceCounters counters;
            for (int x = 0; x < gb.width; ++x) {
                const size_t i = size_t(y) * size_t(gb.width) + size_t(x);
                if (gb.object[i] < 0) continue;
                const float* r = gb.input(i);
                Vec3 d = radiance(Vec3(r[0], r[1], r[2]), Vec3(r[9], r[10], r[11]), Vec3(r[3], r[4], r[5]),
                                  gb.object[i], movable, i, counters);
                out.set(x, y, d.isFinite() ? d : Vec3(0.f));
            }
            rays[size_t(y)] = counters.shadowRays;
        });
        shadowRays = 0;
        for (uint64_t n : rays) shadowRays += n;
        return out;
    }

    Vec3 radiance(const Vec3& p, const Vec3& n, const Vec3& wo, int object, const Light& movable, uint64_t pixel,
                  TraceCounters& counters) const {
        const Scene& scene = tracer_.scene();
        const int mat = scene.objects[size_t(object)].material;
        if (mat < 0) return Vec3(0.f);
        const Brdf& brdf = brdfs_[size_t(mat)];
        const bool glossy = !brdf.ks.isZero();
        auto lightAt = [&](size_t i) -> const Light& { return int(i) == scene.movableLight ? movable : scene.lights[i]; };

        // Per area light, in scene order: the toroidal shift, then the sums over its N samples.
        struct Acc {
            float shiftU = 0.f, shiftV = 0.f;
            float sumF = 0.f, sumFV = 0.f;
            Vec3 glossy{0.f};
        };
        std::vector<Acc> acc;
        Rng shiftRng(seed_, pixel, kShiftSample);
        for (const Light& l : scene.lights)
            if (l.isArea()) {
                Acc a;
                a.shiftU = shiftRng.uniform();
                a.shiftV = shiftRng.uniform();
                acc.push_back(a);
            }

        for (int s = 0; s < samples_; ++s) {
            Rng rng(seed_, pixel, uint64_t(s));
            const float cellU = float(s % grid_.cols), cellV = float(s / grid_.cols);
            size_t r = 0;
            for (size_t li = 0; li < scene.lights.size(); ++li) {
                if (!scene.lights[li].isArea()) continue;
                const Light& l = lightAt(li);
                Acc& a = acc[r++];
                const float j1 = rng.uniform(), j2 = rng.uniform();
                float u = (cellU + j1) / float(grid_.cols) + a.shiftU;
                float v = (cellV + j2) / float(grid_.rows) + a.shiftV;
                if (u >= 1.f) u -= 1.f;
                if (v >= 1.f) v -= 1.f;
                const Vec3 x = l.pointAt(u, v);
                const Vec3 d = x - p;
                const float dist2 = lengthSquared(d);
                if (!(dist2 > 0.f)) continue;
                const Vec3 wi = d / std::sqrt(dist2);
                const float cosTheta = dot(wi, n);
                if (cosTheta <= 0.f) continue;
                float cosL = -dot(wi, l.normal());
                if (!l.oneSided) cosL = std::fabs(cosL);
                if (cosL <= 0.f) continue;
                const float f = cosTheta * cosL / dist2;
                const bool vis = visible(p, n, x, movable, counters);
                a.sumF += f;
                if (vis) {
                    a.sumFV += f;
                    if (glossy) a.glossy += glossyLobe(brdf, wo, n, wi) * f;
                }
            }
        }

        Vec3 L(0.f);
        size_t r = 0;
        for (size_t li = 0; li < scene.lights.size(); ++li) {
            const Light& l = lightAt(li);
            if (l.isArea()) {
                const Acc& a = acc[r++];
                Vec3 centroid;
                const double omega = projectedSolidAngle(l, p, n, &centroid);
                if (omega > 0.0 && !brdf.kd.isZero()) {
                    const float ratio = a.sumF > 0.f ? a.sumFV / a.sumF
                                                     : (visible(p, n, centroid, movable, counters) ? 1.f : 0.f);
                    L += brdf.kd * l.radiance * float(omega * double(kInvPi) * double(ratio));
                }
                if (glossy) L += l.radiance * a.glossy * (l.area() / float(samples_));
            } else {
                const Vec3 d = l.position - p;
                const float dist2 = lengthSquared(d);
                if (!(dist2 > 0.f)) continue;
                const Vec3 wi = d / std::sqrt(dist2);
                const float cosTheta = dot(wi, n);
                if (cosTheta <= 0.f || !visible(p, n, l.position, movable, counters)) continue;
                L += l.intensity * (brdf.kd * kInvPi + glossyLobe(brdf, wo, n, wi)) * (cosTheta / dist2);
            }
        }
        return L;
    }

private:
    static Vec3 glossyLobe(const Brdf& b, const Vec3& wo, const Vec3& n, const Vec3& wi) {
        return b.ks * ((b.n + 2.f) * kInv2Pi * powCos(dot(reflect(wo, n), wi), b.n));
    }

    bool visible(const Vec3& p, const Vec3& n, const Vec3& target, const Light& movable, TraceCounters& c) const {
        const Accel& accel = tracer_.accel();
        Ray s;
        s.origin = accel.spawnOrigin(p, n, target - p);
        const Vec3 d = target - s.origin;
        const float dist = length(d);
        // As PathTracer's NEE: stop short of the target so the light's own quad does not occlude it.
        s.tmax = dist * (1.f - 1e-4f) - accel.offset(target);
        if (!(s.tmax > 0.f)) return true;
        s.dir = d / dist;
        ++c.shadowRays;
        return !tracer_.occluded(s, movable);
    }

    const PathTracer& tracer_;
    int samples_;
    uint64_t seed_;
    SampleGrid grid_;
    std::vector<Brdf> brdfs_;
};

}  // namespace rrf::bench
