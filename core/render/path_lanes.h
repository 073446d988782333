#pragma once
/// The path tracer's lockstep vertices as SIMD lanes (issue 28 item 4; docs/design.md §5, "The
/// tracer's lanes"), for AVX2 (two halves of 8) and AVX-512: for a batch of up to 16 diffuse paths
/// at the same depth, one vertex step (the light samples of every path, their shadow rays as one
/// Embree packet per light, the BRDF bounce and Russian roulette, the bounce rays as one packet,
/// the arrival at the next hit) runs on structure-of-arrays state, one path per lane, without a
/// branch per path.
///
/// Every lane does trace()'s arithmetic in trace()'s order with the same IEEE operations (no fused
/// multiply-add: the unit is built with -ffp-contract=off; the cosine and sine of the bounce by the C
/// library, lane by lane), and draws its path's random numbers in the same order, so a path's result
/// is trace()'s bit for bit (test PathTracer.BatchIsTracePerSample*), up to the edge cases in which
/// Embree answers a packet and a single ray differently (its sphere test, in a last bit).
///
/// Like the MLP's kernels (nn/mlp_isa.h) the lanes are one translation unit per instruction set,
/// built with that set's flags and called only on a CPU that has it (isaSupported()); nothing
/// but this header's plain structs crosses the boundary, and everything the unit defines lives in its
/// own namespace (CTest `isa_symbols`).

#include <cstdint>

#include <embree3/rtcore.h>

namespace rrf::path_lanes {

/// Paths per batch, one per lane: Embree's widest packet.
constexpr int kLanes = 16;

/// Three coordinates of 16 lanes.
struct alignas(64) Lanes3 {
    float x[kLanes], y[kLanes], z[kLanes];
};

/// The paths of a batch at their current vertex, path i in lane i. Set up by the caller from the
/// vertex as PathTracer's enter() sees it; step() adds the vertex's light and turns the lanes that
/// bounce into the next rays.
struct alignas(64) PathLanes {
    Lanes3 p;         ///< hit point
    Lanes3 ng;        ///< geometric normal as stored
    Lanes3 n;         ///< shading normal turned to the side the path arrived from
    Lanes3 kd;        ///< the diffuse BRDF's albedo
    Lanes3 beta;      ///< throughput
    Lanes3 direct;    ///< Radiance::direct so far
    Lanes3 indirect;  ///< Radiance::indirect so far
    float side[kLanes];      ///< dot(wo, ng)
    uint64_t rng[kLanes];    ///< each path's Rng counter (Rng::state())
    uint32_t live = 0;       ///< lanes at a vertex (bit i = lane i)
    uint32_t smooth = 0;     ///< lanes whose hit has a shading normal of its own
    int depth = 0;           ///< the vertex's depth, the same for every live lane
};

/// A rect light as the light sample reads it.
struct RectLight {
    float corner[3], edge1[3], edge2[3];
    float nl[3];  ///< cross(edge1, edge2)
    float radiance[3];
    int oneSided;
};

/// A point light as the light sample reads it.
struct PointLight {
    float position[3], intensity[3];
};

/// The movable area light's ray test (PathTracer's AreaLightShape at its corner).
struct MovableLight {
    float corner[3], edge1[3], edge2[3], n[3], nn;  ///< a rect (AreaLightShape)
    float normal[3];  ///< Light::normal(), the hit's geometric normal
    int material;     ///< the light's material (-1: black)
    float radiance[3];
    int oneSided;
};

/// What step() needs besides the lanes.
struct Setup {
    RTCScene scene;
    const RTCIntersectContext* context;  ///< initialised by the caller (Embree's inline function)
    float sceneScale;                    ///< Accel's, for ray offsets
    const RectLight* rect;
    int rectCount;
    const PointLight* point;
    int pointCount;
    const MovableLight* movable;  ///< null when the scene has no movable area light
    int bounces;                  ///< whether vertices at this depth bounce (PathTracer's enter())
    // Where the bounce rays arrive, by Embree's geomID (Accel::GeometryTable):
    const int* geomMaterial;    ///< the material of what the geometry is (-1: a black emitter)
    const int* geomNormalBase;  ///< Accel::GeometryTable::normalBase
    const float* normals;       ///< Accel::GeometryTable::normals
    const float* materialKd;    ///< x, y, z per material: the diffuse BRDF's kd
    // The emission a camera ray sees (start()), by Embree's geomID and by Scene light:
    const int* geomLight;          ///< Accel::GeometryTable::light
    const float* lightRadiance;    ///< x, y, z per light
    const float* lightNormal;      ///< cross(edge1, edge2), x, y, z per light
    const int* lightOneSided;      ///< per light
    const RTCIntersectContext* cameraContext;  ///< start()'s packet (coherent when one origin)
};

/// One step's packet and outcome: the rays traced (the bounce rays, or start()'s camera rays), with
/// tfar and hit filled by Embree for the lanes in `bounced`, and the shadow rays traced.
struct alignas(64) Step {
    RTCRayHit16 next;
    uint32_t bounced = 0;   ///< the lanes that bounced
    uint32_t resolve = 0;   ///< those of them that hit a geometry without a table entry
    uint64_t shadowRays = 0;
};

/// step(): adds the light sampled at the live lanes' vertices to their direct (depth 0) or indirect light,
/// then samples their bounces and traces them (`out`). A bounce that arrives at a geometry with a
/// table entry or at the movable light leaves its lane live at the new vertex (PathTracer's arrive()
/// and enter() for a diffuse NEE path: no emission counted, the shading normal the geometric one);
/// `out.resolve` are the lanes the caller sets up itself (spheres, vertex normals). Lanes that end
/// leave `live`.
/// start(): the camera rays the caller put in out.next.ray (the lanes of lanes.live, all others
/// unset: beta 1, no light yet; any tnear and tfar), traced as one packet, and their first vertices
/// set up as step() sets up a bounce's, the emission seen there added to `direct` (PathTracer's
/// emissionSeen()).
#define RRF_PATH_LANES_DECLARE(isa) \
    namespace isa {                 \
    void step(const Setup& setup, PathLanes& lanes, Step& out); \
    void start(const Setup& setup, PathLanes& lanes, Step& out); \
    }
RRF_PATH_LANES_DECLARE(avx2)
RRF_PATH_LANES_DECLARE(avx512)
#undef RRF_PATH_LANES_DECLARE

/// The lanes' instruction sets; None is the portable lockstep.
enum class Isa { None, Avx2, Avx512 };
/// "AVX-512 lanes", "AVX2 lanes" or "portable".
const char* isaName(Isa isa);
/// Whether this build has the lanes for `isa` and this CPU runs them (None always).
bool isaSupported(Isa isa);
/// The widest lanes this build and CPU run (None if none).
Isa bestIsa();
/// One instruction set's step() and start().
using StepFunction = void (*)(const Setup&, PathLanes&, Step&);
struct Kernels {
    StepFunction step = nullptr, start = nullptr;
};
/// The kernels of `isa`; null for None.
Kernels kernelsOf(Isa isa);

}  // namespace rrf::path_lanes
