#version 330 core
// G-buffer pass, fragment stage: intersects the camera ray of this pixel's centre with the
// rasterised primitive, exactly as the CPU's primary ray (rrf::CameraRays, jitter 0.5) would, so
// that positions do not carry interpolation error.
//   kind 0: triangle of an object (plane intersection)
//   kind 1: sphere proxy (a cube around the sphere; the sphere itself is ray-cast here)
//   kind 2: triangle of a one-sided rect light, kind 3: of a two-sided one
// Outputs (RGBA32F each):
//   0: hit point xyz, id (object id >= 0, -2 for a light; the clear value -1 marks background)
//   1: shading normal flipped to face the viewer (the network input), kind: the geometric normal,
//      or on a smooth mesh the interpolated vertex normals turned to its side (core/scene/accel.cpp)
//   2: emitted radiance towards the eye (lights only), alpha 1

flat in vec4 vGeometry;
flat in vec3 vNormal;
flat in vec2 vInfo;
flat in vec3 vEmission;
in vec3 vShading;

uniform vec3 uEye;
uniform vec3 uForward;  // CameraRays::forward_
uniform vec3 uRight;    // CameraRays::right_ (scaled by tan(fovY/2) * aspect)
uniform vec3 uUp;       // CameraRays::up_ (scaled by tan(fovY/2))
uniform vec2 uViewport; // width, height in pixels
uniform float uFar;     // depth = ray distance / uFar

layout(location = 0) out vec4 oPosition;
layout(location = 1) out vec4 oNormal;
layout(location = 2) out vec4 oEmission;

void main() {
    // gl_FragCoord is the pixel centre (px + 0.5, row-from-bottom + 0.5); image rows grow downwards.
    float sx = 2.0 * gl_FragCoord.x / uViewport.x - 1.0;
    float sy = 1.0 - 2.0 * (uViewport.y - gl_FragCoord.y) / uViewport.y;
    vec3 dir = normalize(uForward + uRight * sx + uUp * sy);
    int kind = int(vInfo.y);

    float t;
    vec3 ng;
    if (kind == 1) {
        // Stable quadratic (Haines et al., "Precision improvements for ray/sphere intersection",
        // Ray Tracing Gems ch. 7): the discriminant from the closest approach, not b^2 - c, and the
        // smaller root as c / q, so neither suffers cancellation.
        vec3 oc = uEye - vGeometry.xyz;
        float r = vGeometry.w;
        float b = dot(oc, dir);
        vec3 f = oc - b * dir;
        float disc = r * r - dot(f, f);
        if (disc < 0.0) discard;
        float q = -b - (b >= 0.0 ? 1.0 : -1.0) * sqrt(disc);
        float c = dot(oc, oc) - r * r;
        float t0 = q != 0.0 ? c / q : 0.0, t1 = q;
        if (t0 > t1) { float s = t0; t0 = t1; t1 = s; }
        t = t0 > 0.0 ? t0 : t1;  // eye inside the sphere: the far side
        if (t <= 0.0) discard;
        ng = normalize(uEye + dir * t - vGeometry.xyz);
    } else {
        float denom = dot(vGeometry.xyz, dir);
        t = (vGeometry.w - dot(vGeometry.xyz, uEye)) / denom;
        // Rasterised but (numerically) parallel to the ray, or behind the eye: no hit.
        if (!(t > 0.0) || isinf(t)) discard;
        ng = vNormal;
    }
    vec3 p = uEye + dir * t;
    vec3 wo = -dir;
    bool lightBack = kind == 2 && dot(wo, ng) <= 0.0;  // one-sided emitters are dark from behind

    gl_FragDepth = clamp(t / uFar, 0.0, 1.0);
    oPosition = vec4(p, vInfo.x);
    vec3 ns = ng;
    if (kind == 0 && dot(vShading, vShading) > 0.0) {
        ns = normalize(vShading);
        if (dot(ns, ng) < 0.0) ns = -ns;
    }
    oNormal = vec4(dot(wo, ns) >= 0.0 ? ns : -ns, float(kind));
    oEmission = vec4(lightBack ? vec3(0.0) : vEmission, 1.0);
}
