// The GLSL predictor's direct light (GlslPredictor::setPrediction): exact direct light in the shader
// (shaders/direct_light.glsl) over the scene's triangles uploaded here, or, above the shader's
// triangle limit, computed on the CPU (core/predict/exact_direct.h) and uploaded each frame.

#include "app/gl/glsl_predictor.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glad/gl.h>

#include <tbb/parallel_for.h>

#include "app/gl/gl_state.h"
#include "core/predict/exact_direct.h"

namespace rrf {

void GlslPredictor::setPrediction(const PredictionSettings& prediction) {
    const bool same = prediction.direct == prediction_.direct && prediction.directSamples == prediction_.directSamples &&
                      prediction.seed == prediction_.seed;
    prediction_ = prediction;
    if (same) return;
    directMode_ = 0;
    directNote_.clear();
    if (prediction.direct != PredictionSettings::Direct::Exact) return;
    size_t triangles = 0, rects = 0;
    for (const Object& o : scene_.objects)
        if (o.kind != Object::Kind::Sphere) triangles += o.primitiveCount() * (o.kind == Object::Kind::Quads ? 2 : 1);
    for (const Light& l : scene_.lights) rects += l.isArea();
    if (triangles <= size_t(kMaxShaderDirectTriangles) && rects <= size_t(kMaxShaderDirectRectLights)) {
        directMode_ = 1;
        uploadDirectScene();
        return;
    }
    directMode_ = 2;
    directNote_ = "exact direct light on the CPU: the scene has " + std::to_string(triangles) + " triangles and " +
                  std::to_string(rects) + " area lights, the shader's brute-force shadow rays take at most " +
                  std::to_string(kMaxShaderDirectTriangles) + " and " + std::to_string(kMaxShaderDirectRectLights);
    std::fprintf(stderr, "GLSL predictor: %s\n", directNote_.c_str());
    if (!hostTracer_) {
        hostAccel_ = std::make_unique<Accel>(scene_);
        hostTracer_ = std::make_unique<PathTracer>(scene_, *hostAccel_, Estimator::NEE, 1);
    }
    if (!directHostTex_) {
        GlStateGuard guard;
        directHostTex_ = makeFloatTexture(1, 1, nullptr);
    }
}

void GlslPredictor::uploadDirectScene() {
    // Layout: shaders/direct_light.glsl's header comment.
    std::vector<float> rects, points, materials, triangles, spheres;
    auto put = [](std::vector<float>& v, const Vec3& a, float w) { v.insert(v.end(), {a.x, a.y, a.z, w}); };
    for (const Light& l : scene_.lights) {
        if (l.isArea()) {
            put(rects, l.corner, l.oneSided ? 1.f : 0.f);
            put(rects, l.edge1, l.area());
            put(rects, l.edge2, l.type == Light::Type::Triangle ? 1.f : 0.f);
            put(rects, l.radiance, 0.f);
        } else {
            put(points, l.position, 0.f);
            put(points, l.intensity, 0.f);
        }
    }
    for (const Object& o : scene_.objects) {
        const Brdf b = o.material >= 0 ? Brdf(scene_.materials[size_t(o.material)]) : Brdf();
        put(materials, b.kd, b.n);
        put(materials, b.ks, 0.f);
        if (o.kind == Object::Kind::Sphere) {
            put(spheres, o.center, o.radius);
            continue;
        }
        const size_t nv = size_t(o.verticesPerPrimitive());
        for (size_t p = 0; p < o.primitiveCount(); ++p) {
            Vec3 q[4];
            for (size_t k = 0; k < nv; ++k) q[k] = o.positions[o.indices[p * nv + k]];
            // Embree's split of a quad v0 v1 v2 v3: (v0, v1, v3) and (v2, v3, v1), as addQuad.
            const int tris[2][3] = {{0, 1, 3}, {2, 3, 1}};
            if (nv == 4) {
                for (const auto& t : tris)
                    for (int k : t) put(triangles, q[k], 0.f);
            } else {
                for (int k = 0; k < 3; ++k) put(triangles, q[k], 0.f);
            }
        }
    }
    const float header = 3.f;
    const float nRect = float(rects.size() / 16), nPoint = float(points.size() / 8), nTri = float(triangles.size() / 12),
                nSphere = float(spheres.size() / 4);
    const float firstRect = header, firstPoint = firstRect + 4 * nRect, firstMaterial = firstPoint + 2 * nPoint,
                firstTri = firstMaterial + float(materials.size() / 4), firstSphere = firstTri + 3 * nTri;
    std::vector<float> data = {nRect, nPoint, nTri, nSphere, firstRect, firstPoint, firstTri, firstSphere,
                               firstMaterial, 0.f, 0.f, 0.f};
    for (const auto* part : {&rects, &points, &materials, &triangles, &spheres}) data.insert(data.end(), part->begin(), part->end());
    if (!directBuffer_) glGenBuffers(1, &directBuffer_);
    glBindBuffer(GL_TEXTURE_BUFFER, directBuffer_);
    glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(data.size() * sizeof(float)), data.data(), GL_DYNAMIC_DRAW);
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
    if (!directBufferTex_) {
        GLint active = 0, bound = 0;
        glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
        glActiveTexture(GL_TEXTURE4);
        glGetIntegerv(GL_TEXTURE_BINDING_BUFFER, &bound);
        glGenTextures(1, &directBufferTex_);
        glBindTexture(GL_TEXTURE_BUFFER, directBufferTex_);
        glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, directBuffer_);
        glBindTexture(GL_TEXTURE_BUFFER, GLuint(bound));
        glActiveTexture(GLenum(active));
    }
    checkGl("uploading the scene for exact direct light");
}

void GlslPredictor::computeHostDirect() {
    const GlGBuffer g = readGBuffer();
    const int w = g.width, h = g.height;
    const ExactDirect direct(*hostTracer_, prediction_.directSamples, prediction_.seed);
    const Light movable = hostTracer_->movableLightAt(scene_.lightPosition());
    const Vec3 eye = scene_.camera.eye;
    std::vector<float> rgba(4 * g.pixelCount(), 0.f);
    tbb::parallel_for(0, h, [&](int y) {
        TraceCounters counters;
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            if (g.objectId[i] < 0) continue;
            const Vec3 p(g.position[3 * i], g.position[3 * i + 1], g.position[3 * i + 2]);
            const Vec3 n(g.normal[3 * i], g.normal[3 * i + 1], g.normal[3 * i + 2]);
            Vec3 L = direct.radiance(p, n, normalize(eye - p), g.objectId[i], movable, i, counters);
            if (!L.isFinite()) L = Vec3(0.f);
            float* out = &rgba[4 * (size_t(h - 1 - y) * size_t(w) + size_t(x))];  // GL rows: bottom first
            for (int c = 0; c < 3; ++c) out[c] = L[c];
        }
    });
    glActiveTexture(GL_TEXTURE5);
    glBindTexture(GL_TEXTURE_2D, directHostTex_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, rgba.data());
    checkGl("uploading CPU-computed direct light");
}

}  // namespace rrf
