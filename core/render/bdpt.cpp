#include "core/render/bdpt.h"

#include <algorithm>
#include <cmath>

namespace rrf {

namespace {
/// The light subpaths' stream tag ("BDPTLITE"), so they never share numbers with the camera side.
constexpr uint64_t kLightStream = 0x424450544C495445ULL;

/// Solid-angle density `pdf` at `from` turned into an area density at `to`.
float toArea(float pdf, const BdptVertex& from, const BdptVertex& to) {
    const Vec3 d = to.p - from.p;
    const float d2 = lengthSquared(d);
    if (!(d2 > 0.f)) return 0.f;
    if (to.onSurface()) pdf *= std::fabs(dot(to.ng, d)) / std::sqrt(d2);
    return pdf / d2;
}

/// Light vertex of emitter `index` at point `p` (area) or its position (point light).
BdptVertex lightVertex(const Light& l, int index, const Vec3& p) {
    BdptVertex v;
    v.kind = BdptVertex::Kind::Light;
    v.light = index;
    v.delta = !l.isArea();
    v.p = l.isArea() ? p : l.position;
    if (l.isArea()) v.ng = v.ns = l.normal();
    return v;
}

/// Emitted radiance (area) or intensity (point) of `l` towards unit direction `w` leaving it.
Vec3 emitted(const Light& l, const Vec3& w) { return l.isArea() ? l.emittedTowards(w) : l.intensity; }

/// Solid-angle density with which an emitter's light subpath leaves in direction `w`: cosine
/// around the normal (either side with probability ½ when two-sided), uniform for point lights.
float emissionPdf(const Light& l, const Vec3& w) {
    if (!l.isArea()) return 0.25f * kInvPi;
    const float c = dot(w, l.normal());
    if (l.oneSided) return c > 0.f ? c * kInvPi : 0.f;
    return 0.5f * std::fabs(c) * kInvPi;
}
}  // namespace

Rng bdptLightRng(uint64_t seed, uint64_t stream, uint64_t sample) { return Rng(mix64(seed ^ kLightStream), stream, sample); }

PinholeImportance::PinholeImportance(const Camera& camera, int width, int height)
    : rays_(camera, width, height), eye_(camera.eye), width_(width), height_(height) {
    forward_ = normalize(camera.target - camera.eye);
    const float tanHalf = std::tan(0.5f * camera.fovYDegrees * kPi / 180.f);
    imagePlaneArea_ = 4.f * tanHalf * tanHalf * float(width) / float(height);
}

float PinholeImportance::density(const Vec3& w) const {
    const float c = dot(w, forward_);
    if (c <= 0.f) return 0.f;
    uint32_t pixel;
    if (!pixelOf(w, pixel)) return 0.f;
    return 1.f / (imagePlaneArea_ * c * c * c);
}

bool PinholeImportance::pixelOf(const Vec3& w, uint32_t& pixel) const {
    float x, y;
    if (!rays_.project(w, x, y)) return false;
    if (!(x >= 0.f && x < float(width_) && y >= 0.f && y < float(height_))) return false;
    const int ix = std::min(int(x), width_ - 1), iy = std::min(int(y), height_ - 1);
    pixel = uint32_t(iy) * uint32_t(width_) + uint32_t(ix);
    return true;
}

BidirectionalTracer::BidirectionalTracer(const PathTracer& tracer, int maxDepth, bool lightTracingOnly)
    : tracer_(tracer), maxDepth_(std::max(1, maxDepth)), lightTracingOnly_(lightTracingOnly) {
    // Emitters are picked by power (area · π · radiance, 4π · intensity), which moving the movable
    // light does not change; a scene whose emitters are all black gets uniform picks.
    const Scene& scene = tracer.scene();
    double total = 0.0;
    std::vector<double> power;
    for (const Light& l : scene.lights) {
        const double p = l.isArea() ? double(l.area()) * kPi * double(l.radiance.sum()) * (l.oneSided ? 1.0 : 2.0)
                                    : 4.0 * kPi * double(l.intensity.sum());
        power.push_back(std::max(0.0, p));
        total += power.back();
    }
    if (!(total > 0.0)) {
        std::fill(power.begin(), power.end(), 1.0);
        total = double(power.size());
    }
    double run = 0.0;
    for (double p : power) {
        run += p;
        lightCdf_.push_back(run);
        lightPick_.push_back(float(p / total));
    }
}

int BidirectionalTracer::pickLight(float u) const {
    if (lightCdf_.empty()) return -1;
    const double target = double(u) * lightCdf_.back();
    const auto it = std::upper_bound(lightCdf_.begin(), lightCdf_.end(), target);
    return int(std::min(size_t(it - lightCdf_.begin()), lightCdf_.size() - 1));
}

float BidirectionalTracer::pdfLightOrigin(int light, const Light& movable) const {
    if (light < 0 || size_t(light) >= lightPick_.size()) return 0.f;
    const Light& l = tracer_.light(light, movable);
    return l.isArea() ? lightPick_[size_t(light)] / l.area() : lightPick_[size_t(light)];
}

float BidirectionalTracer::pdfLight(const BdptVertex& lv, const BdptVertex& next, const Light& movable) const {
    const Light& l = tracer_.light(lv.light, movable);
    const Vec3 d = next.p - lv.p;
    const float d2 = lengthSquared(d);
    if (!(d2 > 0.f)) return 0.f;
    const Vec3 w = d / std::sqrt(d2);
    float pdf = emissionPdf(l, w) / d2;
    if (next.onSurface()) pdf *= std::fabs(dot(next.ng, w));
    return pdf;
}

Vec3 BidirectionalTracer::f(const BdptVertex& v, const Vec3& wa, const Vec3& wb, bool importance) const {
    if (v.kind != BdptVertex::Kind::Surface || v.material < 0) return Vec3(0.f);
    // Two-sided surfaces reflect on the side both directions are on (as the path tracer shades the
    // side it sees); directions on opposite sides of the geometric surface do not connect.
    const float sa = dot(wa, v.ng), sb = dot(wb, v.ng);
    if (!(sa * sb > 0.f)) return Vec3(0.f);
    const Frame frame(sa > 0.f ? v.ns : -v.ns);
    Vec3 value = tracer_.brdf(v.material).eval(frame.toLocal(wa), frame.toLocal(wb));
    if (importance) {
        // Adjoint BRDF with shading normals (Veach 1997 §5.3; pbrt's CorrectShadingNormal): light
        // arrives along wa and leaves along wb; the factor is 1 wherever ns = ng.
        const float den = std::fabs(sa) * std::fabs(dot(wb, v.ns));
        value = den > 0.f ? value * (std::fabs(dot(wa, v.ns)) * std::fabs(sb) / den) : Vec3(0.f);
    }
    return value;
}

float BidirectionalTracer::pdfArea(const BdptVertex& v, const BdptVertex* prev, const BdptVertex& next,
                                   const PinholeImportance* camera, const Light& movable) const {
    if (v.kind == BdptVertex::Kind::Light) return pdfLight(v, next, movable);
    const Vec3 d = next.p - v.p;
    const float len = length(d);
    if (!(len > 0.f)) return 0.f;
    const Vec3 wn = d / len;
    if (v.kind == BdptVertex::Kind::Camera) return camera ? toArea(camera->density(wn), v, next) : 0.f;
    if (v.material < 0) return 0.f;
    const Vec3 wp = prev ? normalize(prev->p - v.p) : v.wPrev;
    const float sp = dot(wp, v.ng), sn = dot(wn, v.ng);
    if (!(sp * sn > 0.f)) return 0.f;
    const Frame frame(sp > 0.f ? v.ns : -v.ns);
    return toArea(tracer_.brdf(v.material).pdf(frame.toLocal(wp), frame.toLocal(wn)), v, next);
}

bool BidirectionalTracer::visible(const BdptVertex& a, const BdptVertex& b, const Light& movable,
                                  TraceCounters& counters) const {
    const Accel& accel = tracer_.accel();
    const Vec3 d0 = b.p - a.p;
    const float len0 = length(d0);
    if (!(len0 > 0.f)) return false;
    const Vec3 w = d0 / len0;
    Ray s;
    s.origin = a.onSurface() ? accel.spawnOrigin(a.p, a.ng, w) : a.p;
    const Vec3 d = b.p - s.origin;
    const float dist = length(d);
    // Stop short of the target so its own surface (or the light's quad) does not occlude it.
    s.tmax = dist * (1.f - 1e-4f) - (b.onSurface() ? accel.offset(b.p) : 0.f);
    if (!(s.tmax > 0.f)) return true;
    s.dir = d / dist;
    ++counters.shadowRays;
    if (counters.shadowRayLog) counters.shadowRayLog->push_back(s);
    return !tracer_.occluded(s, movable);
}

bool BidirectionalTracer::scatter(std::vector<BdptVertex>& path, Vec3& beta, float beta0, int bounces, bool importance,
                                  Ray& ray, float& pdfDir, Rng& rng) const {
    BdptVertex& cur = path.back();
    if (cur.material < 0) return false;
    const float side = dot(cur.wPrev, cur.ng);
    if (side == 0.f) return false;
    const Frame frame(side > 0.f ? cur.ns : -cur.ns);
    const Vec3 woLocal = frame.toLocal(cur.wPrev);
    const Brdf& brdf = tracer_.brdf(cur.material);
    const float uLobe = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    Vec3 wiLocal, weight;
    if (!brdf.sample(woLocal, uLobe, u1, u2, wiLocal, weight)) return false;
    const Vec3 wi = frame.toWorld(wiLocal);
    // As the path tracer: a direction above the shading normal but below the geometric surface ends the path.
    if (dot(wi, cur.ng) * side <= 0.f) return false;
    const float pdfFwd = brdf.pdf(woLocal, wiLocal), pdfRev = brdf.pdf(wiLocal, woLocal);
    if (!(pdfFwd > 0.f)) return false;
    beta *= weight;
    if (importance) {
        const float den = std::fabs(side) * std::fabs(wiLocal.z);
        beta = den > 0.f ? beta * (std::fabs(woLocal.z) * std::fabs(dot(wi, cur.ng)) / den) : Vec3(0.f);
    }
    if (bounces >= 2) {
        // Russian roulette on the throughput relative to the subpath's start, bounded away from 0.
        const float q = std::clamp(beta.maxComponent() / beta0, 0.05f, 1.f);
        if (q < 1.f) {
            if (rng.uniform() >= q) return false;
            beta = beta / q;
        }
    }
    if (beta.isZero() || !beta.isFinite()) return false;
    if (path.size() >= 2) {
        BdptVertex& prev = path[path.size() - 2];
        prev.pdfRev = toArea(pdfRev, cur, prev);
    }
    ray = Ray{};
    ray.origin = tracer_.accel().spawnOrigin(cur.p, cur.ng, wi);
    ray.dir = wi;
    pdfDir = pdfFwd;
    return true;
}

BdptVertex BidirectionalTracer::surfaceVertex(const Hit& hit, const Vec3& beta, const Vec3& wPrev) const {
    BdptVertex v;
    v.p = hit.p;
    v.ng = hit.ng;
    v.ns = hit.shading();
    v.material = tracer_.materialOf(hit);
    v.light = hit.light;
    v.beta = beta;
    v.wPrev = wPrev;
    return v;
}

void BidirectionalTracer::walk(Ray ray, Vec3 beta, float pdfDir, bool importance, std::vector<BdptVertex>& path,
                               int maxVertices, const Light& movable, Rng& rng, TraceCounters& counters,
                               int bounces) const {
    const float beta0 = std::max(beta.maxComponent(), 1e-30f);
    for (; int(path.size()) < maxVertices; ++bounces) {
        Hit hit;
        ++counters.rays;
        if (counters.rayLog) counters.rayLog->push_back(ray);
        if (!tracer_.intersect(ray, movable, hit)) return;
        BdptVertex v = surfaceVertex(hit, beta, -ray.dir);
        v.pdfFwd = toArea(pdfDir, path.back(), v);
        // A light subpath that reaches a black emitter ends without a vertex: nothing connects to it.
        if (importance && v.material < 0) return;
        path.push_back(v);
        if (int(path.size()) >= maxVertices) return;
        if (!scatter(path, beta, beta0, bounces, importance, ray, pdfDir, rng)) return;
    }
}

void BidirectionalTracer::lightSubpath(std::vector<BdptVertex>& path, int maxVertices, const Light& movable, Rng& rng,
                                       TraceCounters& counters) const {
    path.clear();
    const float uPick = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform(), uSide = rng.uniform(),
                u3 = rng.uniform(), u4 = rng.uniform();
    const int index = pickLight(uPick);
    if (index < 0) return;
    const Light& l = tracer_.light(index, movable);
    BdptVertex v0 = lightVertex(l, index, l.isArea() ? l.pointAt(u1, u2) : Vec3(0.f));
    v0.pdfFwd = pdfLightOrigin(index, movable);
    Vec3 w;
    if (l.isArea()) {
        const Vec3 n = (!l.oneSided && uSide < 0.5f) ? -v0.ng : v0.ng;
        w = Frame(n).toWorld(sampleCosineHemisphere(u3, u4));
    } else {
        w = sampleUniformSphere(u3, u4);
    }
    const float pdfDir = emissionPdf(l, w);
    const Vec3 Le = emitted(l, w);
    if (!(pdfDir > 0.f) || !(v0.pdfFwd > 0.f) || Le.isZero()) return;
    v0.beta = Le;
    path.push_back(v0);
    if (maxVertices <= 1) return;
    const float cosL = l.isArea() ? std::fabs(dot(w, v0.ng)) : 1.f;
    Ray ray;
    ray.origin = l.isArea() ? tracer_.accel().spawnOrigin(v0.p, v0.ng, w) : v0.p;
    ray.dir = w;
    walk(ray, Le * (cosL / (v0.pdfFwd * pdfDir)), pdfDir, true, path, maxVertices, movable, rng, counters);
}

}  // namespace rrf
