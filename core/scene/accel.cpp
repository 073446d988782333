#include "core/scene/accel.h"

#include <stdexcept>
#include <string>

namespace rrf {

void Accel::packRays(const Ray* rays, int count, RTCRay16& r, int* valid) {
    for (int i = 0; i < 16; ++i) {
        const Ray& ray = rays[i < count ? i : 0];
        valid[i] = i < count ? -1 : 0;
        r.org_x[i] = ray.origin.x;
        r.org_y[i] = ray.origin.y;
        r.org_z[i] = ray.origin.z;
        r.dir_x[i] = ray.dir.x;
        r.dir_y[i] = ray.dir.y;
        r.dir_z[i] = ray.dir.z;
        // Lanes off get an empty interval too: without 16-wide kernels Embree splits the packet and
        // tells active rays by their interval, not by `valid`.
        r.tnear[i] = i < count ? ray.tmin : INFINITY;
        r.tfar[i] = i < count ? ray.tmax : -INFINITY;
        r.time[i] = 0.f;
        r.mask[i] = 0xFFFFFFFFu;
        r.id[i] = unsigned(i);
        r.flags[i] = 0;
    }
}

RTCIntersectContextFlags Accel::packetFlags(const Ray* rays, int count) {
    for (int i = 1; i < count; ++i)
        if (!(rays[i].origin == rays[0].origin)) return RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    return RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
}

namespace {

void embreeError(void*, RTCError code, const char* str) {
    // Errors are turned into exceptions where they are detected (rtcGetDeviceError after builds);
    // this callback only exists so Embree does not print to stderr behind the user's back.
    (void)code;
    (void)str;
}

void check(RTCDevice device, const char* what) {
    const RTCError e = rtcGetDeviceError(device);
    if (e != RTC_ERROR_NONE) throw std::runtime_error(std::string("Embree error during ") + what + " (code " + std::to_string(int(e)) + ")");
}
}  // namespace

Accel::Accel(const Scene& scene, const std::string& embreeConfig) {
    sceneScale_ = scene.scale();
    device_ = rtcNewDevice(("threads=0" + (embreeConfig.empty() ? std::string() : "," + embreeConfig)).c_str());
    if (!device_) throw std::runtime_error("Embree: cannot create device (code " + std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
    rtcSetDeviceErrorFunction(device_, embreeError, nullptr);
    scene_ = rtcNewScene(device_);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);

    for (const Object& o : scene.objects) {
        GeomInfo info;
        info.object = o.id;
        if (o.smooth()) info.smooth = &o;
        if (o.kind == Object::Kind::Sphere) addSphere(o.center, o.radius, info);
        else addMesh(o.positions, o.indices, o.kind == Object::Kind::Quads, std::move(info));
    }
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        // The movable light is intersected analytically by the path tracer, so that it can sit at a
        // different place for every path (training records) without rebuilding the BVH.
        if (!l.isArea() || int(i) == scene.movableLight) continue;
        GeomInfo info;
        info.light = int(i);
        Vec3 v[4];
        const int n = l.vertices(v);
        if (n == 4) addMesh({v[0], v[1], v[2], v[3]}, {0, 1, 2, 3}, true, std::move(info));
        else addMesh({v[0], v[1], v[2]}, {0, 1, 2}, false, std::move(info));
    }
    rtcCommitScene(scene_);
    check(device_, "BVH build");
    for (const GeomInfo& g : geoms_) {
        table_.object.push_back(g.object);
        table_.light.push_back(g.light);
        const bool flat = !g.sphere && !g.smooth;
        table_.normalBase.push_back(flat ? int(table_.normals.size() / 3) : -1);
        if (flat)
            for (const Vec3& n : g.normals) table_.normals.insert(table_.normals.end(), {n.x, n.y, n.z});
    }
}

Accel::~Accel() {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
}

void Accel::addMesh(const std::vector<Vec3>& positions, const std::vector<uint32_t>& indices, bool quads,
                    GeomInfo info) {
    const unsigned nv = quads ? 4 : 3;
    const size_t prims = indices.size() / nv;
    RTCGeometry g = rtcNewGeometry(device_, quads ? RTC_GEOMETRY_TYPE_QUAD : RTC_GEOMETRY_TYPE_TRIANGLE);
    // rtcSetNewGeometryBuffer pads the allocation so Embree's 16-byte SIMD loads stay in bounds.
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), positions.size()));
    for (size_t i = 0; i < positions.size(); ++i) {
        v[3 * i] = positions[i].x;
        v[3 * i + 1] = positions[i].y;
        v[3 * i + 2] = positions[i].z;
    }
    auto* idx = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, quads ? RTC_FORMAT_UINT4 : RTC_FORMAT_UINT3, nv * sizeof(uint32_t), prims));
    std::copy(indices.begin(), indices.begin() + long(prims * nv), idx);
    info.normals.resize(prims);
    for (size_t p = 0; p < prims; ++p) {
        const uint32_t* q = &indices[p * nv];
        Vec3 n = quads ? cross(positions[q[2]] - positions[q[0]], positions[q[3]] - positions[q[1]])
                       : cross(positions[q[1]] - positions[q[0]], positions[q[2]] - positions[q[0]]);
        const float len = length(n);
        info.normals[p] = len > 0.f ? n / len : Vec3(0, 0, 1);
    }
    rtcCommitGeometry(g);
    const unsigned id = rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
    check(device_, "geometry creation");
    if (id != geoms_.size()) throw std::runtime_error("Embree returned an unexpected geometry id");
    geoms_.push_back(std::move(info));
}

