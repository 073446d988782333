#pragma once
/// Embree 3 acceleration structure over a Scene: every object and every area light except the
/// movable one becomes one Embree geometry (quads, triangles or a sphere point); the movable light
/// is intersected analytically by PathTracer so it can move per path without a rebuild. Built with RTC_SCENE_FLAG_ROBUST so that rays
/// exactly along edges and through vertices do not slip between primitives.
///
/// Hit normals are our own per-primitive geometric normals (not Embree's Ng), so the orientation
/// convention does not depend on Embree's winding rules.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <embree3/rtcore.h>

#include "core/scene/scene.h"

namespace rrf {

struct Ray {
    Vec3 origin;
    Vec3 dir;  ///< unit length
    float tmin = 0.f;
    float tmax = INFINITY;
};

/// What a ray hit. Either an object (object ≥ 0) or an emitter (light ≥ 0), never both.
struct Hit {
    float t = INFINITY;
    Vec3 p;       ///< hit point
    Vec3 ng;      ///< unit geometric normal, as stored (not flipped towards the ray)
    /// Unit shading normal: the object's interpolated vertex normals where it has them (turned to
    /// ng's side); zero = none (hits built by hand). Read it through shading().
    Vec3 ns{0.f};
    int object = -1;
    int light = -1;
    uint32_t prim = 0;
    bool valid() const { return object >= 0 || light >= 0; }
    /// The normal shading uses (BRDF frame, cosines, network input): ns, or ng where there is none.
    /// Ray offsets and the side a ray arrives from use ng.
    Vec3 shading() const { return ns.isZero() ? ng : ns; }
};

class Accel {
public:
    /// Builds the BVH. Throws std::runtime_error with Embree's message on failure. Smooth meshes'
    /// vertex normals are read from `scene` at every hit, so the scene's objects must outlive the
    /// Accel and stay where they are (rebuild the Accel after changing Scene::objects).
    /// `embreeConfig`: more of Embree's device configuration, e.g. "max_isa=avx2" (the tests run the
    /// tracer's lanes on Embree's narrower kernels that way).
    explicit Accel(const Scene& scene, const std::string& embreeConfig = "");
    ~Accel();
    Accel(const Accel&) = delete;
    Accel& operator=(const Accel&) = delete;

    /// Closest hit in [ray.tmin, ray.tmax]; returns false on a miss.
    bool intersect(const Ray& ray, Hit& hit) const;
    /// True if anything lies in [ray.tmin, ray.tmax].
    bool occluded(const Ray& ray) const;
    /// occluded() for `count` ≤ kPacket rays at once (blocked[i] = occluded(rays[i])), traced as one
    /// Embree packet, marked coherent when the rays share their origin: the shadow rays of one
    /// receiver to one light leave from the same origin towards nearby points, so the packet shares
    /// its traversal and runs several times faster than the rays one by one (bench/bench_direct.cpp);
    /// rays from many points go as an incoherent packet, still faster than one by one
    /// (bench/bench_render.cpp). Same answers as occluded() up to the edge cases of two watertight ray
    /// tests.
    static constexpr int kPacket = 16;
    void occludedPacket(const Ray* rays, int count, bool* blocked) const;
    /// intersect() for `count` ≤ kPacket rays at once (found[i] = intersect(rays[i], hits[i]); hits of
    /// misses are left as they were), traced as one Embree packet, coherent or not as in
    /// occludedPacket(): camera rays of neighbouring pixels share most of their traversal. Same hits
    /// as intersect() up to the edge cases of two watertight ray tests.
    void intersectPacket(const Ray* rays, int count, Hit* hits, bool* found) const;
    /// Embree's 16-wide ray layout of `rays` (count ≤ kPacket) and its lane mask. Lanes past `count`
    /// repeat ray 0 but are masked off (valid = 0) and empty (tnear > tfar), so Embree never reads
    /// garbage, also where it splits the packet for narrower kernels and reads only the interval.
    static void packRays(const Ray* rays, int count, RTCRay16& r, int* valid);
    /// Embree's traversal flag for a packet: coherent when all rays leave from one point (camera
    /// rays, the shadow rays of one receiver), where the packet shares its traversal; incoherent
    /// otherwise (bounce rays, shadow rays of many points), where Embree's incoherent packet
    /// traversal is the faster one (bench/bench_render.cpp).
    static RTCIntersectContextFlags packetFlags(const Ray* rays, int count);
    /// The Hit of lane `lane` of a packet that rtcIntersect16 traced against handle(), as intersect()
    /// fills it for the lane's ray; false when the lane missed.
    bool hitOfPacket(const RTCRayHit16& rh, int lane, Hit& hit) const;

    /// Ray offset scale for self-intersection avoidance: a hit point p is moved by
    /// offset(p) along the normal. Relative to both the point's magnitude and the scene's size so
    /// that scenes from 1e-3 to 1e4 units neither self-shadow (acne) nor leak.
    float offset(const Vec3& p) const {
        const float m = std::max(std::fabs(p.x), std::max(std::fabs(p.y), std::fabs(p.z)));
        return 2e-5f * (m + sceneScale_);
    }
    /// Origin for a ray leaving a surface at p with geometric normal ng towards direction dir.
    Vec3 spawnOrigin(const Vec3& p, const Vec3& ng, const Vec3& dir) const {
        const float e = offset(p);
        return dot(dir, ng) >= 0.f ? p + ng * e : p - ng * e;
    }

    /// The geometries as flat tables indexed by Embree's geomID, for code that resolves the hits of
    /// many rays at once (render/path_lanes.h): the Scene object or light each one is (-1 for
    /// neither) and where its primitives' unit geometric normals start in `normals` (x, y, z per
    /// primitive), -1 for spheres and meshes with vertex normals, whose hits need fillHit()'s own work.
    struct GeometryTable {
        std::vector<int> object, light, normalBase;
        std::vector<float> normals;
    };
    const GeometryTable& geometryTable() const { return table_; }
    /// The scene's size that offset() adds to a point's magnitude.
    float sceneScale() const { return sceneScale_; }
    RTCScene handle() const { return scene_; }
    RTCDevice device() const { return device_; }

private:
    struct GeomInfo {
        int object = -1;
        int light = -1;
        bool sphere = false;
        Vec3 center;                 ///< sphere
        std::vector<Vec3> normals;   ///< per primitive (quads, triangles)
        const Object* smooth = nullptr;  ///< triangles with vertex normals (Object::normals)
    };
    void addMesh(const std::vector<Vec3>& positions, const std::vector<uint32_t>& indices, bool quads,
                 GeomInfo info);
    /// Hit's ns for a hit at barycentrics (u, v) of triangle `prim` of `g` (Embree's convention).
    static Vec3 shadingNormal(const GeomInfo& g, uint32_t prim, float u, float v, const Vec3& ng);
    /// The Hit of `ray` from Embree's answer (t, ids, barycentrics, Embree's Ng for spheres).
    void fillHit(const Ray& ray, float t, unsigned geomID, unsigned primID, float u, float v, const Vec3& embreeNg,
                 Hit& hit) const;
    void addSphere(const Vec3& c, float r, GeomInfo info);

    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::vector<GeomInfo> geoms_;  ///< indexed by Embree geomID
    GeometryTable table_;          ///< geometryTable()
    float sceneScale_ = 1.f;
};

}  // namespace rrf
