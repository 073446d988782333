#include "core/predict/shadow_casters.h"

#include <algorithm>
#include <cmath>

namespace rrf {

namespace {

/// Unit `v`, or zero when it is too short to give a direction.
Vec3 unitOrZero(const Vec3& v) {
    const float len = length(v);
    return len > 1e-20f ? v / len : Vec3(0.f);
}

/// Appends direction d to `dirs` unless it (or its opposite) is there already.
void addDirection(std::vector<Vec3>& dirs, const Vec3& d) {
    const Vec3 u = unitOrZero(d);
    if (u.isZero()) return;
    for (const Vec3& e : dirs)
        if (std::fabs(dot(e, u)) > 1.f - 1e-6f) return;
    dirs.push_back(u);
}

/// Unit normal of the planar polygon v[0..count) by Newell's method (the polygon turns
/// counter-clockwise about it); zero for a degenerate one.
Vec3 polygonNormal(const Vec3* v, int count) {
    Vec3 n(0.f);
    for (int k = 0; k < count; ++k) n += cross(v[k], v[(k + 1) % count]);
    return unitOrZero(n);
}

/// True when the planar polygon turns the same way at every corner.
bool convexPolygon(const Vec3* v, int count) {
    const Vec3 n = polygonNormal(v, count);
    if (n.isZero()) return false;
    for (int k = 0; k < count; ++k) {
        const Vec3 a = v[(k + 1) % count] - v[k], b = v[(k + 2) % count] - v[(k + 1) % count];
        if (dot(cross(a, b), n) < 0.f) return false;
    }
    return true;
}

void interval(const Vec3* v, size_t count, const Vec3& axis, float& lo, float& hi) {
    lo = hi = dot(v[0], axis);
    for (size_t k = 1; k < count; ++k) {
        const float d = dot(v[k], axis);
        lo = std::min(lo, d);
        hi = std::max(hi, d);
    }
}

float maxAbs(const Vec3& v) { return std::max(std::fabs(v.x), std::max(std::fabs(v.y), std::fabs(v.z))); }

}  // namespace

void ShadowCasters::Counts::add(const Counts& o) {
    unoccluded += o.unoccluded;
    occluded += o.occluded;
    segments += o.segments;
    rays += o.rays;
}

bool ShadowCasters::Hull::outside(const Vec3& x, float margin) const {
    if (kind == Kind::Sphere) return length(x - center) > radius + margin;
    for (size_t k = 0; k < planeN.size(); ++k)
        if (dot(planeN[k], x) > planeD[k] + margin) return true;
    return false;
}

bool ShadowCasters::Hull::blocks(const Ray& ray) const {
    switch (kind) {
        case Kind::Solid: {
            // Clip the ray's interval against every face's half-space (Cyrus–Beck).
            float t0 = ray.tmin, t1 = ray.tmax;
            for (size_t k = 0; k < planeN.size(); ++k) {
                const float den = dot(planeN[k], ray.dir), num = planeD[k] - dot(planeN[k], ray.origin);
                if (den == 0.f) {
                    if (num < 0.f) return false;
                    continue;
                }
                const float t = num / den;
                if (den > 0.f) t1 = std::min(t1, t);
                else t0 = std::max(t0, t);
                if (t0 > t1) return false;
            }
            return !(t0 <= ray.tmin && t1 >= ray.tmax);  // wholly inside crosses no face
        }
        case Kind::Polygon: {
            const float den = dot(planeN[0], ray.dir);
            if (den == 0.f) return false;
            const float t = (planeD[0] - dot(planeN[0], ray.origin)) / den;
            if (!(t >= ray.tmin && t <= ray.tmax)) return false;
            const Vec3 q = ray.origin + ray.dir * t;
            for (size_t k = 1; k < planeN.size(); ++k)
                if (dot(planeN[k], q) < planeD[k]) return false;
            return true;
        }
        case Kind::Sphere: {
            const Vec3 oc = ray.origin - center;
            const float b = dot(oc, ray.dir), c = dot(oc, oc) - radius * radius, disc = b * b - c;
            if (disc < 0.f) return false;
            const float s = std::sqrt(disc), ta = -b - s, tb = -b + s;
            return (ta >= ray.tmin && ta <= ray.tmax) || (tb >= ray.tmin && tb <= ray.tmax);
        }
        case Kind::Bounds: break;
    }
    return true;  // a bound proves nothing: count it as a hit (never used for Segments)
}

void ShadowCasters::Hull::blocksBatch(const Vec3& o, const float* dx, const float* dy, const float* dz,
                                      const float* end, int32_t* blocked) const {
    // Lane by lane with int masks, selects and no early exits: loops the compiler vectorises.
    switch (kind) {
        case Kind::Solid: {
            alignas(16) float t0[kBatch], t1[kBatch];
            alignas(16) int32_t miss[kBatch];
            for (int k = 0; k < kBatch; ++k) {
                t0[k] = 0.f;
                t1[k] = end[k];
                miss[k] = 0;
            }
            for (size_t f = 0; f < planeN.size(); ++f) {
                const Vec3 n = planeN[f];
                const float num = planeD[f] - dot(n, o);
                const int32_t outsideSlab = num < 0.f ? -1 : 0;
                for (int k = 0; k < kBatch; ++k) {
                    const float den = n.x * dx[k] + n.y * dy[k] + n.z * dz[k];
                    const float t = num / den;  // ±inf or NaN for den = 0, where neither bound moves
                    miss[k] |= den == 0.f ? outsideSlab : 0;
                    const float lower = t < t1[k] ? t : t1[k], upper = t > t0[k] ? t : t0[k];
                    t1[k] = den > 0.f ? lower : t1[k];
                    t0[k] = den < 0.f ? upper : t0[k];
                }
            }
            // The surface is crossed when part of the segment is inside, but not all of it (a ray
            // from inside a room to a light inside it crosses nothing).
            for (int k = 0; k < kBatch; ++k)
                blocked[k] |= (t0[k] <= t1[k] ? -1 : 0) & ~miss[k] & (t0[k] <= 0.f && t1[k] >= end[k] ? 0 : -1);
            return;
        }
        case Kind::Polygon: {
            const Vec3 n = planeN[0];
            const float num = planeD[0] - dot(n, o);
            alignas(16) int32_t hit[kBatch];
            alignas(16) float qx[kBatch], qy[kBatch], qz[kBatch];
            for (int k = 0; k < kBatch; ++k) {
                const float den = n.x * dx[k] + n.y * dy[k] + n.z * dz[k];
                const float t = num / den;
                hit[k] = (den != 0.f ? -1 : 0) & (t >= 0.f ? -1 : 0) & (t <= end[k] ? -1 : 0);
                qx[k] = o.x + dx[k] * t;
                qy[k] = o.y + dy[k] * t;
                qz[k] = o.z + dz[k] * t;
            }
            for (size_t e = 1; e < planeN.size(); ++e) {
                const Vec3 m = planeN[e];
                const float d = planeD[e];
                for (int k = 0; k < kBatch; ++k) hit[k] &= m.x * qx[k] + m.y * qy[k] + m.z * qz[k] >= d ? -1 : 0;
            }
            for (int k = 0; k < kBatch; ++k) blocked[k] |= hit[k];
            return;
        }
        case Kind::Sphere: {
            const Vec3 oc = o - center;
            const float c = dot(oc, oc) - radius * radius;
            for (int k = 0; k < kBatch; ++k) {
                const float a = dx[k] * dx[k] + dy[k] * dy[k] + dz[k] * dz[k];
                const float b = oc.x * dx[k] + oc.y * dy[k] + oc.z * dz[k];
                const float disc = b * b - a * c;
                const float s = std::sqrt(disc > 0.f ? disc : 0.f);
                const float ta = (-b - s) / a, tb = (-b + s) / a;
                const int32_t in = (ta >= 0.f ? -1 : 0) & (ta <= end[k] ? -1 : 0);
                const int32_t out = (tb >= 0.f ? -1 : 0) & (tb <= end[k] ? -1 : 0);
                blocked[k] |= (disc >= 0.f ? -1 : 0) & (in | out);
            }
            return;
        }
        case Kind::Bounds: break;
    }
    for (int k = 0; k < kBatch; ++k) blocked[k] = -1;  // a bound proves nothing (never used for Segments)
}

void ShadowCasters::setBound(Hull& h) {
    if (h.kind == Hull::Kind::Sphere) {
        h.boundCenter = h.center;
        h.boundRadius = h.radius;
        return;
    }
    h.boundCenter = h.box.center();
    h.boundRadius = 0.f;
    for (const Vec3& x : h.vertices) h.boundRadius = std::max(h.boundRadius, length(x - h.boundCenter));
}

ShadowCasters::Hull ShadowCasters::polygonHull(const Vec3* v, int count) {
    Hull h;
    h.kind = Hull::Kind::Polygon;
    h.vertices.assign(v, v + count);
    const Vec3 n = polygonNormal(v, count);
    h.axes.push_back(n);
    h.planeN.push_back(n);
    h.planeD.push_back(dot(n, v[0]));
    for (int k = 0; k < count; ++k) {
        const Vec3 e = v[(k + 1) % count] - v[k];
        addDirection(h.edges, e);
        const Vec3 m = cross(n, e);  // points into the polygon: it turns counter-clockwise about n
        h.planeN.push_back(m);
        h.planeD.push_back(dot(m, v[k]));
        h.box.expand(v[k]);
    }
    return h;
}

ShadowCasters::Hull ShadowCasters::boundsHull(const Bounds3& b) {
    Hull h;
    for (int k = 0; k < 8; ++k)
        h.vertices.push_back(Vec3(k & 1 ? b.hi.x : b.lo.x, k & 2 ? b.hi.y : b.lo.y, k & 4 ? b.hi.z : b.lo.z));
    h.axes = {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    h.edges = h.axes;
    h.box = b;
    return h;
}

ShadowCasters::ShadowCasters(const PathTracer& tracer) : tracer_(tracer), sceneScale_(tracer.scene().scale()) {
    const Scene& scene = tracer.scene();
    const float tol = 1e-5f * sceneScale_;
    constexpr size_t kAnalysedPrims = 64;  // set-up and the per-receiver search stay small
    for (const Object& o : scene.objects) {
        const int id = o.id;
        std::vector<char> primConvex;
        int solidIndex = -1;
        if (o.kind == Object::Kind::Sphere) {
            Hull h;
            h.kind = Hull::Kind::Sphere;
            h.center = o.center;
            h.radius = o.radius;
            h.box.expand(o.center - Vec3(o.radius));
            h.box.expand(o.center + Vec3(o.radius));
            setBound(h);
            solidIndex = int(hulls_.size());
            hulls_.push_back({std::move(h), id});
            solidIndex_.push_back(solidIndex);
            convexPrim_.push_back({});
            continue;
        }
        const int vp = o.verticesPerPrimitive();
        const size_t prims = o.primitiveCount();
        auto primVertices = [&](size_t k, Vec3* v) {
            for (int j = 0; j < vp; ++j) v[j] = o.positions[o.indices[k * size_t(vp) + size_t(j)]];
        };
        for (size_t k = 0; k < prims; ++k) {
            Vec3 v[4];
            primVertices(k, v);
            primConvex.push_back(char(convexPolygon(v, vp)));
        }
        // A convex solid: closed, and every vertex behind every primitive's plane (which gives the
        // outward normals). Its one hull blocks from outside and is cheaper than its faces.
        bool solid = o.closed && prims > 0 && prims <= kAnalysedPrims;
        std::vector<Vec3> outward;
        std::vector<float> offsets;
        for (size_t k = 0; solid && k < prims; ++k) {
            Vec3 v[4];
            primVertices(k, v);
            Vec3 nk = polygonNormal(v, vp);
            bool above = false, below = false;
            for (const Vec3& x : o.positions) {
                const float d = dot(nk, x - v[0]);
                above |= d > tol;
                below |= d < -tol;
            }
            if (nk.isZero() || (above && below) || (!above && !below)) solid = false;  // bent, or flat
            if (above) nk = -nk;
            outward.push_back(nk);
            offsets.push_back(dot(nk, v[0]));
        }
        if (solid) {
            Hull h;
            h.kind = Hull::Kind::Solid;
            for (const Vec3& x : o.positions)  // a box's faces share corners: project each once
                if (std::find(h.vertices.begin(), h.vertices.end(), x) == h.vertices.end()) h.vertices.push_back(x);
            for (const Vec3& nk : outward) addDirection(h.axes, nk);
            h.planeN = std::move(outward);
            h.planeD = std::move(offsets);
            for (size_t k = 0; k < prims; ++k) {
                Vec3 v[4];
                primVertices(k, v);
                for (int j = 0; j < vp; ++j) addDirection(h.edges, v[(j + 1) % vp] - v[j]);
            }
            for (const Vec3& x : h.vertices) {
                h.box.expand(x);
                h.center += x / float(h.vertices.size());
            }
            setBound(h);
            solidIndex = int(hulls_.size());
            hulls_.push_back({std::move(h), id});
        } else if (prims <= kAnalysedPrims) {
            // Each convex primitive is its own exact hull (a wall, one face of an open mesh).
            Bounds3 rest;
            for (size_t k = 0; k < prims; ++k) {
                Vec3 v[4];
                primVertices(k, v);
                if (!primConvex[k] || polygonNormal(v, vp).isZero()) {
                    for (int j = 0; j < vp; ++j) rest.expand(v[j]);
                    continue;
                }
                Hull h = polygonHull(v, vp);
                setBound(h);
                hulls_.push_back({std::move(h), id});
            }
            if (!rest.empty()) {
                Hull h = boundsHull(rest);
                setBound(h);
                hulls_.push_back({std::move(h), id});
            }
        } else {
            Hull h = boundsHull(o.bounds());
            setBound(h);
            hulls_.push_back({std::move(h), id});
        }
        solidIndex_.push_back(solidIndex);
        convexPrim_.push_back(std::move(primConvex));
    }
    for (const Light& l : scene.lights) {
        Vec3 v[4];
        lightHulls_.push_back(l.isArea() ? polygonHull(v, l.vertices(v)) : Hull{});
        setBound(lightHulls_.back());
    }
}

bool ShadowCasters::separated(const Hull& h, const Vec3* pyr, int count, const Vec3* faces, const Bounds3& pb,
                              float margin) {
    const Bounds3& hb = h.box;
    if (pb.hi.x + margin < hb.lo.x || hb.hi.x + margin < pb.lo.x || pb.hi.y + margin < hb.lo.y ||
        hb.hi.y + margin < pb.lo.y || pb.hi.z + margin < hb.lo.z || hb.hi.z + margin < pb.lo.z)
        return true;
    const int m = count - 1;  // base vertices pyr[1..m]; faces[0] the base, faces[1..m] the sides
    // The bounding sphere against the pyramid's face axes: exact for a sphere (but for the pyramid's
    // edges and corners), and for other hulls a cheap test before the full one.
    for (int k = 0; k <= m; ++k) {
        if (faces[k].isZero()) continue;
        float lo, hi;
        interval(pyr, size_t(count), faces[k], lo, hi);
        const float c = dot(h.boundCenter, faces[k]);
        if (c - h.boundRadius > hi + margin || c + h.boundRadius < lo - margin) return true;
    }
    if (h.kind == Hull::Kind::Sphere) return false;
    auto apart = [&](const Vec3& axis) {
        if (axis.isZero()) return false;
        float plo, phi, hlo, hhi;
        interval(pyr, size_t(count), axis, plo, phi);
        interval(h.vertices.data(), h.vertices.size(), axis, hlo, hhi);
        return phi + margin < hlo || hhi + margin < plo;
    };
    for (const Vec3& a : h.axes)
        if (apart(a)) return true;
    for (int k = 0; k <= m; ++k)
        if (apart(faces[k])) return true;
    for (int k = 0; k < m; ++k) {
        const Vec3 side = pyr[1 + k] - pyr[0], rim = pyr[1 + (k + 1) % m] - pyr[1 + k];
        for (const Vec3& e : h.edges)
            if (apart(unitOrZero(cross(side, e))) || apart(unitOrZero(cross(rim, e)))) return true;
    }
    return false;
}

void ShadowCasters::find(const Vec3& origin, const Vec3& normal, const ClippedLight& base, int receiver, int light,
                         const Light& movable, TraceCounters& counters, Casters& out) const {
    out.count = 0;
    out.verdict = Casters::Verdict::Unoccluded;
    if (base.empty()) return;
    const Scene& scene = tracer_.scene();
    const int m = base.count;
    Vec3 pyr[6], faces[6];
    pyr[0] = origin;
    Bounds3 pb;
    pb.expand(origin);
    for (int k = 0; k < m; ++k) {
        pyr[k + 1] = base.vertex[k];
        pb.expand(base.vertex[k]);
    }
    faces[0] = polygonNormal(base.vertex, m);
    for (int k = 0; k < m; ++k) faces[k + 1] = unitOrZero(cross(pyr[1 + k] - origin, pyr[1 + (k + 1) % m] - origin));
    const float margin = 1e-5f * (maxAbs(origin) + sceneScale_);

    bool exact = true;
    int found = 0;
    auto consider = [&](const Hull* h) {
        if (separated(*h, pyr, m + 1, faces, pb, margin)) return;
        if (found < kMaxSegmentCasters) out.hull[found] = h;
        ++found;
        exact = exact && h->exact();
    };
    for (const Entry& e : hulls_) {
        const Hull& h = e.hull;
        if (e.object == receiver) {
            // A solid shadows its own point only when the point looks into it (a room seen from
            // inside); a polygon in the receiver's own plane never does.
            if ((h.kind == Hull::Kind::Solid || h.kind == Hull::Kind::Sphere) && dot(normal, h.center - origin) < 0.f)
                continue;
            if (h.kind == Hull::Kind::Polygon && std::fabs(dot(h.planeN[0], normal)) > 1.f - 1e-4f &&
                std::fabs(dot(h.planeN[0], origin) - h.planeD[0]) <= 4.f * tracer_.accel().offset(origin) + margin)
                continue;
        }
        consider(&h);
    }
    for (size_t li = 0; li < scene.lights.size(); ++li) {
        if (int(li) == light || !scene.lights[li].isArea()) continue;  // its own samples' rays stop short of it
        if (int(li) == scene.movableLight) {
            Vec3 v[4];
            out.movable = polygonHull(v, movable.vertices(v));
            setBound(out.movable);
            consider(&out.movable);
        } else {
            consider(&lightHulls_[li]);
        }
    }
    if (found == 0) return;
    out.count = std::min(found, kMaxSegmentCasters);

    // t*: below 1 − 1e-4 − offset(x)/|x − o|, the fraction of its length a sample ray keeps
    // (ExactDirect stops it short of the light), for every x of the base: offset is largest at a
    // vertex (it grows with |x|∞) and |x − o| is at least o's distance to the base's plane.
    const Accel& accel = tracer_.accel();
    const float h = std::fabs(dot(base.vertex[0] - origin, faces[0]));
    float maxOffset = 0.f;
    for (int k = 0; k < m; ++k) maxOffset = std::max(maxOffset, accel.offset(base.vertex[k]));
    const float tStar = 1.f - 2e-4f - maxOffset / h;
    const bool proofPossible = tStar > 0.5f;  // else the receiver is almost on the light

    if (exact && found <= kMaxSegmentCasters) {
        for (int c = 0; proofPossible && c < out.count; ++c) {
            const Hull& hc = *out.hull[c];
            if ((hc.kind == Hull::Kind::Solid || hc.kind == Hull::Kind::Sphere) && !hc.outside(origin, margin)) continue;
            bool all = true;
            for (int k = 0; all && k < m; ++k) {
                Ray ray;
                ray.origin = origin;
                const Vec3 d = base.vertex[k] - origin;
                const float dist = length(d);
                ray.dir = d / dist;
                ray.tmax = dist * tStar;
                all = dist > 0.f && hc.blocks(ray);
            }
            if (all) {
                out.verdict = Casters::Verdict::Occluded;
                return;
            }
        }
        out.verdict = Casters::Verdict::Segments;
        return;
    }
    out.count = 0;
    out.verdict = proofPossible && occludedByEmbree(origin, base, tStar, margin, movable, counters)
                      ? Casters::Verdict::Occluded
                      : Casters::Verdict::Rays;
}

int64_t ShadowCasters::convexPart(const Hit& hit, const Vec3& origin, float margin) const {
    if (hit.light >= 0) return -2 - int64_t(hit.light);  // a light is a parallelogram or a triangle
    if (hit.object < 0) return -1;
    const size_t o = size_t(hit.object);
    if (solidIndex_[o] >= 0)
        return hulls_[size_t(solidIndex_[o])].hull.outside(origin, margin) ? (int64_t(o) << 32 | 0xFFFFFFFFLL) : -1;
    if (hit.prim < convexPrim_[o].size() && convexPrim_[o][hit.prim]) return int64_t(o) << 32 | int64_t(hit.prim);
    return -1;
}

bool ShadowCasters::occludedByEmbree(const Vec3& origin, const ClippedLight& base, float tStar, float margin,
                                     const Light& movable, TraceCounters& counters) const {
    int64_t part = -1;
    for (int k = 0; k < base.count; ++k) {
        Ray ray;
        ray.origin = origin;
        const Vec3 d = base.vertex[k] - origin;
        const float dist = length(d);
        if (!(dist > 0.f)) return false;
        ray.dir = d / dist;
        ray.tmax = dist * tStar;
        ++counters.shadowRays;
        Hit hit;
        if (!tracer_.intersect(ray, movable, hit)) return false;
        const int64_t id = convexPart(hit, origin, margin);
        if (id == -1 || (k > 0 && id != part)) return false;
        part = id;
    }
    return true;
}

}  // namespace rrf
