#pragma once
/// Scenes built in code for the rendering tests (no JSON loader involved), plus small statistics
/// helpers shared by the Monte Carlo tests.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/scene/accel.h"
#include "core/render/brdf.h"
#include "core/scene/camera_rays.h"
#include "core/render/renderer.h"
#include "core/render/path_tracer.h"
#include "core/util/rng.h"
#include "core/scene/scene.h"

namespace rrf::test {

inline int addLambert(Scene& s, const Vec3& albedo, const std::string& name = "lambert") {
    Material m;
    m.type = Material::Type::Lambert;
    m.name = name;
    m.kd = albedo;
    s.materials.push_back(m);
    return int(s.materials.size()) - 1;
}

inline int addPhong(Scene& s, const Vec3& kd, const Vec3& ks, float exponent, const std::string& name = "phong") {
    Material m;
    m.type = Material::Type::Phong;
    m.name = name;
    m.kd = kd;
    m.ks = ks;
    m.exponent = exponent;
    s.materials.push_back(m);
    return int(s.materials.size()) - 1;
}

/// Adds an object made of parallelograms corner + s·e1 + t·e2; the geometric normal is e1 × e2.
struct QuadSpec {
    Vec3 corner, e1, e2;
};
inline int addQuads(Scene& s, const std::vector<QuadSpec>& quads, int material, const std::string& name = "quads") {
    Object o;
    o.kind = Object::Kind::Quads;
    o.name = name;
    o.id = int(s.objects.size());
    o.material = material;
    for (const QuadSpec& q : quads) {
        const uint32_t base = uint32_t(o.positions.size());
        o.positions.push_back(q.corner);
        o.positions.push_back(q.corner + q.e1);
        o.positions.push_back(q.corner + q.e1 + q.e2);
        o.positions.push_back(q.corner + q.e2);
        for (uint32_t k = 0; k < 4; ++k) o.indices.push_back(base + k);
    }
    s.objects.push_back(std::move(o));
    return int(s.objects.size()) - 1;
}

inline int addRectLight(Scene& s, const Vec3& corner, const Vec3& e1, const Vec3& e2, const Vec3& radiance,
                        bool oneSided = true, int material = -1) {
    Light l;
    l.type = Light::Type::Rect;
    l.name = "rect" + std::to_string(s.lights.size());
    l.corner = corner;
    l.edge1 = e1;
    l.edge2 = e2;
    l.radiance = radiance;
    l.oneSided = oneSided;
    l.material = material;
    s.lights.push_back(l);
    return int(s.lights.size()) - 1;
}

inline int addPointLight(Scene& s, const Vec3& position, const Vec3& intensity) {
    Light l;
    l.type = Light::Type::Point;
    l.name = "point" + std::to_string(s.lights.size());
    l.position = position;
    l.intensity = intensity;
    s.lights.push_back(l);
    return int(s.lights.size()) - 1;
}

/// The six faces of the cube [-h, h]³ as parallelograms whose normal e1 × e2 points inwards.
inline std::vector<QuadSpec> inwardCubeFaces(float h) {
    const float w = 2.f * h;
    return {
        {{-h, -h, -h}, {0, w, 0}, {0, 0, w}},  // x = -h, normal +x
        {{h, -h, -h}, {0, 0, w}, {0, w, 0}},   // x = +h, normal -x
        {{-h, -h, -h}, {0, 0, w}, {w, 0, 0}},  // y = -h, normal +y
        {{-h, h, -h}, {w, 0, 0}, {0, 0, w}},   // y = +h, normal -y
        {{-h, -h, -h}, {w, 0, 0}, {0, w, 0}},  // z = -h, normal +z
        {{-h, -h, h}, {0, w, 0}, {w, 0, 0}},   // z = +h, normal -z
    };
}

/// White furnace: six one-sided emitters (radiance `le`) forming a closed cube, each reflecting with
/// material `material`; the camera sits at the centre. Every camera ray sees Le / (1 − albedo) when
/// the material is Lambert.
inline Scene furnaceScene(float le, const Material& wall, int size = 16) {
    Scene s;
    s.materials.push_back(wall);
    for (const QuadSpec& q : inwardCubeFaces(1.f)) addRectLight(s, q.corner, q.e1, q.e2, Vec3(le), true, 0);
    s.camera.eye = Vec3(0.f, 0.f, 0.f);
    s.camera.target = Vec3(0.3f, 0.2f, -1.f);
    s.camera.up = Vec3(0, 1, 0);
    s.camera.fovYDegrees = 100.f;
    s.camera.width = size;
    s.camera.height = size;
    return s;
}

/// Cornell-like open box [-1,1]³ (front z = +1 open) with a one-sided ceiling light facing down and a
/// closed block standing on the floor, everything multiplied by `scale` (radiance unchanged, so the
/// image is the same at every scale). `lightScale` enlarges the light about its centre and divides
/// its radiance by lightScale², keeping its power (a larger light makes the naive estimator quieter).
inline Scene cornellLike(float scale = 1.f, int size = 32, float lightScale = 1.f) {
    Scene s;
    const int white = addLambert(s, Vec3(0.75f, 0.72f, 0.70f), "white");
    const int red = addLambert(s, Vec3(0.60f, 0.06f, 0.05f), "red");
    const int green = addLambert(s, Vec3(0.10f, 0.45f, 0.08f), "green");
    const float k = scale;
    auto q = [k](Vec3 c, Vec3 a, Vec3 b) { return QuadSpec{c * k, a * k, b * k}; };
    // Walls face inwards (e1 × e2 points into the box).
    addQuads(s, {q({-1, -1, -1}, {0, 0, 2}, {2, 0, 0}),   // floor, +y
                 q({-1, 1, -1}, {2, 0, 0}, {0, 0, 2}),    // ceiling, -y
                 q({-1, -1, -1}, {2, 0, 0}, {0, 2, 0})},  // back, +z
             white, "white walls");
    addQuads(s, {q({-1, -1, -1}, {0, 2, 0}, {0, 0, 2})}, red, "left wall");    // x = -1, +x
    addQuads(s, {q({1, -1, -1}, {0, 0, 2}, {0, 2, 0})}, green, "right wall");  // x = +1, -x
    // Closed block [-0.6,-0.1] × [-1,-0.2] × [-0.5,0] standing on the floor (faces point outwards):
    // its contact line with the floor is where too-large ray offsets would leak light.
    const Vec3 lo(-0.6f, -1.f, -0.5f), hi(-0.1f, -0.2f, 0.f);
    const Vec3 d = hi - lo;
    addQuads(s, {q(lo, {0, 0, d.z}, {0, d.y, 0}),                    // x = lo, -x
                 q({hi.x, lo.y, lo.z}, {0, d.y, 0}, {0, 0, d.z}),    // x = hi, +x
                 q(lo, {d.x, 0, 0}, {0, 0, d.z}),                    // y = lo, -y
                 q({lo.x, hi.y, lo.z}, {0, 0, d.z}, {d.x, 0, 0}),    // y = hi, +y
                 q(lo, {0, d.y, 0}, {d.x, 0, 0}),                    // z = lo, -z
                 q({lo.x, lo.y, hi.z}, {d.x, 0, 0}, {0, d.y, 0})},   // z = hi, +z
             white, "block");
    // Light just below the ceiling, normal e1 × e2 = -y (facing down).
    const Vec3 e1(0.5f * lightScale, 0, 0), e2(0, 0, 0.4f * lightScale);
    addRectLight(s, (Vec3(0.f, 0.99f, 0.f) - 0.5f * (e1 + e2)) * k, e1 * k, e2 * k,
                 Vec3(15.f, 12.f, 8.f) / (lightScale * lightScale));
    s.camera.eye = Vec3(0, 0, 3.9f) * k;
    s.camera.target = Vec3(0, 0, 0);
    s.camera.up = Vec3(0, 1, 0);
    s.camera.fovYDegrees = 39.3077f;
    s.camera.width = size;
    s.camera.height = size;
    return s;
}

struct D3 {
    double x, y, z;
};
inline D3 sub(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline D3 crossD(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double dotD(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline double lenD(D3 a) { return std::sqrt(dotD(a, a)); }
inline D3 toD(const Vec3& v) { return {v.x, v.y, v.z}; }

/// Irradiance at p (normal n) from a uniform Lambertian parallelogram of radiance L lying entirely
/// above p's tangent plane (Lambert 1760):
///   E = (L/2) Σ_i Θ_i n·(v_i × v_{i+1}) / |v_i × v_{i+1}|,
/// v_i the unit vectors from p to the vertices, Θ_i the angle between consecutive ones. The sign of
/// the sum depends on the winding as seen from p, hence the absolute value. Double precision.
inline double polygonIrradiance(const Light& l, const Vec3& pf, const Vec3& nf) {
    const D3 p = toD(pf), n = toD(nf);
    const D3 c = toD(l.corner), e1 = toD(l.edge1), e2 = toD(l.edge2);
    const std::array<D3, 4> vs = {c, D3{c.x + e1.x, c.y + e1.y, c.z + e1.z},
                                  D3{c.x + e1.x + e2.x, c.y + e1.y + e2.y, c.z + e1.z + e2.z},
                                  D3{c.x + e2.x, c.y + e2.y, c.z + e2.z}};
    double sum = 0;
    for (size_t i = 0; i < 4; ++i) {
        D3 a = sub(vs[i], p), b = sub(vs[(i + 1) % 4], p);
        const double la = lenD(a), lb = lenD(b);
        a = {a.x / la, a.y / la, a.z / la};
        b = {b.x / lb, b.y / lb, b.z / lb};
        const D3 axb = crossD(a, b);
        const double s = lenD(axb);
        if (s == 0) continue;
        const double theta = std::atan2(s, dotD(a, b));
        sum += theta * dotD(n, axb) / s;
    }
    return 0.5 * double(l.radiance.x) * std::fabs(sum);
}

/// The caustic case of a near-mirror: a glossy floor quad (y = 0, facing +y, x ∈ [fx0, fx0 + fw],
/// z ∈ [−fd/2, fd/2], Phong with kd 0, ks `ks`, exponent `e`) reflects a downward 0.2 × 0.2 light of
/// radiance `le` at y = 1 onto a diffuse ceiling of albedo `rho` beside it (y = 1, x ∈ [0, 2], z ∈
/// [−2, 2], facing −y): the ceiling sees the light only by way of the floor. Objects: 0 the mirror,
/// 1 the ceiling. The camera looks up at the ceiling from (0.5, 0.6, 0), 60°, size × size.
inline Scene mirrorCausticScene(float e, float ks, float rho, float le, int size, float fx0 = -3.f, float fw = 6.f,
                                float fd = 6.f) {
    Scene s;
    const int mirror = addPhong(s, Vec3(0.f), Vec3(ks), e, "mirror");
    const int white = addLambert(s, Vec3(rho), "ceiling");
    addQuads(s, {{{fx0, 0, -0.5f * fd}, {0, 0, fd}, {fw, 0, 0}}}, mirror, "mirror");  // +y
    addQuads(s, {{{0.f, 1, -2}, {2, 0, 0}, {0, 0, 4}}}, white, "ceiling");            // -y
    addRectLight(s, Vec3(-0.6f, 1.f, -0.1f), Vec3(0.2f, 0, 0), Vec3(0, 0, 0.2f), Vec3(le));  // faces -y
    s.camera.eye = Vec3(0.5f, 0.6f, 0.f);
    s.camera.target = Vec3(0.5f, 1.f, 0.f);
    s.camera.up = Vec3(0, 0, 1);
    s.camera.fovYDegrees = 60.f;
    s.camera.width = s.camera.height = size;
    return s;
}

/// ∫ cos³θ / d² dA over mirrorCausticScene's light mirrored to y = −1, seen from the ceiling point p
/// (midpoint rule, n × n): a mirror of lobe energy ks cosθ makes the ceiling's radiance
/// ρ/π · ks · Le · this (cosθ at the ceiling, at the mirror and at the image are the same angle).
inline double mirroredLightIntegral(const Vec3& p, int n = 64) {
    double e = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double qx = -0.6 + 0.2 * (i + 0.5) / n, qz = -0.1 + 0.2 * (j + 0.5) / n, qy = -1.0;
            const double dx = qx - p.x, dy = qy - p.y, dz = qz - p.z;
            const double d2 = dx * dx + dy * dy + dz * dz, cy = std::fabs(dy) / std::sqrt(d2);
            e += cy * cy * cy / d2 * (0.04 / (n * n));
        }
    return e;
}

/// Running mean and variance (Welford), in double.
struct RunningStat {
    uint64_t n = 0;
    double mean = 0, m2 = 0;
    void add(double x) {
        ++n;
        const double d = x - mean;
        mean += d / double(n);
        m2 += d * (x - mean);
    }
    double variance() const { return n > 1 ? m2 / double(n - 1) : 0.0; }
    /// Standard error of the mean.
    double sigma() const { return n > 1 ? std::sqrt(variance() / double(n)) : 0.0; }
};


/// A Lambert floor y = 0 of half-size `half` (albedo rho, normal +y), object 0.
inline Scene floorScene(float rho, float half) {
    Scene s;
    const int m = addLambert(s, Vec3(rho));
    addQuads(s, {{{-half, 0, -half}, {0, 0, 2 * half}, {2 * half, 0, 0}}}, m, "floor");
    return s;
}

/// A square light of side `side` centred above (cx, cz) at height h, facing down (e1 × e2 = −y).
inline void addCeilingLight(Scene& s, float cx, float cz, float h, float side, float radiance = 4.f,
                            bool oneSided = true) {
    addRectLight(s, Vec3(cx - 0.5f * side, h, cz - 0.5f * side), Vec3(side, 0, 0), Vec3(0, 0, side), Vec3(radiance),
                 oneSided);
}

/// A hit on object 0 at p with geometric normal ng.
inline Hit surfaceHit(const Vec3& p, const Vec3& ng = Vec3(0, 1, 0)) {
    Hit h;
    h.t = 1.f;
    h.p = p;
    h.ng = ng;
    h.object = 0;
    return h;
}

/// Statistics of PathTracer::shade (NEE) at floor point p towards wo, first channel.
struct FloorShading {
    RunningStat direct;
    uint64_t nonFinite = 0, indirectNonZero = 0;
};
inline FloorShading shadeFloor(const Scene& scene, const Vec3& p, int samples, uint64_t seed,
                               const Vec3& wo = Vec3(0, 1, 0), const Vec3& ng = Vec3(0, 1, 0)) {
    const Accel accel(scene);
    const PathTracer tracer(scene, accel, Estimator::NEE, 8);
    TraceCounters counters;
    FloorShading st;
    for (int i = 0; i < samples; ++i) {
        Rng rng(seed, uint64_t(i));
        const Radiance L = tracer.shade(surfaceHit(p, ng), wo, rng, counters);
        if (!L.direct.isFinite() || !L.indirect.isFinite()) {
            ++st.nonFinite;
            continue;
        }
        if (!L.indirect.isZero()) ++st.indirectNonZero;
        st.direct.add(L.direct.x);
    }
    return st;
}

/// Monte Carlo estimate of the image mean (first channel) of direct, indirect and global radiance:
/// each sample picks a uniformly random pixel and jitter, so the samples are i.i.d. and the standard
/// errors are exact (unlike pixel-wise variances, no assumption about correlation is needed).
struct ImageMeanStats {
    RunningStat direct, indirect, global;
    uint64_t nonFinite = 0;
};
inline ImageMeanStats traceImageMean(const Scene& scene, const Accel& accel, Estimator estimator, int samples,
                                     uint64_t seed, int maxDepth = 64) {
    const PathTracer tracer(scene, accel, estimator, maxDepth);
    const CameraRays cam(scene.camera, scene.camera.width, scene.camera.height);
    TraceCounters counters;
    ImageMeanStats st;
    for (int i = 0; i < samples; ++i) {
        Rng rng(seed, uint64_t(i));
        const int px = int(rng.uniformInt(uint32_t(scene.camera.width)));
        const int py = int(rng.uniformInt(uint32_t(scene.camera.height)));
        const float jx = rng.uniform(), jy = rng.uniform();
        const Radiance L = tracer.trace(cam.generate(px, py, jx, jy), rng, counters);
        if (!L.direct.isFinite() || !L.indirect.isFinite()) {
            ++st.nonFinite;
            continue;
        }
        st.direct.add(L.direct.x);
        st.indirect.add(L.indirect.x);
        st.global.add(double(L.direct.x) + double(L.indirect.x));
    }
    return st;
}

/// Gauss–Legendre nodes and weights on [-1, 1] (Newton iteration on P_n; exact for degree 2n−1).
struct GaussLegendre {
    std::vector<double> x, w;
    explicit GaussLegendre(int n) : x(size_t(n)), w(size_t(n)) {
        const double pi = 3.14159265358979323846;
        for (int i = 0; i < n; ++i) {
            double z = std::cos(pi * (i + 0.75) / (n + 0.5)), dp = 1;
            for (int it = 0; it < 100; ++it) {
                double p0 = 1, p1 = z;
                for (int k = 2; k <= n; ++k) {
                    const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n * (z * p1 - p0) / (z * z - 1);
                const double dz = p1 / dp;
                z -= dz;
                if (std::fabs(dz) < 1e-16) break;
            }
            x[size_t(i)] = z;
            w[size_t(i)] = 2 / ((1 - z * z) * dp * dp);
        }
    }
    /// ∫_a^b f, split into `panels` equal panels.
    double integrate(const std::function<double(double)>& f, double a, double b, int panels = 1) const {
        double sum = 0;
        const double h = (b - a) / panels;
        for (int p = 0; p < panels; ++p) {
            const double lo = a + p * h, mid = lo + 0.5 * h;
            for (size_t i = 0; i < x.size(); ++i) sum += w[i] * f(mid + 0.5 * h * x[i]);
        }
        return sum * 0.5 * h;
    }
};

/// Regularised upper incomplete gamma function Q(a, x) (series below a+1, Lentz continued fraction
/// above; Numerical Recipes §6.2). The chi-square survival function is Q(dof/2, χ²/2).
inline double gammaQ(double a, double x) {
    if (x <= 0) return 1.0;
    const double lg = std::lgamma(a);
    if (x < a + 1) {
        double ap = a, sum = 1 / a, del = sum;
        for (int n = 0; n < 10000; ++n) {
            ap += 1;
            del *= x / ap;
            sum += del;
            if (std::fabs(del) < std::fabs(sum) * 1e-15) break;
        }
        return 1 - sum * std::exp(-x + a * std::log(x) - lg);
    }
    const double tiny = 1e-300;
    double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
    for (int i = 1; i < 10000; ++i) {
        const double an = -i * (i - a);
        b += 2;
        d = an * d + b;
        if (std::fabs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::fabs(c) < tiny) c = tiny;
        d = 1 / d;
        const double del = d * c;
        h *= del;
        if (std::fabs(del - 1) < 1e-15) break;
    }
    return std::exp(-x + a * std::log(x) - lg) * h;
}

/// Pearson's chi-square test of observed against expected counts. Bins with an expected count below
/// 5 are pooled (smallest first) so the χ² approximation holds. Returns the p-value; `dof` receives
/// the degrees of freedom used.
inline double chiSquarePValue(const std::vector<double>& observed, const std::vector<double>& expected,
                              int* dofOut = nullptr) {
    std::vector<std::pair<double, double>> bins;  // (expected, observed)
    for (size_t i = 0; i < observed.size(); ++i) bins.emplace_back(expected[i], observed[i]);
    std::sort(bins.begin(), bins.end());
    double chi2 = 0, poolE = 0, poolO = 0;
    int used = 0;
    for (const auto& [e, o] : bins) {
        if (poolE + e < 5.0 && e < 5.0) {
            poolE += e;
            poolO += o;
            continue;
        }
        if (poolE > 0) {  // fold the pool into this bin
            const double ee = e + poolE, oo = o + poolO;
            poolE = poolO = 0;
            chi2 += (oo - ee) * (oo - ee) / ee;
        } else {
            chi2 += (o - e) * (o - e) / e;
        }
        ++used;
    }
    if (poolE > 0) {  // leftover pool (every bin tiny): one more bin
        chi2 += (poolO - poolE) * (poolO - poolE) / poolE;
        ++used;
    } else if (poolO > 0) {
        return 0.0;  // samples where the pdf says none can be
    }
    const int dof = std::max(1, used - 1);
    if (dofOut) *dofOut = dof;
    return gammaQ(0.5 * dof, 0.5 * chi2);
}

/// Šidák-corrected per-test significance for a family of `tests` chi-square tests with overall
/// significance 0.01: the chance that any correct sampler fails one of them is 1%.
inline double sidakAlpha(int tests, double overall = 0.01) { return 1.0 - std::pow(1.0 - overall, 1.0 / tests); }
/// Number of chi-square tests in the sampling family (test_sampling.cpp: cosine + 4 Phong
/// exponents; test_brdf.cpp: mixture at 3 view angles, and the glossy project's 3 Phong materials at
/// 2 view angles).
constexpr int kChiSquareTests = 14;

/// Phong BRDF with grey kd, ks and exponent n.
inline Brdf phong(float kd, float ks, float n) {
    Material m;
    m.type = Material::Type::Phong;
    m.kd = Vec3(kd);
    m.ks = Vec3(ks);
    m.exponent = n;
    return Brdf(m);
}

/// Renders `scene` at its camera size in one pass and returns the snapshot.
inline RenderSnapshot render(const Scene& scene, const Accel& accel, const RenderOptions& o) {
    Renderer r(scene, accel, o);
    r.run();
    return r.snapshot();
}
/// Options for rendering `scene` at its camera size (`samplesPerPass` 0 = all spp in one pass).
inline RenderOptions renderOptions(const Scene& scene, Estimator estimator, int spp, int samplesPerPass = 0,
                                   uint64_t seed = 1) {
    RenderOptions o;
    o.width = scene.camera.width;
    o.height = scene.camera.height;
    o.spp = spp;
    o.samplesPerPass = samplesPerPass > 0 ? samplesPerPass : spp;
    o.estimator = estimator;
    o.seed = seed;
    return o;
}
inline RenderSnapshot render(const Scene& scene, const Accel& accel, Estimator estimator, int spp, uint64_t seed = 1) {
    return render(scene, accel, renderOptions(scene, estimator, spp, spp, seed));
}

/// Standard error of the image mean of channel c from the per-pixel variances of the mean
/// (pixels are independent, so the variances add).
inline double imageMeanSigma(const RenderSnapshot& s, int c = 0) {
    double sum = 0;
    for (size_t i = 0; i < s.variance.pixelCount(); ++i) sum += s.variance.data[3 * i + size_t(c)];
    return std::sqrt(sum) / double(s.variance.pixelCount());
}

}  // namespace rrf::test
