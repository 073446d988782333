#pragma once
/// Bidirectional path tracing with multiple importance sampling over all strategies (Veach 1997
/// ch. 10, pbrt-v3 §16.3), for the reference images and training records of scenes whose glossy
/// lobes carry light from the emitters to diffuse surfaces (caustics), which the unidirectional path
/// tracer finds only by rare BRDF samples (docs/design.md §4a).
///
/// A sample builds an eye subpath and a light subpath and connects every prefix pair (s light
/// vertices, t eye vertices). Strategy (s, t) produces a path of s + t vertices; its contribution is
/// weighted by the power heuristic over every other strategy that could have produced the same path
/// (ratios of the vertices' forward and reverse area densities, pbrt's MISWeight). The strategies:
///   s = 0        the eye subpath hits an emitter (BRDF sampling, as the naive estimator);
///   s = 1        a fresh light sample connected to an eye vertex (next-event estimation);
///   t = 1        a light-subpath vertex connected to the camera: light tracing, "splatted" onto the
///                pixel it projects to (image renders only; a record's start point cannot be hit);
///   s, t ≥ 2     connections of inner vertices.
/// With `lightTracingOnly` the inner connections are left out and the other three are combined
/// (the path tracer and the light tracer by MIS), cheaper per sample.
///
/// The eye subpath starts either at the pinhole camera (renders: vertex 0 is the camera) or at a
/// surface point seen along a fixed direction (training records: vertex 0 is that point). The
/// output splits like the path tracer's: direct = emission seen directly + paths of exactly one
/// reflection, indirect = paths of two or more reflections.
///
/// Determinism: every random number of a sample comes from the Rng the caller passes (camera side)
/// and from Rng(seed, stream, sample) of its own light stream (bdptLightRng), so renders are
/// identical for any thread count. The light subpath's Russian roulette divides the throughput and
/// keeps the densities, which leaves the MIS weights summing to 1 (unbiased).

#include <cstdint>
#include <vector>

#include "core/render/path_tracer.h"
#include "core/scene/camera_rays.h"

namespace rrf {

/// A light-tracing contribution (strategy t = 1) to pixel `pixel` of the same iteration.
struct Splat {
    uint32_t pixel = 0;
    Radiance L;
};

/// The pinhole camera's importance for light tracing: the density of camera rays over directions
/// (uniform over the image plane at distance 1, 1 / (A cos³θ)) and the projection to pixels.
class PinholeImportance {
public:
    PinholeImportance(const Camera& camera, int width, int height);
    /// Solid-angle density of a camera ray in unit direction `w` (from the eye); 0 outside the image.
    /// It is also the importance W(w) of one light path among width × height per iteration.
    float density(const Vec3& w) const;
    /// Pixel index that direction `w` from the eye falls into; false outside the image.
    bool pixelOf(const Vec3& w, uint32_t& pixel) const;
    const Vec3& eye() const { return eye_; }

private:
    CameraRays rays_;
    Vec3 eye_, forward_;
    float imagePlaneArea_ = 1.f;
    int width_, height_;
};

/// One vertex of a subpath (area densities, pbrt's Vertex).
struct BdptVertex {
    enum class Kind : uint8_t { Camera, Light, Surface };
    Kind kind = Kind::Surface;
    Vec3 p{0.f};
    Vec3 ng{0.f};       ///< unit geometric normal (surfaces: as stored; lights: the emitter's normal)
    Vec3 ns{0.f};       ///< unit shading normal on ng's side (Hit::shading())
    Vec3 beta{0.f};     ///< throughput of the subpath up to and including this vertex's arrival
    Vec3 wPrev{0.f};    ///< unit direction towards the previous vertex (surfaces)
    float pdfFwd = 0.f; ///< area density of this vertex when sampled from its own subpath
    float pdfRev = 0.f; ///< area density when sampled from the other end
    int material = -1;  ///< surfaces: material index (-1: black, the walk ends here)
    int light = -1;     ///< emitter index: light vertices and surfaces that emit
    bool delta = false; ///< point light (a position no ray can hit)
    bool onSurface() const { return kind == Kind::Surface || (kind == Kind::Light && !delta); }
};

class BidirectionalTracer {
public:
    /// `tracer` (an NEE path tracer of the same scene) supplies intersection, occlusion, BRDFs and
    /// lights, and must outlive this. `maxDepth` bounds the reflections of a path, as the path
    /// tracer's does.
    BidirectionalTracer(const PathTracer& tracer, int maxDepth, bool lightTracingOnly = false);