void Accel::addSphere(const Vec3& c, float r, GeomInfo info) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
    v[0] = c.x;
    v[1] = c.y;
    v[2] = c.z;
    v[3] = r;
    rtcCommitGeometry(g);
    const unsigned id = rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
    check(device_, "sphere creation");
    if (id != geoms_.size()) throw std::runtime_error("Embree returned an unexpected geometry id");
    info.sphere = true;
    info.center = c;
    geoms_.push_back(std::move(info));
}

bool Accel::intersect(const Ray& ray, Hit& hit) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    rh.ray.org_x = ray.origin.x;
    rh.ray.org_y = ray.origin.y;
    rh.ray.org_z = ray.origin.z;
    rh.ray.dir_x = ray.dir.x;
    rh.ray.dir_y = ray.dir.y;
    rh.ray.dir_z = ray.dir.z;
    rh.ray.tnear = ray.tmin;
    rh.ray.tfar = ray.tmax;
    rh.ray.time = 0.f;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    fillHit(ray, rh.ray.tfar, rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v,
            Vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z), hit);
    return true;
}

void Accel::fillHit(const Ray& ray, float t, unsigned geomID, unsigned primID, float u, float v, const Vec3& embreeNg,
                    Hit& hit) const {
    const GeomInfo& g = geoms_[geomID];
    hit.t = t;
    hit.p = ray.origin + ray.dir * t;
    hit.object = g.object;
    hit.light = g.light;
    hit.prim = primID;
    if (g.sphere) {
        // Embree's Ng for spheres is (p − c) unnormalised; normalise our own for precision.
        const float len = length(embreeNg);
        hit.ng = len > 0.f ? embreeNg / len : normalize(hit.p - g.center);
    } else {
        hit.ng = g.normals[primID];
    }
    hit.ns = g.smooth ? shadingNormal(g, primID, u, v, hit.ng) : Vec3(0.f);
}

void Accel::intersectPacket(const Ray* rays, int count, Hit* hits, bool* found) const {
    if (count <= 0) return;
    if (count > kPacket) throw std::invalid_argument("Accel::intersectPacket: more than 16 rays");
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = packetFlags(rays, count);
    alignas(64) RTCRayHit16 rh;
    alignas(64) int valid[kPacket];
    packRays(rays, count, rh.ray, valid);
    for (int i = 0; i < kPacket; ++i) {
        rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(valid, scene_, &ctx, &rh);
    for (int i = 0; i < count; ++i) {
        found[i] = rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
        if (found[i])
            fillHit(rays[i], rh.ray.tfar[i], rh.hit.geomID[i], rh.hit.primID[i], rh.hit.u[i], rh.hit.v[i],
                    Vec3(rh.hit.Ng_x[i], rh.hit.Ng_y[i], rh.hit.Ng_z[i]), hits[i]);
    }
}

bool Accel::hitOfPacket(const RTCRayHit16& rh, int lane, Hit& hit) const {
    const size_t i = size_t(lane);
    if (rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) return false;
    Ray ray;
    ray.origin = Vec3(rh.ray.org_x[i], rh.ray.org_y[i], rh.ray.org_z[i]);
    ray.dir = Vec3(rh.ray.dir_x[i], rh.ray.dir_y[i], rh.ray.dir_z[i]);
    fillHit(ray, rh.ray.tfar[i], rh.hit.geomID[i], rh.hit.primID[i], rh.hit.u[i], rh.hit.v[i],
            Vec3(rh.hit.Ng_x[i], rh.hit.Ng_y[i], rh.hit.Ng_z[i]), hit);
    return true;
}

Vec3 Accel::shadingNormal(const GeomInfo& g, uint32_t prim, float u, float v, const Vec3& ng) {
    const Object& o = *g.smooth;
    const uint32_t* t = &o.indices[size_t(prim) * 3];
    // Embree's barycentrics: p = (1−u−v)·v0 + u·v1 + v·v2.
    const Vec3 n = o.normals[t[0]] * (1.f - u - v) + o.normals[t[1]] * u + o.normals[t[2]] * v;
    const float len = length(n);
    if (!(len > 0.f)) return ng;
    // Vertex normals that disagree with the winding are turned to ng's side: the winding decides
    // which side is the front everywhere else (one-sided emitters, ray offsets).
    return dot(n, ng) < 0.f ? -n / len : n / len;
}

bool Accel::occluded(const Ray& ray) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r;
    r.org_x = ray.origin.x;
    r.org_y = ray.origin.y;
    r.org_z = ray.origin.z;
    r.dir_x = ray.dir.x;
    r.dir_y = ray.dir.y;
    r.dir_z = ray.dir.z;
    r.tnear = ray.tmin;
    r.tfar = ray.tmax;
    r.time = 0.f;
    r.mask = 0xFFFFFFFFu;
    r.id = 0;
    r.flags = 0;
    rtcOccluded1(scene_, &ctx, &r);
    return r.tfar < 0.f;  // Embree sets tfar = -inf on a hit
}

void Accel::occludedPacket(const Ray* rays, int count, bool* blocked) const {
    if (count <= 0) return;
    if (count > kPacket) throw std::invalid_argument("Accel::occludedPacket: more than 16 rays");
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = packetFlags(rays, count);
    alignas(64) RTCRay16 r;
    alignas(64) int valid[kPacket];
    packRays(rays, count, r, valid);
    rtcOccluded16(valid, scene_, &ctx, &r);
    for (int i = 0; i < count; ++i) blocked[i] = r.tfar[i] < 0.f;  // Embree sets tfar = -inf on a hit
}

}  // namespace rrf
