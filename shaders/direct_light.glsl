// Exact direct light for the GLSL predictor: the estimator of core/predict/exact_direct.h, step by
// step, so that the GLSL image matches the CPU's to float rounding except where a shadow ray grazes
// an edge (tests/gl/test_glsl_direct.cpp states the bound). The host (app/gl/glsl_predictor.cpp)
// inserts this file into predict.frag after the #version line; predict.frag calls rrfDirectLight().
//
// uDirectMode: 0 = the networks' direct light (this file unused), 1 = computed here with shadow rays
// against the scene held in uDirectScene, 2 = computed on the CPU by the host (too many triangles for
// a brute-force shader loop) and read from uDirectHost.
//
// uDirectScene: RGBA32F texels (a texture buffer), written by the host:
//   0                 (rect lights, point lights, triangles, spheres)
//   1                 first texel of (rect lights, point lights, triangles, spheres)
//   2                 (first texel of materials, 0, 0, 0)
//   area light        (corner, one-sided), (edge1, area), (edge2, triangle), (radiance, 0): a rect
//                     light (triangle = 0) or a triangle light (triangle = 1, rrf::Light::Type::Triangle)
//   point light       (position, 0), (intensity, 0)
//   material          per object: (kd, exponent), (ks, 0)   (ks = 0 for Lambert, as rrf::Brdf)
//   triangle          (v0, 0), (v1, 0), (v2, 0)            (a quad is Embree's two triangles)
//   sphere            (centre, radius)

uniform int uDirectMode;
uniform samplerBuffer uDirectScene;
uniform sampler2D uDirectHost;
uniform uvec2 uDirectKey;    // mix64(seed' + γ) of rrf::Rng, as (low, high) 32-bit words
uniform ivec3 uDirectGrid;   // samples, columns, rows (rrf::SampleGrid)
uniform float uSceneScale;   // rrf::Scene::scale(): the ray offset's scene term (rrf::Accel::offset)

const float kInvPiD = 0.318309886183790671538;
const float kInv2PiD = 0.159154943091895335769;

// ---- rrf::Rng with 64-bit words as uvec2(low, high) (GLSL 3.30 has no 64-bit integers)
uvec2 add64(uvec2 a, uvec2 b) {
    uint lo = a.x + b.x;
    return uvec2(lo, a.y + b.y + (lo < a.x ? 1u : 0u));
}
uvec2 mulWide(uint a, uint b) {  // full 64-bit product of two 32-bit words, from 16-bit halves
    uint a0 = a & 0xFFFFu, a1 = a >> 16, b0 = b & 0xFFFFu, b1 = b >> 16;
    uint p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    uint mid = (p00 >> 16) + (p01 & 0xFFFFu) + (p10 & 0xFFFFu);
    return uvec2((p00 & 0xFFFFu) | (mid << 16), p11 + (p01 >> 16) + (p10 >> 16) + (mid >> 16));
}
uvec2 mul64(uvec2 a, uvec2 b) {  // product modulo 2^64
    uvec2 r = mulWide(a.x, b.x);
    r.y += a.x * b.y + a.y * b.x;
    return r;
}
uvec2 xorShift(uvec2 z, int s) {  // z ^ (z >> s), 0 < s < 32
    return z ^ uvec2((z.x >> s) | (z.y << (32 - s)), z.y >> s);
}
uvec2 mix64(uvec2 z) {
    z = mul64(xorShift(z, 30), uvec2(0x1CE4E5B9u, 0xBF58476Du));
    z = mul64(xorShift(z, 27), uvec2(0x133111EBu, 0x94D049BBu));
    return xorShift(z, 31);
}
const uvec2 kGamma = uvec2(0x7F4A7C15u, 0x9E3779B9u);
uvec2 rngState;
void rngStart(uvec2 pixelKey, uint sampleIndex) {  // Rng(seed', pixel, sample); pixelKey from rngPixelKey
    rngState = mix64(pixelKey ^ add64(uvec2(sampleIndex, 0u), uvec2(0x2F3D8DD7u, 0x8CB92BA7u)));
}
uvec2 rngPixelKey(uint pixel) { return mix64(uDirectKey ^ add64(uvec2(pixel, 0u), uvec2(0xD9B4E019u, 0x632BE59Bu))); }
float rngUniform() {
    rngState = add64(rngState, kGamma);
    return float(mix64(rngState).y >> 8) * (1.0 / 16777216.0);
}

