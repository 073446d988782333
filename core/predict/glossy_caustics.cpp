#include "core/predict/glossy_caustics.h"

#include <algorithm>
#include <cmath>

#include "core/predict/exact_direct.h"

namespace rrf {

namespace {
/// Factor on the lobe's Gaussian widths: the importance density's tails stay above the lobe's
/// (f / pdf falls off away from the mirror point), at the cost of a few samples outside the peak.
constexpr float kWiden = 1.5f;
/// Along the ray's trace the width grows as 1/cosθ; at grazing incidence it is capped here.
constexpr float kMinCos = 0.05f;
/// Shift stream of (plane, light) unit u: kShiftBase + u (no sample index reaches it).
constexpr uint64_t kShiftBase = 0xFFFF0000ULL;
}  // namespace

std::vector<GlossyCaustics::Plane> GlossyCaustics::planesOf(const Object& o) {
    std::vector<Plane> planes;
    // Smooth shading turns the lobe about interpolated normals, not the face's plane.
    if (o.kind == Object::Kind::Sphere || o.smooth()) return planes;
    const size_t per = size_t(o.verticesPerPrimitive());
    Bounds3 b = o.bounds();
    const float scale = std::max(1e-6f, length(b.hi - b.lo));
    for (size_t k = 0; k + per <= o.indices.size(); k += per) {
        const Vec3 v0 = o.positions[o.indices[k]], v1 = o.positions[o.indices[k + 1]],
                   v2 = o.positions[o.indices[k + 2]];
        const Vec3 c = cross(v1 - v0, v2 - v0);
        const float len = length(c);
        if (!(len > 0.f)) continue;  // degenerate: no area, no light
        const Vec3 m = c / len;
        const float off = dot(m, v0);
        bool known = false;
        for (const Plane& p : planes)
            if (std::fabs(dot(p.m, m)) > 1.f - 1e-5f && std::fabs(p.c - off * (dot(p.m, m) > 0.f ? 1.f : -1.f)) <= 1e-5f * scale) {
                known = true;
                break;
            }
        if (known) continue;
        if (planes.size() == size_t(kMaxCasterPlanes)) return {};
        planes.push_back({m, off});
    }
    return planes;
}

GlossyCaustics::GlossyCaustics(const PathTracer& tracer, int samples, float minExponent, uint64_t seed)
    : tracer_(tracer), samples_(std::max(1, samples)), seed_(mix64(seed ^ kGlossyCausticStream)) {
    const Scene& scene = tracer.scene();
    planes_.resize(scene.objects.size());
    ks_.assign(scene.objects.size(), Vec3(0.f));
    exponent_.assign(scene.objects.size(), 0.f);
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const Object& o = scene.objects[i];
        if (o.material < 0) continue;
        const Material& m = scene.materials[size_t(o.material)];
        if (!(minExponent > 0.f) || m.type != Material::Type::Phong || m.ks.isZero() || m.exponent < minExponent)
            continue;
        planes_[i] = planesOf(o);
        ks_[i] = m.ks;
        exponent_[i] = m.exponent;
        anyCaster_ = anyCaster_ || !planes_[i].empty();
    }
}

void GlossyCaustics::exclude(int object) {
    if (object < 0 || size_t(object) >= planes_.size()) return;
    planes_[size_t(object)].clear();
    anyCaster_ = false;
    for (const std::vector<Plane>& p : planes_) anyCaster_ = anyCaster_ || !p.empty();
}

