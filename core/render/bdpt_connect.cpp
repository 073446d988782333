// Connection of the two subpaths of a bidirectional sample and the multiple-importance weights of
// each strategy (core/render/bdpt.h).
#include <cmath>

#include "core/render/bdpt.h"

namespace rrf {

namespace {
/// pbrt's remap0: a density of 0 (a vertex no strategy samples, e.g. the record's own point) counts as 1.
float remap0(float f) { return f != 0.f ? f : 1.f; }
}  // namespace

struct BidirectionalTracer::Paths {
    std::vector<BdptVertex> light, eye;
    bool cameraMode = true;
};

bool BidirectionalTracer::allowed(int s, int t, bool cameraMode) const {
    if (t < 1) return false;                              // no light subpath hits a pinhole or a record's point
    if (cameraMode && t == 1 && s < 2) return false;      // the camera vertex alone, or camera to the light (pbrt)
    if (lightTracingOnly_ && s >= 2 && !(cameraMode && t == 1)) return false;
    return true;
}

float BidirectionalTracer::misWeight(const Paths& paths, const BdptVertex& sampled, int s, int t, bool cameraMode,
                                     const PinholeImportance* camera, const Light& movable) const {
    // pbrt-v3's MISWeight with the power heuristic: the densities of the connection vertices and
    // their neighbours change with the connection; everything else is as sampled.
    const BdptVertex* qs = s > 0 ? (s == 1 ? &sampled : &paths.light[size_t(s - 1)]) : nullptr;
    const BdptVertex* pt = &paths.eye[size_t(t - 1)];
    const BdptVertex* qsMinus = s > 1 ? &paths.light[size_t(s - 2)] : nullptr;
    const BdptVertex* ptMinus = t > 1 ? &paths.eye[size_t(t - 2)] : nullptr;
    auto lightFwd = [&](int i) { return s == 1 && i == 0 ? sampled.pdfFwd : paths.light[size_t(i)].pdfFwd; };
    auto lightRev = [&](int i) -> float {
        if (i == s - 1) return pdfArea(*pt, ptMinus, *qs, camera, movable);
        if (i == s - 2) return pdfArea(*qs, pt, *qsMinus, camera, movable);
        return paths.light[size_t(i)].pdfRev;
    };
    auto eyeRev = [&](int i) -> float {
        if (i == t - 1) return s > 0 ? pdfArea(*qs, qsMinus, *pt, camera, movable) : pdfLightOrigin(pt->light, movable);
        if (i == t - 2) return s > 0 ? pdfArea(*pt, qs, *ptMinus, camera, movable) : pdfLight(*pt, *ptMinus, movable);
        return paths.eye[size_t(i)].pdfRev;
    };
    double sum = 0.0, r = 1.0;
    // Shorter eye subpaths: strategy (s + t − i, i).
    for (int i = t - 1; i > 0; --i) {
        r *= double(remap0(eyeRev(i))) / double(remap0(paths.eye[size_t(i)].pdfFwd));
        if (allowed(s + t - i, i, cameraMode)) sum += r * r;
    }
    // Shorter light subpaths: strategy (i, s + t − i); a point light cannot be hit (i = 0).
    r = 1.0;
    const bool deltaLight = s > 0 && (s == 1 ? sampled.delta : paths.light[0].delta);
    for (int i = s - 1; i >= 0; --i) {
        r *= double(remap0(lightRev(i))) / double(remap0(lightFwd(i)));
        if (!(i == 0 && deltaLight) && allowed(i, s + t - i, cameraMode)) sum += r * r;
    }
    const double w = 1.0 / (1.0 + sum);
    return std::isfinite(w) ? float(w) : 0.f;
}

Radiance BidirectionalTracer::connect(Paths& paths, const PinholeImportance* camera, const Light& movable, Rng& rng,
                                      TraceCounters& counters, std::vector<Splat>* splats) const {
    Radiance L;
    const bool cameraMode = paths.cameraMode;
    const int maxReflections = tracer_.effects().indirect ? maxDepth_ : 1;
    const int nLight = int(paths.light.size()), nEye = int(paths.eye.size());
    for (int t = 1; t <= nEye; ++t) {
        for (int s = 0; s <= nLight; ++s) {
            // Reflections of the path: every vertex but the camera, the light-subpath origin and an
            // eye vertex that ends on an emitter (s = 0).
            const int reflections = s + t - 2 + (cameraMode ? 0 : 1);
            if (reflections < 0 || reflections > maxReflections || !allowed(s, t, cameraMode)) continue;
            if (!cameraMode && s == 0 && t == 1) continue;  // the record's own emission: added by shade()
            Vec3 c(0.f);
            BdptVertex sampled;
            uint32_t pixel = 0;
            const bool splat = cameraMode && t == 1;
            if (s == 0) {
                const BdptVertex& pt = paths.eye[size_t(t - 1)];
                if (pt.kind != BdptVertex::Kind::Surface || pt.light < 0) continue;
                c = pt.beta * tracer_.light(pt.light, movable).emittedTowards(pt.wPrev);
                if (c.isZero()) continue;
            } else if (splat) {
                const BdptVertex& qs = paths.light[size_t(s - 1)];
                const Vec3 d = camera->eye() - qs.p;
                const float dist2 = lengthSquared(d);
                if (!(dist2 > 0.f)) continue;
                const Vec3 w = d / std::sqrt(dist2);
                if (!camera->pixelOf(-w, pixel)) continue;
                c = qs.beta * f(qs, qs.wPrev, w, true) * (std::fabs(dot(qs.ns, w)) / dist2 * camera->density(-w));
                if (c.isZero() || !visible(qs, paths.eye[0], movable, counters)) continue;
                sampled = paths.eye[0];
            } else if (s == 1) {
                const BdptVertex& pt = paths.eye[size_t(t - 1)];
                const float uPick = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
                if (pt.kind != BdptVertex::Kind::Surface || pt.material < 0) continue;
                const int index = pickLight(uPick);
                if (index < 0) continue;
                const Light& l = tracer_.light(index, movable);
                sampled = BdptVertex{};
                sampled.kind = BdptVertex::Kind::Light;
                sampled.light = index;
                sampled.delta = !l.isArea();
                sampled.p = l.isArea() ? l.pointAt(u1, u2) : l.position;
                if (l.isArea()) sampled.ng = sampled.ns = l.normal();
                sampled.pdfFwd = pdfLightOrigin(index, movable);
                const Vec3 d = sampled.p - pt.p;
                const float dist2 = lengthSquared(d);
                if (!(dist2 > 0.f) || !(sampled.pdfFwd > 0.f)) continue;
                const Vec3 w = d / std::sqrt(dist2);
                const Vec3 Le = l.isArea() ? l.emittedTowards(-w) : l.intensity;
                const float G = std::fabs(dot(pt.ns, w)) * (l.isArea() ? std::fabs(dot(sampled.ng, w)) : 1.f) / dist2;
                c = pt.beta * f(pt, pt.wPrev, w, false) * Le * (G / sampled.pdfFwd);
                if (c.isZero() || !visible(pt, sampled, movable, counters)) continue;
            } else {
                const BdptVertex& qs = paths.light[size_t(s - 1)];
                const BdptVertex& pt = paths.eye[size_t(t - 1)];
                if (pt.kind != BdptVertex::Kind::Surface || pt.material < 0) continue;
                const Vec3 d = pt.p - qs.p;
                const float dist2 = lengthSquared(d);
                if (!(dist2 > 0.f)) continue;
                const Vec3 w = d / std::sqrt(dist2);
                const float G = std::fabs(dot(qs.ns, w)) * std::fabs(dot(pt.ns, w)) / dist2;
                c = qs.beta * f(qs, qs.wPrev, w, true) * f(pt, pt.wPrev, -w, false) * pt.beta * G;
                if (c.isZero() || !visible(qs, pt, movable, counters)) continue;
            }
            c *= misWeight(paths, sampled, s, t, cameraMode, camera, movable);
            Radiance add;
            (reflections <= 1 ? add.direct : add.indirect) = c;
            if (splat) {
                splats->push_back({pixel, add});
            } else {
                L.direct += add.direct;
                L.indirect += add.indirect;
            }
        }
    }
    return L;
}

Radiance BidirectionalTracer::tracePixel(const CameraRays& rays, const PinholeImportance& camera, int px, int py,
                                         const Light& movable, Rng& rng, Rng& lightRng, TraceCounters& counters,
                                         std::vector<Splat>& splats, bool cameraPaths) const {
    thread_local Paths paths;
    paths.cameraMode = true;
    paths.eye.clear();
    const int maxReflections = tracer_.effects().indirect ? maxDepth_ : 1;
    const float jx = rng.uniform(), jy = rng.uniform();
    const Ray ray = rays.generate(px, py, jx, jy);
    BdptVertex cam;
    cam.kind = BdptVertex::Kind::Camera;
    cam.p = camera.eye();
    cam.beta = Vec3(1.f);
    paths.eye.push_back(cam);
    if (cameraPaths)
        walk(ray, Vec3(1.f), camera.density(ray.dir), false, paths.eye, maxReflections + 2, movable, rng, counters);
    lightSubpath(paths.light, maxReflections + 1, movable, lightRng, counters);
    return connect(paths, &camera, movable, rng, counters, &splats);
}

Radiance BidirectionalTracer::shade(const Hit& hit, const Vec3& wo, const Light& movable, Rng& rng,
                                    TraceCounters& counters) const {
    thread_local Paths paths;
    paths.cameraMode = false;
    paths.eye.clear();
    Radiance L;
    if (hit.light >= 0) L.direct += tracer_.light(hit.light, movable).emittedTowards(wo);
    const int maxReflections = tracer_.effects().indirect ? maxDepth_ : 1;
    const BdptVertex x = surfaceVertex(hit, Vec3(1.f), wo);
    paths.eye.push_back(x);
    if (x.material < 0) return L;
    Vec3 beta(1.f);
    Ray ray;
    float pdfDir = 0.f;
    if (scatter(paths.eye, beta, 1.f, 0, false, ray, pdfDir, rng))
        walk(ray, beta, pdfDir, false, paths.eye, maxReflections + 1, movable, rng, counters, 1);
    // A record's paths reflect at its own point, so their light subpaths need one vertex less.
    lightSubpath(paths.light, maxReflections, movable, rng, counters);
    const Radiance c = connect(paths, nullptr, movable, rng, counters, nullptr);
    L.direct += c.direct;
    L.indirect += c.indirect;
    return L;
}

}  // namespace rrf