    /// One camera sample through pixel (px, py) (jitter from `rng`): returns the strategies that end
    /// on the camera ray's own pixel (t ≥ 2) and appends the light-tracing contributions (t = 1)
    /// to `splats`. The light subpath draws from `lightRng`. Without `cameraPaths` only the light
    /// subpath and its splats are traced (a part of an image split by rows, for another part's
    /// pixel): the splats are the same either way.
    Radiance tracePixel(const CameraRays& rays, const PinholeImportance& camera, int px, int py, const Light& movable,
                        Rng& rng, Rng& lightRng, TraceCounters& counters, std::vector<Splat>& splats,
                        bool cameraPaths = true) const;
    /// Radiance leaving the surface point `hit` towards `wo` (a training record): strategies t ≥ 1
    /// with the point as the eye subpath's first vertex; `rng` drives both subpaths.
    Radiance shade(const Hit& hit, const Vec3& wo, const Light& movable, Rng& rng, TraceCounters& counters) const;

    const PathTracer& tracer() const { return tracer_; }
    bool lightTracingOnly() const { return lightTracingOnly_; }

private:
    struct Paths;
    /// Extends `path` from `ray` (sampled with solid-angle density `pdfDir` at path.back()) until it
    /// leaves the scene, reaches maxVertices, or a BRDF sample or Russian roulette ends it.
    void walk(Ray ray, Vec3 beta, float pdfDir, bool importance, std::vector<BdptVertex>& path, int maxVertices,
              const Light& movable, Rng& rng, TraceCounters& counters, int bounces = 0) const;
    /// The surface vertex of `hit`, reached with throughput `beta` from direction `wPrev`.
    BdptVertex surfaceVertex(const Hit& hit, const Vec3& beta, const Vec3& wPrev) const;
    /// Samples the BRDF at path.back(): updates `beta` (and the previous vertex's reverse density),
    /// sets the next `ray` and its `pdfDir`; false when the path ends there.
    bool scatter(std::vector<BdptVertex>& path, Vec3& beta, float beta0, int bounces, bool importance, Ray& ray,
                 float& pdfDir, Rng& rng) const;
    void lightSubpath(std::vector<BdptVertex>& path, int maxVertices, const Light& movable, Rng& rng,
                      TraceCounters& counters) const;
    /// Connects every (s, t) of `paths` (camera != null: image sample with splats).
    Radiance connect(Paths& paths, const PinholeImportance* camera, const Light& movable, Rng& rng,
                     TraceCounters& counters, std::vector<Splat>* splats) const;
    float misWeight(const Paths& paths, const BdptVertex& sampled, int s, int t, bool cameraMode,
                    const PinholeImportance* camera, const Light& movable) const;

    // Densities and BRDF values at vertices (bdpt.cpp).
    Vec3 f(const BdptVertex& v, const Vec3& wa, const Vec3& wb, bool importance) const;
    float pdfArea(const BdptVertex& v, const BdptVertex* prev, const BdptVertex& next, const PinholeImportance* camera,
                  const Light& movable) const;
    float pdfLight(const BdptVertex& lightVertex, const BdptVertex& next, const Light& movable) const;
    float pdfLightOrigin(int light, const Light& movable) const;
    int pickLight(float u) const;
    bool visible(const BdptVertex& a, const BdptVertex& b, const Light& movable, TraceCounters& counters) const;
    bool allowed(int s, int t, bool cameraMode) const;

    const PathTracer& tracer_;
    int maxDepth_;
    bool lightTracingOnly_;
    std::vector<double> lightCdf_;  ///< running sum of the emitters' powers (pick ∝ power)
    std::vector<float> lightPick_;  ///< probability of picking each emitter
};

/// The light subpath's random numbers for sample `sample` of stream `stream` (a pixel or record):
/// a stream of its own so that the camera side's numbers are those of any other estimator.
Rng bdptLightRng(uint64_t seed, uint64_t stream, uint64_t sample);

}  // namespace rrf
