#version 330 core
// G-buffer pass, vertex stage. Geometry arrives non-indexed so that every triangle carries its own
// flat attributes (the plane it lies in, its CPU geometric normal, its object id and kind).
// The projection reproduces rrf::CameraRays: a point maps to the pixel whose ray passes through it.

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec4 aGeometry;  // polygon: triangle plane (unit n, d = n·p); sphere: (centre, radius)
layout(location = 2) in vec3 aNormal;    // polygon: geometric normal as core/scene/accel.cpp stores it
layout(location = 3) in vec2 aInfo;      // (object id, or -2 for a light; kind, see gbuffer.frag)
layout(location = 4) in vec3 aEmission;  // lights: emitted radiance
layout(location = 5) in vec3 aShading;   // smooth meshes: the vertex normal; zero: flat

uniform vec3 uEye;
uniform vec3 uForward;   // unit
uniform vec3 uRightUnit; // unit
uniform vec3 uUpUnit;    // unit
uniform vec2 uTanHalf;   // (tan(fovY/2) * width/height, tan(fovY/2))
uniform vec2 uNearFar;   // clip distances along the view axis

flat out vec4 vGeometry;
flat out vec3 vNormal;
flat out vec2 vInfo;
flat out vec3 vEmission;
out vec3 vShading;  // interpolated (perspective-correct: barycentric on the triangle, as Embree's u, v)

void main() {
    vec3 d = aPosition - uEye;
    float x = dot(d, uRightUnit), y = dot(d, uUpUnit), z = dot(d, uForward);
    float n = uNearFar.x, f = uNearFar.y;
    // Only clipping uses this depth; the fragment stage writes the exact ray distance as depth.
    gl_Position = vec4(x / uTanHalf.x, y / uTanHalf.y, (z * (f + n) - 2.0 * f * n) / (f - n), z);
    vGeometry = aGeometry;
    vNormal = aNormal;
    vInfo = aInfo;
    vEmission = aEmission;
    vShading = aShading;
}