// ---- scene access
vec4 dsTexel(int i) { return texelFetch(uDirectScene, i); }

// ---- shadow rays: brute force over every occluder (rrf::PathTracer::occluded's answer)
bool hitsTriangle(vec3 o, vec3 d, float tmax, vec3 v0, vec3 v1, vec3 v2) {
    vec3 e1 = v1 - v0, e2 = v2 - v0, pv = cross(d, e2);
    float det = dot(e1, pv);
    if (det == 0.0) return false;
    float inv = 1.0 / det;
    vec3 tv = o - v0;
    float u = dot(tv, pv) * inv;
    if (u < 0.0 || u > 1.0) return false;
    vec3 qv = cross(tv, e1);
    float v = dot(d, qv) * inv;
    if (v < 0.0 || u + v > 1.0) return false;
    float t = dot(e2, qv) * inv;
    // t = 0 counts, as in Embree (ray interval [tnear = 0, tfar]): a ray starting exactly on another
    // surface, as at a crease between two walls, is occluded on both paths.
    return t >= 0.0 && t < tmax;
}
bool hitsAreaLight(vec3 o, vec3 d, float tmax, vec3 c, vec3 e1, vec3 e2, bool triangle) {
    vec3 n = cross(e1, e2);
    float denom = dot(d, n);
    if (denom == 0.0) return false;
    float t = dot(c - o, n) / denom;
    if (!(t > 0.0 && t < tmax)) return false;
    vec3 q = o + d * t - c;
    float nn = dot(n, n);
    float a = dot(cross(q, e2), n) / nn, b = dot(cross(e1, q), n) / nn;
    if (triangle) return a >= 0.0 && b >= 0.0 && a + b <= 1.0;
    return a >= 0.0 && a <= 1.0 && b >= 0.0 && b <= 1.0;
}
bool hitsSphere(vec3 o, vec3 d, float tmax, vec3 c, float r) {
    vec3 oc = o - c;
    float b = dot(oc, d), cc = dot(oc, oc) - r * r, disc = b * b - cc;
    if (disc < 0.0) return false;
    float s = sqrt(disc), t0 = -b - s, t1 = -b + s;
    return (t0 > 0.0 && t0 < tmax) || (t1 > 0.0 && t1 < tmax);
}
float rayOffset(vec3 p) { return 2e-5 * (max(abs(p.x), max(abs(p.y), abs(p.z))) + uSceneScale); }

// Visibility of `target` from p (normal n, target on n's side), as rrf::ExactDirect::visible.
bool dsVisible(vec3 p, vec3 n, vec3 target) {
    vec3 o = p + n * rayOffset(p);
    vec3 d = target - o;
    float dist = length(d);
    float tmax = dist * (1.0 - 1e-4) - rayOffset(target);
    if (!(tmax > 0.0)) return true;
    d /= dist;
    vec4 counts = dsTexel(0), first = dsTexel(1);
    for (int k = 0; k < int(counts.z); ++k) {
        int t = int(first.z) + 3 * k;
        if (hitsTriangle(o, d, tmax, dsTexel(t).xyz, dsTexel(t + 1).xyz, dsTexel(t + 2).xyz)) return false;
    }
    for (int k = 0; k < int(counts.x); ++k) {
        int t = int(first.x) + 4 * k;
        vec4 e2 = dsTexel(t + 2);
        if (hitsAreaLight(o, d, tmax, dsTexel(t).xyz, dsTexel(t + 1).xyz, e2.xyz, e2.w > 0.5)) return false;
    }
    for (int k = 0; k < int(counts.w); ++k) {
        vec4 s = dsTexel(int(first.w) + k);
        if (hitsSphere(o, d, tmax, s.xyz, s.w)) return false;
    }
    return true;
}

