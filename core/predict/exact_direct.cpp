#include "core/predict/exact_direct.h"

#include <cmath>

#include <Eigen/Core>
#include <tbb/parallel_for.h>

#include "core/predict/phong_lobe_integral.h"

namespace rrf {

SampleGrid::SampleGrid(int samples) {
    cols = std::max(1, int(std::ceil(std::sqrt(double(samples)))));
    rows = (std::max(1, samples) + cols - 1) / cols;
}

ExactDirect::ExactDirect(const PathTracer& tracer, int samples, uint64_t seed, Options options)
    : tracer_(tracer),
      samples_(std::max(1, samples)),
      seed_(exactDirectSeed(seed)),
      grid_(samples_),
      options_(options),
      casters_(tracer) {
    for (const Material& m : tracer.scene().materials) brdfs_.emplace_back(m);
}

bool ExactDirect::visible(const Vec3& p, const Vec3& n, const Vec3& target, const Light& movable,
                          TraceCounters& c) const {
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
    if (c.shadowRayLog) c.shadowRayLog->push_back(s);
    return !tracer_.occluded(s, movable);
}

ExactDirect::Sums ExactDirect::traceSamples(const Light& l, int areaIndex, const Vec3& p, const Vec3& n,
                                            const Vec3& mirror, const Brdf& brdf, const Light& movable,
                                            const ShadowCasters::Casters* casters, uint64_t pixel,
                                            TraceCounters& c) const {
    static_assert(ShadowCasters::kBatch == Accel::kPacket, "one chunk of samples is one packet of rays");
    constexpr int K = ShadowCasters::kBatch;
    const Accel& accel = tracer_.accel();
    const bool glossy = !brdf.ks.isZero();
    // Each Rng gives two numbers per area light in scene order: skip those of the lights before.
    auto skip = [&](Rng& rng) {
        for (int k = 0; k < 2 * areaIndex; ++k) rng.uniform();
    };
    const uint64_t key = Rng::streamKey(seed_, pixel);
    Rng shiftRng = Rng::ofStream(key, kShiftSample);
    skip(shiftRng);
    const float shiftU = shiftRng.uniform(), shiftV = shiftRng.uniform();
    const Vec3 lightNormal = l.normal();
    const Vec3 origin = accel.spawnOrigin(p, n, n);  // every sample is above the horizon: one origin
    const float invCols = 1.f / float(grid_.cols), invRows = 1.f / float(grid_.rows);
    const bool triangle = l.type == Light::Type::Triangle;
    const float offsetScale = accel.offset(Vec3(0.f));  // offset(x) = 2e-5 (|x|∞ + scale) = this + 2e-5 |x|∞

    Sums sums;
    int col = 0, row = 0;  // sample s's cell: (s mod cols, s div cols)
    for (int s0 = 0; s0 < samples_; s0 += K) {
        const int count = std::min(K, samples_ - s0);
        // Chunks of K samples: the random numbers one by one, then every step lane by lane over
        // fixed-size arrays so that the compiler vectorises it; the sums stay in sample order.
        alignas(16) float u[K], v[K];
        for (int k = 0; k < K; ++k) {
            float uu = 0.5f, vv = 0.5f;  // lanes past `count` get a harmless point, masked below
            if (k < count) {
                Rng rng = Rng::ofStream(key, uint64_t(s0 + k));
                skip(rng);
                const float j1 = rng.uniform(), j2 = rng.uniform();
                uu = (float(col) + j1) * invCols + shiftU;
                vv = (float(row) + j2) * invRows + shiftV;
                if (++col == grid_.cols) {
                    col = 0;
                    ++row;
                }
                if (uu >= 1.f) uu -= 1.f;
                if (vv >= 1.f) vv -= 1.f;
            }
            // Light::pointAt's fold of the square onto a triangle.
            const bool fold = triangle && uu + vv > 1.f;
            u[k] = fold ? 1.f - uu : uu;
            v[k] = fold ? 1.f - vv : vv;
        }
        // Eigen arrays of K lanes: explicit SIMD packets, evaluated in the scalar code's order.
        using Lanes = Eigen::Array<float, K, 1>;
        const Eigen::Map<const Lanes> uu(u), vv(v);
        const Lanes xx = l.corner.x + l.edge1.x * uu + l.edge2.x * vv;
        const Lanes xy = l.corner.y + l.edge1.y * uu + l.edge2.y * vv;
        const Lanes xz = l.corner.z + l.edge1.z * uu + l.edge2.z * vv;
        const Lanes qx = xx - p.x, qy = xy - p.y, qz = xz - p.z;
        const Lanes dist2 = qx * qx + qy * qy + qz * qz;
        const Lanes inv = dist2.sqrt().inverse();
        const Lanes cosTheta = (qx * n.x + qy * n.y + qz * n.z) * inv;
        Lanes cosL = -(qx * lightNormal.x + qy * lightNormal.y + qz * lightNormal.z) * inv;
        if (!l.oneSided) cosL = cosL.abs();
        alignas(16) float f[K], ca[K], dx[K], dy[K], dz[K], dist[K], tmax[K];
        Lanes::Map(f) = cosTheta * cosL * (inv * inv);
        Lanes::Map(ca) = (qx * mirror.x + qy * mirror.y + qz * mirror.z) * inv;
        // The shadow ray, as visible(): from the common origin, stopped short of the sample.
        const Lanes ox = xx - origin.x, oy = xy - origin.y, oz = xz - origin.z;
        Lanes::Map(dx) = ox;
        Lanes::Map(dy) = oy;
        Lanes::Map(dz) = oz;
        const Lanes len = (ox * ox + oy * oy + oz * oz).sqrt();
        Lanes::Map(dist) = len;
        const Lanes ext = xx.abs().max(xy.abs()).max(xz.abs());
        Lanes::Map(tmax) = len * (1.f - 1e-4f) - (2e-5f * ext + offsetScale);
        alignas(16) int32_t valid[K];  // −1 / 0 masks
        for (int k = 0; k < K; ++k)
            valid[k] = k < count && dist2[k] > 0.f && cosTheta[k] > 0.f && cosL[k] > 0.f ? -1 : 0;
        alignas(16) float g[K] = {};
        if (glossy) {
            // cos^e α in float, as the shader: only the glossy ratio's weights use it.
            const Eigen::Map<const Lanes> c(ca);
            const Lanes lobe = brdf.n == 0.f ? Lanes::Ones().eval() : (brdf.n * c.max(1e-30f).log()).exp().eval();
            Lanes::Map(g) = (c > 0.f).select(lobe, 0.f);
        }
        alignas(16) int32_t blocked[K], traced[K];
        for (int k = 0; k < K; ++k) traced[k] = valid[k] & (tmax[k] > 0.f ? -1 : 0);  // else visible without a ray
        if (casters) {
            alignas(16) float end[K];
            for (int k = 0; k < K; ++k) end[k] = traced[k] ? tmax[k] / dist[k] : -1.f;
            ShadowCasters::blocked(*casters, origin, dx, dy, dz, end, blocked);
            for (int k = 0; k < K; ++k) {
                blocked[k] &= traced[k];
                c.shadowRays += traced[k] ? 1 : 0;
            }
        } else {
            Ray rays[K];
            int index[K], m = 0;
            for (int k = 0; k < K; ++k) {
                blocked[k] = 0;
                if (!traced[k]) continue;
                Ray& ray = rays[m];
                ray.origin = origin;
                ray.dir = Vec3(dx[k], dy[k], dz[k]) * (1.f / dist[k]);
                ray.tmin = 0.f;
                ray.tmax = tmax[k];
                if (c.shadowRayLog) c.shadowRayLog->push_back(ray);
                index[m++] = k;
            }
            bool hit[K];
            tracer_.occludedPacket(rays, m, movable, hit);
            for (int j = 0; j < m; ++j) blocked[index[j]] = hit[j] ? -1 : 0;
            c.shadowRays += uint64_t(m);
        }
        for (int k = 0; k < K; ++k) {
            if (!valid[k]) continue;
            sums.f += f[k];
            sums.g += g[k] * f[k];
            if (blocked[k]) continue;
            sums.fv += f[k];
            sums.gv += g[k] * f[k];
        }
    }
    return sums;
}

Vec3 ExactDirect::radiance(const Vec3& p, const Vec3& n, const Vec3& wo, int object, const Light& movable,
                           uint64_t pixel, TraceCounters& counters, ShadowCasters::Counts* settled, bool gloss) const {
    const Scene& scene = tracer_.scene();
    const int mat = scene.objects[size_t(object)].material;
    if (mat < 0) return Vec3(0.f);
    Brdf brdf = brdfs_[size_t(mat)];
    if (!gloss) brdf.ks = Vec3(0.f);
    const bool diffuse = !brdf.kd.isZero(), glossy = !brdf.ks.isZero();
    const Vec3 mirror = reflect(wo, n);
    const Vec3 origin = tracer_.accel().spawnOrigin(p, n, n);  // every shadow ray's origin

    Vec3 L(0.f);
    int areaIndex = 0;
    for (size_t li = 0; li < scene.lights.size(); ++li) {
        const Light& l = int(li) == scene.movableLight ? movable : scene.lights[li];
        if (!l.isArea()) {
            const Vec3 d = l.position - p;
            const float dist2 = lengthSquared(d);
            if (!(dist2 > 0.f)) continue;
            const Vec3 wi = d / std::sqrt(dist2);
            const float cosTheta = dot(wi, n);
            if (cosTheta <= 0.f || !visible(p, n, l.position, movable, counters)) continue;
            const Vec3 lobe = brdf.ks * ((brdf.n + 2.f) * kInv2Pi * powCos(dot(mirror, wi), brdf.n));
            L += l.intensity * (brdf.kd * kInvPi + lobe) * (cosTheta / dist2);
            continue;
        }
        const int r = areaIndex++;
        Vec3 centroid;
        ClippedLight clipped;
        const double omega = projectedSolidAngle(l, p, n, &centroid, &clipped);
        if (!(omega > 0.0)) continue;  // nothing of the light above the horizon
        const float lobeIntegral = glossy ? phongLobeIntegral(l, p, n, mirror, brdf.n) : 0.f;
        if (!diffuse && !(lobeIntegral > 0.f)) continue;

        float rd = 0.f, rg = 0.f;
        bool known = false;
        ShadowCasters::Casters casters;
        if (options_.proofs) {
            casters_.find(origin, n, clipped, object, int(li), movable, counters, casters);
            if (casters.verdict == ShadowCasters::Casters::Verdict::Unoccluded) {
                rd = rg = 1.f;
                known = true;
                if (settled) ++settled->unoccluded;
            } else if (casters.verdict == ShadowCasters::Casters::Verdict::Occluded) {
                known = true;
                if (settled) ++settled->occluded;
            }
        }
        if (!known) {
            const bool segments = options_.proofs && casters.verdict == ShadowCasters::Casters::Verdict::Segments;
            const Sums s = traceSamples(l, r, p, n, mirror, brdf, movable, segments ? &casters : nullptr, pixel, counters);
            if (settled) ++(segments ? settled->segments : settled->rays);
            if (s.f > 0.f) rd = s.fv / s.f;
            else rd = visible(p, n, centroid, movable, counters) ? 1.f : 0.f;
            rg = s.g > 0.f ? s.gv / s.g : rd;
        }
        if (diffuse) L += brdf.kd * l.radiance * float(omega * double(kInvPi) * double(rd));
        if (glossy) L += l.radiance * brdf.ks * ((brdf.n + 2.f) * kInv2Pi * lobeIntegral * rg);
    }
    return L;
}

Image ExactDirect::image(const GBuffer& gb, const Light& movable, uint64_t& nonFinite, ShadowCasters::Counts* settled,
                         TraceCounters* counters) const {
    Image out(gb.width, gb.height);
    std::vector<uint64_t> rowBad(size_t(gb.height), 0);
    std::vector<ShadowCasters::Counts> rowSettled(size_t(gb.height));
    std::vector<TraceCounters> rowCounters(size_t(gb.height));
    tbb::parallel_for(0, gb.height, [&](int y) {
        TraceCounters& c = rowCounters[size_t(y)];
        for (int x = 0; x < gb.width; ++x) {
            const size_t i = size_t(y) * size_t(gb.width) + size_t(x);
            const int id = gb.object[i];
            if (id < 0) continue;
            const float* r = gb.input(i);
            const bool gloss = gb.directWithoutGloss.empty() || !gb.directWithoutGloss[i];
            Vec3 d = radiance(Vec3(r[0], r[1], r[2]), Vec3(r[9], r[10], r[11]), Vec3(r[3], r[4], r[5]), id, movable, i,
                              c, &rowSettled[size_t(y)], gloss);
            if (!d.isFinite()) {
                ++rowBad[size_t(y)];
                d = Vec3(0.f);
            }
            out.set(x, y, d);
        }
    });
    for (int y = 0; y < gb.height; ++y) {
        nonFinite += rowBad[size_t(y)];
        if (settled) settled->add(rowSettled[size_t(y)]);
        if (counters) counters->shadowRays += rowCounters[size_t(y)].shadowRays;
    }
    return out;
}

}  // namespace rrf
