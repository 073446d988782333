#include "core/predict/gbuffer.h"

#include <stdexcept>

#include <tbb/parallel_for.h>

#include "core/scene/camera_rays.h"

namespace rrf {

GBuffer buildGBuffer(const PathTracer& tracer, const RecordLayout& layout, const Vec3& lightPos, int width, int height) {
    if (width <= 0 || height <= 0) throw std::invalid_argument("buildGBuffer: image size must be positive");
    const Scene& scene = tracer.scene();
    GBuffer g;
    g.width = width;
    g.height = height;
    g.numInputs = layout.inputCount();
    const bool hasMovable = scene.movableLight >= 0 && scene.movableLight < int(scene.lights.size());
    g.lightPosition = hasMovable ? lightPos : scene.lightPosition();
    const Light movable = hasMovable ? tracer.movableLightAt(g.lightPosition) : Light{};
    const size_t n = g.pixelCount();
    g.inputs.assign(n * size_t(g.numInputs), 0.f);
    g.object.assign(n, -1);
    g.light.assign(n, -1);
    g.emitted.assign(n, Vec3(0.f));
    g.normal.assign(n, Vec3(0.f));
    g.distance.assign(n, 0.f);

    const CameraRays camera(scene.camera, width, height);
    tbb::parallel_for(0, height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const size_t i = size_t(y) * size_t(width) + size_t(x);
            const Ray ray = camera.generate(x, y, 0.5f, 0.5f);
            Hit hit;
            if (!tracer.intersect(ray, movable, hit)) continue;
            const Vec3 wo = -ray.dir;
            if (hit.light >= 0) {
                g.light[i] = hit.light;
                const Light& l = hit.light == scene.movableLight ? movable : scene.lights[size_t(hit.light)];
                g.emitted[i] = l.emittedTowards(wo);
                continue;
            }
            g.object[i] = hit.object;
            const Vec3 ns = hit.shading();
            g.normal[i] = dot(wo, ns) >= 0.f ? ns : -ns;  // as RecordLayout::writeInputs flips it
            g.distance[i] = hit.t;                         // ray.dir is unit
            layout.writeInputs(hit.p, wo, g.lightPosition, ns,
                               scene.materials[size_t(scene.objects[size_t(hit.object)].material)],
                               g.inputs.data() + i * size_t(g.numInputs));
        }
    });

    // Sequential pass: ascending pixel order makes the masks (and so every batch) deterministic.
    g.pixelsByObject.assign(scene.objects.size(), {});
    for (size_t i = 0; i < n; ++i) {
        if (g.object[i] >= 0) g.pixelsByObject[size_t(g.object[i])].push_back(uint32_t(i));
        else if (g.light[i] >= 0) g.emitterPixels.push_back(uint32_t(i));
        else ++g.backgroundPixels;
    }
    return g;
}

}  // namespace rrf