// rrf::projectedSolidAngle in float: Lambert's formula over the light clipped to n's hemisphere.
// Returns the clipped polygon's vertex mean in `clippedCentre`.
float dsProjectedSolidAngle(vec3 c, vec3 e1, vec3 e2, bool triangle, bool oneSided, vec3 p, vec3 n,
                            out vec3 clippedCentre) {
    clippedCentre = p;
    if (oneSided && dot(p - c, cross(e1, e2)) <= 0.0) return 0.0;
    // rrf::Light::vertices: a triangle's corners are c, c + e1, c + e2.
    vec3 quad[4] = triangle ? vec3[4](c - p, c + e1 - p, c + e2 - p, c - p)
                            : vec3[4](c - p, c + e1 - p, c + e1 + e2 - p, c + e2 - p);
    int nv = triangle ? 3 : 4;
    vec3 poly[5];
    int m = 0;
    for (int k = 0; k < nv; ++k) {
        vec3 a = quad[k], b = quad[k + 1 < nv ? k + 1 : 0];
        float ha = dot(a, n), hb = dot(b, n);
        if (ha >= 0.0) poly[m++] = a;
        if ((ha >= 0.0) != (hb >= 0.0)) poly[m++] = a + (b - a) * (ha / (ha - hb));
    }
    if (m < 3) return 0.0;
    vec3 mean = vec3(0.0);
    float sum = 0.0;
    for (int k = 0; k < m; ++k) {
        vec3 a = poly[k], b = poly[k + 1 < m ? k + 1 : 0];
        mean += a;
        float la = length(a), lb = length(b);
        if (!(la > 0.0) || !(lb > 0.0)) return 0.0;
        vec3 axb = cross(a, b);
        float s = length(axb);
        if (s == 0.0) continue;
        sum += atan(s, dot(a, b)) * dot(n, axb) / s;
    }
    clippedCentre = p + mean / float(m);
    return 0.5 * abs(sum);
}

float dsPowCos(float c, float e) { return c <= 0.0 ? 0.0 : (e == 0.0 ? 1.0 : exp(e * log(c))); }

// ---- rrf::phongLobeIntegral (core/predict/phong_lobe_integral.h): G = ∫_light cos^e α cosθ dω over
// the lobe's footprint on the light, closed form when the light holds the whole lobe, else an
// iterated 8-point Gauss–Legendre rule with panels split at the mirror ray's hit.
const float kLobeNode[8] = float[8](-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                    -0.1834346424956498, 0.1834346424956498, 0.5255324099163290,
                                    0.7966664774136267, 0.9602898564975363);
const float kLobeWeight[8] = float[8](0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                      0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                      0.2223810344533745, 0.1012285362903763);
const float kTwoPiD = 6.283185307179586;

struct LobeSetup {
    vec3 q0, e1, e2;   // x − p = q0 + u e1 + v e2
    float a0, a1, a2;  // r·(x − p)
    vec3 p0, p1, p2;   // component of x − p across r
    vec3 n, ln;        // receiver normal, unit light normal
    float e;
    bool oneSided;
};

