#include "core/predict/exact_direct.h"

#include <cmath>

namespace rrf {

namespace {

struct D3 {
    double x, y, z;
};
D3 d3(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }
D3 operator-(const D3& a, const D3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator+(const D3& a, const D3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator*(const D3& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dotD(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 crossD(const D3& a, const D3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

/// The Phong lobe of the BRDF without the diffuse part: ks (e+2)/(2π) cos^e α, α between wi and the
/// mirror direction of wo about n (world space; wo and wi on n's side).
Vec3 glossyLobe(const Brdf& b, const Vec3& wo, const Vec3& n, const Vec3& wi) {
    return b.ks * ((b.n + 2.f) * kInv2Pi * powCos(dot(reflect(wo, n), wi), b.n));
}

}  // namespace

double projectedSolidAngle(const Light& l, const Vec3& pf, const Vec3& nf, Vec3* centroid) {
    if (centroid) *centroid = pf;
    const D3 p = d3(pf), n = d3(nf);
    const D3 c = d3(l.corner), e1 = d3(l.edge1), e2 = d3(l.edge2);
    if (l.oneSided && dotD(p - c, crossD(e1, e2)) <= 0.0) return 0.0;  // behind the emitting side
    Vec3 corners[4];
    const int nv = l.vertices(corners);
    D3 quad[4];
    for (int k = 0; k < nv; ++k) quad[k] = d3(corners[k]) - p;
    // Clip to the receiver's hemisphere: the part below the horizon sends no light to the surface.
    D3 poly[5];
    int m = 0;
    for (int k = 0; k < nv; ++k) {
        const D3 &a = quad[k], &b = quad[(k + 1) % nv];
        const double ha = dotD(a, n), hb = dotD(b, n);
        if (ha >= 0.0) poly[m++] = a;
        if ((ha >= 0.0) != (hb >= 0.0)) poly[m++] = a + (b - a) * (ha / (ha - hb));
    }
    if (m < 3) return 0.0;
    D3 mean{0, 0, 0};
    double sum = 0.0;
    for (int k = 0; k < m; ++k) {
        const D3 a = poly[k], b = poly[(k + 1) % m];
        mean = mean + a;
        const double la = std::sqrt(dotD(a, a)), lb = std::sqrt(dotD(b, b));
        if (!(la > 0.0) || !(lb > 0.0)) return 0.0;  // p on a vertex of the light
        const D3 axb = crossD(a, b);
        const double s = std::sqrt(dotD(axb, axb));
        if (s == 0.0) continue;  // edge collinear with p: subtends no angle
        // atan2 rather than acos: accurate for the tiny angles of distant or grazing edges.
        sum += std::atan2(s, dotD(a, b)) * dotD(n, axb) / s;
    }
    if (centroid) {
        const D3 q = p + mean * (1.0 / m);
        *centroid = Vec3(float(q.x), float(q.y), float(q.z));
    }
    return 0.5 * std::fabs(sum);
}

SampleGrid::SampleGrid(int samples) {
    cols = std::max(1, int(std::ceil(std::sqrt(double(samples)))));
    rows = (std::max(1, samples) + cols - 1) / cols;
}

ExactDirect::ExactDirect(const PathTracer& tracer, int samples, uint64_t seed)
    : tracer_(tracer), samples_(std::max(1, samples)), seed_(exactDirectSeed(seed)), grid_(samples_) {
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

Vec3 ExactDirect::radiance(const Vec3& p, const Vec3& n, const Vec3& wo, int object, const Light& movable,
                           uint64_t pixel, TraceCounters& counters) const {
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

}  // namespace rrf
