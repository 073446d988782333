#include "core/predict/gbuffer.h"

#include <algorithm>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/scene/camera_rays.h"

namespace rrf {

namespace {
/// An empty buffer of `count` samples laid out as width × height.
GBuffer emptyBuffer(const PathTracer& tracer, const RecordLayout& layout, const Vec3& lightPos, int width, int height) {
    const Scene& scene = tracer.scene();
    GBuffer g;
    g.width = width;
    g.height = height;
    g.numInputs = layout.inputCount();
    const bool hasMovable = scene.movableLight >= 0 && scene.movableLight < int(scene.lights.size());
    g.lightPosition = hasMovable ? lightPos : scene.lightPosition();
    const size_t n = g.pixelCount();
    g.inputs.assign(n * size_t(g.numInputs), 0.f);
    g.object.assign(n, -1);
    g.light.assign(n, -1);
    g.emitted.assign(n, Vec3(0.f));
    g.normal.assign(n, Vec3(0.f));
    g.distance.assign(n, 0.f);
    g.geometricNormal.assign(n, Vec3(0.f));
    return g;
}

/// Traces `ray` and writes sample i of `g`: the network inputs of what it hit, or the emission of
/// the light it sees.
void writeSample(const PathTracer& tracer, const RecordLayout& layout, const Light& movable, const Ray& ray, size_t i,
                 GBuffer& g) {
    const Scene& scene = tracer.scene();
    Hit hit;
    if (!tracer.intersect(ray, movable, hit)) return;
    const Vec3 wo = -ray.dir;
    if (hit.light >= 0) {
        g.light[i] = hit.light;
        const Light& l = hit.light == scene.movableLight ? movable : scene.lights[size_t(hit.light)];
        g.emitted[i] = l.emittedTowards(wo);
        return;
    }
    g.object[i] = hit.object;
    const Vec3 ns = hit.shading();
    g.normal[i] = dot(wo, ns) >= 0.f ? ns : -ns;  // as RecordLayout::writeInputs flips it
    g.geometricNormal[i] = dot(wo, hit.ng) >= 0.f ? hit.ng : -hit.ng;
    g.distance[i] = hit.t;                         // ray.dir is unit
    layout.writeInputs(hit.p, wo, g.lightPosition, ns,
                       scene.materials[size_t(scene.objects[size_t(hit.object)].material)],
                       g.inputs.data() + i * size_t(g.numInputs));
}

/// Sequential pass: ascending pixel order makes the masks (and so every batch) deterministic.
void indexPixels(const Scene& scene, GBuffer& g) {
    g.pixelsByObject.assign(scene.objects.size(), {});
    for (size_t i = 0; i < g.pixelCount(); ++i) {
        if (g.object[i] >= 0) g.pixelsByObject[size_t(g.object[i])].push_back(uint32_t(i));
        else if (g.light[i] >= 0) g.emitterPixels.push_back(uint32_t(i));
        else ++g.backgroundPixels;
    }
}

Light movableOf(const PathTracer& tracer, const GBuffer& g) {
    const Scene& scene = tracer.scene();
    const bool hasMovable = scene.movableLight >= 0 && scene.movableLight < int(scene.lights.size());
    return hasMovable ? tracer.movableLightAt(g.lightPosition) : Light{};
}
}  // namespace

GBuffer buildGBuffer(const PathTracer& tracer, const RecordLayout& layout, const Vec3& lightPos, int width, int height) {
    if (width <= 0 || height <= 0) throw std::invalid_argument("buildGBuffer: image size must be positive");
    GBuffer g = emptyBuffer(tracer, layout, lightPos, width, height);
    const Light movable = movableOf(tracer, g);
    const CameraRays camera(tracer.scene().camera, width, height);
    tbb::parallel_for(0, height, [&](int y) {
        for (int x = 0; x < width; ++x)
            writeSample(tracer, layout, movable, camera.generate(x, y, 0.5f, 0.5f), size_t(y) * size_t(width) + size_t(x), g);
    });
    indexPixels(tracer.scene(), g);
    return g;
}

GBuffer buildGBufferFromRays(const PathTracer& tracer, const RecordLayout& layout, const Vec3& lightPos,
                             const std::vector<Ray>& rays) {
    // Rows of kRaysPerRow: the passes over a buffer (exact direct light) run in parallel over rows.
    const size_t width = std::min(rays.size(), kRaysPerRow);
    const size_t height = width ? (rays.size() + width - 1) / width : 0;
    GBuffer g = emptyBuffer(tracer, layout, lightPos, int(width), int(height));
    const Light movable = movableOf(tracer, g);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i < r.end(); ++i)
            if (rays[i].tmax > rays[i].tmin) writeSample(tracer, layout, movable, rays[i], i, g);
    });
    indexPixels(tracer.scene(), g);
    return g;
}

}  // namespace rrf