float dsLobeIntegrand(LobeSetup s, float u, float v) {
    float rd = (s.a0 + u * s.a1) + v * s.a2;
    vec3 d = (s.q0 + s.e1 * u) + s.e2 * v;
    float dist2 = dot(d, d);
    float inv = 1.0 / sqrt(dist2);
    float cosT = dot(s.n, d) * inv;
    float cosL = -dot(s.ln, d) * inv;
    if (!s.oneSided) cosL = abs(cosL);
    if (!(rd > 0.0 && cosT > 0.0 && cosL > 0.0)) return 0.0;
    vec3 a = (s.p0 + s.p1 * u) + s.p2 * v;
    float sin2 = min(dot(a, a) / dist2, 1.0 - 1e-7);
    float lc = sin2 < 1e-3 ? -sin2 * (1.0 + sin2 * (0.5 + sin2 * (1.0 / 3.0))) : log(1.0 - sin2);
    float lobe = s.e == 0.0 ? 1.0 : exp(0.5 * s.e * lc);
    return lobe * cosT * cosL / dist2;
}

// Inserts x into the sorted breaks b[0..m) when it lies strictly inside (b[0], b[m−1]).
void dsAddBreak(inout float b[4], inout int m, float x) {
    if (!(x > b[0] && x < b[m - 1])) return;
    int k = m;
    while (k > 0 && b[k - 1] > x) {
        b[k] = b[k - 1];
        --k;
    }
    b[k] = x;
    ++m;
}

float dsPhongLobeIntegral(vec3 c, vec3 e1, vec3 e2, bool triangle, bool oneSided, vec3 p, vec3 n, vec3 r, float e) {
    vec3 nl = cross(e1, e2);
    float area2 = length(nl);
    if (!(area2 > 0.0)) return 0.0;
    LobeSetup s;
    s.q0 = c - p;
    s.e1 = e1;
    s.e2 = e2;
    s.n = n;
    s.ln = nl / area2;
    s.e = e;
    s.oneSided = oneSided;
    if (oneSided && dot(s.q0, nl) >= 0.0) return 0.0;
    s.a0 = dot(r, s.q0);
    s.a1 = dot(r, e1);
    s.a2 = dot(r, e2);
    s.p0 = s.q0 - r * s.a0;
    s.p1 = e1 - r * s.a1;
    s.p2 = e2 - r * s.a2;

    float u0 = 0.0, u1 = 1.0, v0 = 0.0, v1 = 1.0;
    // rrf::lobeFootprintTan2: τ² with cos^e α = ε = 1e-6·2π/(e+2) on the cone; unbounded for wide lobes.
    float x = e > 0.0 ? -2.0 * log(1e-6 * kTwoPiD / (e + 2.0)) / e : 100.0;
    if (x <= 80.0) {
        float tau2 = x < 1e-3 ? x * (1.0 + 0.5 * x) : exp(x) - 1.0;
        float A = tau2 * s.a1 * s.a1 - dot(s.p1, s.p1);
        float B = tau2 * s.a1 * s.a2 - dot(s.p1, s.p2);
        float C = tau2 * s.a2 * s.a2 - dot(s.p2, s.p2);
        float D = tau2 * s.a0 * s.a1 - dot(s.p0, s.p1);
        float E = tau2 * s.a0 * s.a2 - dot(s.p0, s.p2);
        float F = tau2 * s.a0 * s.a0 - dot(s.p0, s.p0);
        float det = A * C - B * B;
        if (A < 0.0 && C < 0.0 && det > 0.0) {
            float uc = (B * E - C * D) / det, vc = (B * D - A * E) / det;
            float qc = D * uc + E * vc + F;
            if (s.a0 + s.a1 * uc + s.a2 * vc <= 0.0 || !(qc > 0.0)) return 0.0;
            float hu = sqrt(qc * -C / det), hv = sqrt(qc * -A / det);
            float nr = dot(n, r);
            bool inside = uc - hu > 0.0 && vc - hv > 0.0 &&
                          (triangle ? (uc + hu) + (vc + hv) < 1.0 : uc + hu < 1.0 && vc + hv < 1.0);
            if (inside && nr > 0.0 && nr * nr > tau2 / (1.0 + tau2)) return kTwoPiD * nr / (e + 2.0);
            u0 = max(u0, uc - hu);
            u1 = min(u1, uc + hu);
            v0 = max(v0, vc - hv);
            v1 = min(v1, vc + hv);
            if (!(u0 < u1) || !(v0 < v1)) return 0.0;
        }
    }
    float ur = -1.0, vr = -1.0;
    float denom = dot(r, nl);
    if (denom != 0.0) {
        float t = dot(s.q0, nl) / denom;
        if (t > 0.0) {
            vec3 q = r * t - s.q0;
            float nn = dot(nl, nl);
            ur = dot(cross(q, e2), nl) / nn;
            vr = dot(cross(e1, q), nl) / nn;
        }
    }
    float ub[4] = float[4](u0, u1, 0.0, 0.0);
    int mu = 2;
    dsAddBreak(ub, mu, ur);
    if (triangle) dsAddBreak(ub, mu, 1.0 - v1);
    float sum = 0.0;
    for (int pu = 0; pu + 1 < mu; ++pu) {
        float hu = 0.5 * (ub[pu + 1] - ub[pu]), cu = 0.5 * (ub[pu + 1] + ub[pu]);
        for (int i = 0; i < 8; ++i) {
            float u = cu + hu * kLobeNode[i];
            float top = triangle ? min(v1, 1.0 - u) : v1;
            if (!(top > v0)) continue;
            float vb[4] = float[4](v0, top, 0.0, 0.0);
            int mv = 2;
            dsAddBreak(vb, mv, vr);
            float inner = 0.0;
            for (int pv = 0; pv + 1 < mv; ++pv) {
                float hv = 0.5 * (vb[pv + 1] - vb[pv]), cv = 0.5 * (vb[pv + 1] + vb[pv]);
                float panel = 0.0;
                for (int j = 0; j < 8; ++j) panel += kLobeWeight[j] * dsLobeIntegrand(s, u, cv + hv * kLobeNode[j]);
                inner += hv * panel;
            }
            sum += hu * kLobeWeight[i] * inner;
        }
    }
    return sum * area2;
}

