#include "core/predict/glossy_gather.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "core/predict/exact_direct.h"
#include "core/util/warp.h"

namespace rrf {


bool GlossyGather::gathers(const Scene& scene, const Object& o, const PredictionSettings& settings) {
    const PredictionSettings::Gather& g = settings.gather;
    if (!g.on()) return false;
    if (applies(scene.materials[size_t(o.material)], float(g.minExponent))) return true;
    return std::find(g.objects.begin(), g.objects.end(), o.name) != g.objects.end();
}

bool gatherApplies(const Scene& scene, const PredictionSettings& settings) {
    for (const Object& o : scene.objects)
        if (GlossyGather::gathers(scene, o, settings)) return true;
    return false;
}

GlossyGather::GlossyGather(const PathTracer& tracer, const RecordLayout& layout, int lobeSamples, int diffuseSamples,
                           uint64_t seed)
    : tracer_(tracer),
      layout_(layout),
      lobeSamples_(std::max(0, lobeSamples)),
      diffuseSamples_(std::max(0, diffuseSamples)),
      seed_(mix64(seed ^ kGlossyGatherStream)) {}

GlossyGather::Batch GlossyGather::trace(const GBuffer& gb, const uint32_t* pixels, size_t count,
                                        const GlossyCaustics* caustics) const {
    const Scene& scene = tracer_.scene();
    const size_t per = size_t(raysPerPixel());
    std::vector<Ray> rays(count * per);
    Batch b;
    b.weight.assign(rays.size(), Vec3(0.f));
    const SampleGrid lobeGrid(std::max(1, lobeSamples_)), diffuseGrid(std::max(1, diffuseSamples_));
    tbb::parallel_for(size_t(0), count, [&](size_t j) {
        const uint32_t i = pixels[j];
        const int object = gb.object[i];
        if (object < 0) return;
        const Material& m = scene.materials[size_t(scene.objects[size_t(object)].material)];
        const float* in = gb.input(i);
        const Vec3 p(in[0], in[1], in[2]), wo(in[3], in[4], in[5]);
        const Vec3 n = gb.normal[i], ng = gb.geometricNormal[i];
        const Frame frame(n);
        const Vec3 woLocal = frame.toLocal(wo);
        if (woLocal.z <= 0.f) return;
        const Frame lobe(reflect(woLocal, Vec3(0, 0, 1)));
        const Vec3 ks = m.type == Material::Type::Phong ? m.ks : Vec3(0.f);
        const uint64_t key = Rng::streamKey(seed_, i);
        Rng shiftRng = Rng::ofStream(key, kShiftSample);
        const float su = shiftRng.uniform(), sv = shiftRng.uniform(), du = shiftRng.uniform(), dv = shiftRng.uniform();
        for (size_t k = 0; k < per; ++k) {
            Rng rng = Rng::ofStream(key, k);
            const bool glossy = k < size_t(lobeSamples_);
            float u, v;
            Vec3 wl, w;
            if (glossy) {
                lobeGrid.point(int(k), rng, su, sv, u, v);
                wl = lobe.toWorld(samplePhongLobe(u, v, m.exponent));
                if (wl.z <= 0.f) continue;
                w = ks * ((m.exponent + 2.f) / (m.exponent + 1.f) * wl.z / float(lobeSamples_));
            } else {
                diffuseGrid.point(int(k) - lobeSamples_, rng, du, dv, u, v);
                wl = sampleCosineHemisphere(u, v);
                if (wl.z <= 0.f) continue;
                w = m.kd / float(diffuseSamples_);
            }
            if (w.isZero()) continue;
            const Vec3 dir = normalize(frame.toWorld(wl));
            // Above the shading normal but into the surface (smooth meshes): no light comes from
            // there, as a path tracer ends such paths.
            if (dot(dir, ng) <= 0.f) continue;
            Ray& r = rays[j * per + k];
            r.origin = tracer_.accel().spawnOrigin(p, ng, dir);
            r.dir = dir;
            b.weight[j * per + k] = w;
        }
    });
    // Untraced rays (zero weight) are marked empty so buildGBufferFromRays skips them.
    for (size_t k = 0; k < rays.size(); ++k)
        if (b.weight[k].isZero()) rays[k].tmax = 0.f;
    b.secondary = buildGBufferFromRays(tracer_, layout_, gb.lightPosition, rays);
    if (caustics && caustics->anyCaster()) {
        b.secondary.directWithoutGloss.assign(b.secondary.pixelCount(), 0);
        // Cosine rays onto another caster; light an object reflects onto itself stays with its rays.
        for (size_t k = 0; k < rays.size(); ++k) {
            const int hit = b.secondary.object[k];
            if (k % per >= size_t(lobeSamples_) && hit != gb.object[pixels[k / per]] && caustics->casts(hit))
                b.secondary.directWithoutGloss[k] = 1;
        }
    }
    return b;
}

Vec3 GlossyGather::gathered(const Batch& b, const Image& radiance, size_t j) const {
    const size_t per = size_t(raysPerPixel());
    Vec3 sum(0.f);
    const size_t w = size_t(std::max(1, b.secondary.width));
    for (size_t k = j * per; k < (j + 1) * per; ++k)
        if (b.secondary.object[k] >= 0) sum += b.weight[k] * radiance.at(int(k % w), int(k / w));
    return sum;
}

}  // namespace rrf