Vec3 GlossyCaustics::radiance(const Vec3& p, const Vec3& n, const Vec3& ng, const Vec3& kd, int self,
                              const Light& movable, uint64_t pixel, TraceCounters& counters) const {
    if (kd.isZero() || !anyCaster_) return Vec3(0.f);
    const Scene& scene = tracer_.scene();
    const Accel& accel = tracer_.accel();
    const uint64_t key = Rng::streamKey(seed_, pixel);
    const SampleGrid grid(samples_);
    const Vec3 origin = accel.spawnOrigin(p, ng, ng);
    Vec3 sum(0.f);
    uint64_t unit = 0;  // (plane, light) pairs in scene order: their random numbers
    for (size_t o = 0; o < planes_.size(); ++o) {
        const float e = exponent_[o];
        if (int(o) == self) {  // a face never lights its own object here; keep the streams of the rest
            unit += planes_[o].size() * scene.lights.size();
            continue;
        }
        for (const Plane& plane : planes_[o]) {
            for (size_t li = 0; li < scene.lights.size(); ++li, ++unit) {
                Vec3 m = plane.m;
                float c = plane.c;
                float hx = dot(m, p) - c;
                if (hx < 0.f) {
                    m = -m;
                    c = -c;
                    hx = -hx;
                }
                // On the plane, to the rays' offset (a coplanar receiver: the floor under a box's
                // bottom face): no path reflects there.
                if (!(hx > 4.f * accel.offset(p))) continue;
                const Light& l = int(li) == scene.movableLight ? movable : scene.lights[li];
                const bool area = l.isArea();
                const int count = area ? samples_ : 1;
                const Vec3 lightNormal = area ? l.normal() : Vec3(0.f);
                Rng shiftRng = Rng::ofStream(key, kShiftBase + unit);
                const float su = shiftRng.uniform(), sv = shiftRng.uniform();
                Vec3 acc(0.f);
                for (int s = 0; s < count; ++s) {
                    Rng rng = Rng::ofStream(key, unit * uint64_t(samples_) + uint64_t(s));
                    Vec3 lp = l.position;
                    if (area) {
                        float u, v;
                        grid.point(s, rng, su, sv, u, v);
                        lp = l.pointAt(u, v);
                    }
                    const float g1u = rng.uniform(), g2u = rng.uniform();
                    const float hl = dot(m, lp) - c;
                    if (!(hl > 0.f)) continue;
                    // The unfolded path x → l′ (l mirrored through the plane) and its mirror point.
                    const Vec3 image = lp - (2.f * hl) * m;
                    const Vec3 D = image - p;
                    const float Dlen = length(D);
                    if (!(Dlen > 0.f)) continue;
                    const Vec3 d = D / Dlen;
                    const float t = hx / (hx + hl);
                    const Vec3 y0 = p + D * t;
                    const float a = Dlen * t, b = Dlen * (1.f - t);
                    const float cosT = (hx + hl) / Dlen;
                    Vec3 t1 = d - dot(d, m) * m;
                    const float t1len = length(t1);
                    if (t1len > 1e-6f) t1 = t1 / t1len;
                    else t1 = Frame(m).s;
                    const Vec3 t2 = cross(m, t1);
                    const float sAcross = kWiden / (std::sqrt(std::max(e, 1.f)) * (1.f / a + 1.f / b));
                    const float sAlong = sAcross / std::max(cosT, kMinCos);
                    // Box–Muller: (g1, g2) standard normal.
                    const float r = std::sqrt(-2.f * std::log(1.f - g1u)), phi = 2.f * kPi * g2u;
                    const float g1 = r * std::cos(phi), g2 = r * std::sin(phi);
                    const Vec3 y = y0 + (sAlong * g1) * t1 + (sAcross * g2) * t2;
                    const float pdfY = std::exp(-0.5f * (g1 * g1 + g2 * g2)) / (2.f * kPi * sAlong * sAcross);
                    if (!(pdfY > 0.f)) continue;
                    Vec3 wxy = y - p;
                    const float dxy2 = lengthSquared(wxy), dxy = std::sqrt(dxy2);
                    if (!(dxy > 0.f)) continue;
                    wxy = wxy / dxy;
                    const float cosX = dot(n, wxy);
                    if (cosX <= 0.f || dot(ng, wxy) <= 0.f) continue;
                    Vec3 wyl = lp - y;
                    const float dyl2 = lengthSquared(wyl), dyl = std::sqrt(dyl2);
                    if (!(dyl > 0.f)) continue;
                    wyl = wyl / dyl;
                    float cosL = 1.f;
                    if (area) {
                        cosL = -dot(lightNormal, wyl);
                        if (!l.oneSided) cosL = std::fabs(cosL);
                        if (cosL <= 0.f) continue;
                    }
                    const float cosYx = hx / dxy, cosYl = (dot(m, y) - c + hl) / dyl;  // y on the plane: m·y = c
                    const float cosA = dot(reflect(-wxy, m), wyl);
                    const float lobe = (e + 2.f) * kInv2Pi * powCos(cosA, e);
                    if (!(lobe > 0.f) || !(cosYl > 0.f)) continue;
                    const float geom = cosX * cosYx * cosYl * cosL / (dxy2 * dyl2) / pdfY;
                    const Vec3 emitted = area ? l.radiance * l.area() : l.intensity;
                    const Vec3 value = emitted * ks_[o] * (lobe * geom);
                    if (!value.isFinite() || value.isZero()) continue;
                    // x → y must reach this object's plane at y: visibility and "y is on the face" in one ray.
                    Ray ray;
                    ray.origin = origin;
                    const Vec3 toY = y - origin;
                    const float lenY = length(toY);
                    ray.dir = toY / lenY;
                    ray.tmax = lenY * (1.f + 1e-3f) + accel.offset(y);
                    Hit hit;
                    ++counters.shadowRays;
                    if (!tracer_.intersect(ray, movable, hit) || hit.object != int(o)) continue;
                    if (std::fabs(hit.t - lenY) > 1e-3f * lenY + 4.f * accel.offset(y)) continue;
                    // y → l, as exact direct light's shadow rays (stopped short of the light).
                    Ray sh;
                    sh.origin = accel.spawnOrigin(hit.p, m, wyl);
                    const Vec3 toL = lp - sh.origin;
                    const float lenL = length(toL);
                    sh.tmax = lenL * (1.f - 1e-4f) - accel.offset(lp);
                    if (sh.tmax > 0.f) {
                        sh.dir = toL / lenL;
                        ++counters.shadowRays;
                        if (tracer_.occluded(sh, movable)) continue;
                    }
                    acc += value;
                }
                sum += acc / float(count);
            }
        }
    }
    return sum * kd * kInvPi;
}

}  // namespace rrf