const int kMaxDirectRectLights = 8;

// Direct radiance leaving p (normal n facing wo) of `object` towards wo; `pixel` = y·width + x with
// y counted from the top, the CPU predictor's pixel index.
vec3 rrfExactDirect(vec3 p, vec3 n, vec3 wo, int object, uint pixel) {
    vec4 counts = dsTexel(0), first = dsTexel(1);
    int rects = min(int(counts.x), kMaxDirectRectLights);
    vec4 m0 = dsTexel(int(dsTexel(2).x) + 2 * object), m1 = dsTexel(int(dsTexel(2).x) + 2 * object + 1);
    vec3 kd = m0.xyz, ks = m1.xyz;
    float e = m0.w;
    bool glossy = any(notEqual(ks, vec3(0.0)));
    vec3 mirror = 2.0 * dot(wo, n) * n - wo;

    uvec2 key = rngPixelKey(pixel);
    vec2 shift[kMaxDirectRectLights];
    float sumF[kMaxDirectRectLights], sumFV[kMaxDirectRectLights];
    float sumG[kMaxDirectRectLights], sumGV[kMaxDirectRectLights];  // Σ g f, Σ g f V: the glossy ratio
    rngStart(key, 0xFFFFFFFFu);  // rrf::kShiftSample
    for (int r = 0; r < rects; ++r) {
        float su = rngUniform();
        shift[r] = vec2(su, rngUniform());
        sumF[r] = 0.0;
        sumFV[r] = 0.0;
        sumG[r] = 0.0;
        sumGV[r] = 0.0;
    }
    int samples = uDirectGrid.x, cols = uDirectGrid.y, rows = uDirectGrid.z;
    for (int s = 0; s < samples; ++s) {
        rngStart(key, uint(s));
        float cellU = float(s % cols), cellV = float(s / cols);
        for (int r = 0; r < rects; ++r) {
            int t = int(first.x) + 4 * r;
            vec4 c = dsTexel(t), a1 = dsTexel(t + 1), a2 = dsTexel(t + 2);
            float j1 = rngUniform();
            float j2 = rngUniform();
            float u = (cellU + j1) / float(cols) + shift[r].x;
            float v = (cellV + j2) / float(rows) + shift[r].y;
            if (u >= 1.0) u -= 1.0;
            if (v >= 1.0) v -= 1.0;
            if (a2.w > 0.5 && u + v > 1.0) {  // rrf::Light::pointAt's fold of the square onto a triangle
                u = 1.0 - u;
                v = 1.0 - v;
            }
            vec3 x = c.xyz + a1.xyz * u + a2.xyz * v;
            vec3 d = x - p;
            float dist2 = dot(d, d);
            if (!(dist2 > 0.0)) continue;
            vec3 wi = d / sqrt(dist2);
            float cosTheta = dot(wi, n);
            if (cosTheta <= 0.0) continue;
            float cosL = -dot(wi, normalize(cross(a1.xyz, a2.xyz)));
            if (c.w < 0.5) cosL = abs(cosL);
            if (cosL <= 0.0) continue;
            float f = cosTheta * cosL / dist2;
            float g = glossy ? dsPowCos(dot(mirror, wi), e) : 0.0;
            bool vis = dsVisible(p, n, x);
            sumF[r] += f;
            sumG[r] += g * f;
            if (vis) {
                sumFV[r] += f;
                sumGV[r] += g * f;
            }
        }
    }

    vec3 L = vec3(0.0);
    for (int r = 0; r < rects; ++r) {
        int t = int(first.x) + 4 * r;
        vec4 c = dsTexel(t), a1 = dsTexel(t + 1), a2 = dsTexel(t + 2), le = dsTexel(t + 3);
        vec3 clippedCentre;
        float omega = dsProjectedSolidAngle(c.xyz, a1.xyz, a2.xyz, a2.w > 0.5, c.w > 0.5, p, n, clippedCentre);
        if (!(omega > 0.0)) continue;
        float ratio = sumF[r] > 0.0 ? sumFV[r] / sumF[r] : (dsVisible(p, n, clippedCentre) ? 1.0 : 0.0);
        L += kd * le.rgb * (omega * kInvPiD * ratio);
        if (glossy) {
            // Unshadowed glossy light by quadrature, times the lobe-weighted visibility ratio.
            float lobe = dsPhongLobeIntegral(c.xyz, a1.xyz, a2.xyz, a2.w > 0.5, c.w > 0.5, p, n, mirror, e);
            float glossyRatio = sumG[r] > 0.0 ? sumGV[r] / sumG[r] : ratio;
            L += le.rgb * ks * ((e + 2.0) * kInv2PiD * lobe * glossyRatio);
        }
    }
    for (int k = 0; k < int(counts.y); ++k) {
        int t = int(first.y) + 2 * k;
        vec3 lp = dsTexel(t).xyz, intensity = dsTexel(t + 1).xyz;
        vec3 d = lp - p;
        float dist2 = dot(d, d);
        if (!(dist2 > 0.0)) continue;
        vec3 wi = d / sqrt(dist2);
        float cosTheta = dot(wi, n);
        if (cosTheta <= 0.0 || !dsVisible(p, n, lp)) continue;
        L += intensity * (kd * kInvPiD + ks * ((e + 2.0) * kInv2PiD * dsPowCos(dot(mirror, wi), e))) * (cosTheta / dist2);
    }
    return L;
}

// The direct term of pixel px (gl_FragCoord) in modes 1 and 2.
vec3 rrfDirectLight(ivec2 px, ivec2 size, vec3 p, vec3 n, vec3 wo, int object) {
    if (uDirectMode == 2) return texelFetch(uDirectHost, px, 0).rgb;
    return rrfExactDirect(p, n, wo, object, uint((size.y - 1 - px.y) * size.x + px.x));
}
