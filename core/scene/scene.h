#pragma once
/// In-memory scene: camera, materials, world-space geometry grouped into objects, lights and the
/// light region. Produced by `loadScene` (scene_json.cpp) from a JSON file; consumed by the Embree
/// accelerator, the path tracer and the data generator. All geometry is already transformed to
/// world space; objects keep a stable id (their index) and a user-visible name.

#include <cstdint>
#include <string>
#include <vector>

#include "core/util/vec3.h"

namespace rrf {

/// Largest image width or height, one definition for the scene's camera, the project's "render" and
/// "reference" sections, the CLI's --width/--height and the workbench. Whether a size within it fits
/// is decided by the memory it needs (requireRenderMemory, core/render/render_settings.h).
constexpr int kMaxImageSide = 16384;

/// Pinhole camera. Image x grows to the camera's right, image y downwards.
struct Camera {
    Vec3 eye{0, 0, 1};
    Vec3 target{0, 0, 0};
    Vec3 up{0, 1, 0};
    float fovYDegrees = 40.f;  ///< vertical field of view
    int width = 256;
    int height = 256;
};

/// Surface material. Lambert is a Phong material with ks = 0 (`f = kd/π`); Phong is the modified
/// (energy-conserving) Phong `f = kd/π + ks (n+2)/(2π) cos^n α`, α between the mirror direction
/// of ωo and ωi. The loader enforces kd + ks ≤ 1 per channel.
struct Material {
    enum class Type { Lambert, Phong };
    Type type = Type::Lambert;
    std::string name;
    Vec3 kd{0.5f};
    Vec3 ks{0.f};
    float exponent = 1.f;  ///< Phong exponent n ≥ 0 (only for Phong)
};

/// One user-visible object: a set of primitives of one kind sharing one material.
struct Object {
    enum class Kind { Quads, Triangles, Sphere };
    Kind kind = Kind::Triangles;
    std::string name;
    int id = 0;        ///< stable object id (= index in Scene::objects)
    int material = 0;  ///< index into Scene::materials
    /// Quads: 4 indices per primitive (planar, v0 v1 v2 v3 in order around the boundary).
    /// Triangles: 3 indices per primitive. Sphere: empty.
    std::vector<Vec3> positions;
    std::vector<uint32_t> indices;
    /// Per-vertex shading normals (unit, parallel to `positions`), from an OBJ file's `vn`; empty =
    /// flat shading with the geometric normal. Triangles only.
    std::vector<Vec3> normals;
    /// Shaded with interpolated vertex normals: triangles with one normal per position. The path
    /// tracer (Accel) and the GLSL G-buffer both ask this, so they agree on which meshes are smooth.
    bool smooth() const { return kind == Kind::Triangles && !normals.empty() && normals.size() == positions.size(); }
    Vec3 center{0.f};   ///< sphere only
    float radius = 0.f; ///< sphere only
    /// True when the loader knows the surface is closed (box, sphere, or "closed": true in JSON).
    bool closed = false;

    int verticesPerPrimitive() const { return kind == Kind::Quads ? 4 : 3; }
    size_t primitiveCount() const {
        return kind == Kind::Sphere ? 1 : indices.size() / size_t(verticesPerPrimitive());
    }
    Bounds3 bounds() const;
};

/// Light source. A rect light is the parallelogram corner + s·edge1 + t·edge2 (s, t ∈ [0,1]); a
/// triangle light is the triangle corner + s·edge1 + t·edge2 (s, t ≥ 0, s + t ≤ 1), as an OBJ
/// file's emitting faces give them. Both are area lights with normal normalize(edge1 × edge2);
/// one-sided lights emit only on the normal's side. An area light is also visible geometry (hit by
/// camera and BRDF rays, black BSDF). A point light emits `intensity` (W/sr) uniformly in all
/// directions.
struct Light {
    enum class Type { Rect, Point, Triangle };
    Type type = Type::Rect;
    std::string name;
    Vec3 corner{0.f}, edge1{1, 0, 0}, edge2{0, 0, 1};  ///< rect and triangle
    Vec3 radiance{1.f};                                 ///< area lights: emitted radiance
    bool oneSided = true;                               ///< area lights
    Vec3 position{0.f};                                 ///< point
    Vec3 intensity{1.f};                                ///< point
    /// Material of the emitting surface (area lights only): -1 = black (the usual case, as in
    /// Mitsuba's Cornell box). A reflective emitter makes furnace scenes possible (walls that emit
    /// and reflect).
    int material = -1;

    bool isArea() const { return type != Type::Point; }
    Vec3 normal() const { return normalize(cross(edge1, edge2)); }
    /// Radiance the surface of an area light sends towards `w` (unit, pointing away from it): zero
    /// from behind a one-sided light, and zero for point lights, which no ray can hit. The path
    /// tracer and the G-buffer both use this, so prediction and ground truth agree on emitters.
    Vec3 emittedTowards(const Vec3& w) const {
        if (!isArea() || (oneSided && dot(w, cross(edge1, edge2)) <= 0.f)) return Vec3(0.f);
        return radiance;
    }
    float area() const {
        const float a = length(cross(edge1, edge2));
        return type == Type::Triangle ? 0.5f * a : a;
    }
    /// The point of an area light at (u, v) ∈ [0,1)²: uniform (u, v) give points uniform by area,
    /// pdf 1/area(). A triangle folds the square's upper half onto its lower one (u+v > 1 →
    /// 1−u, 1−v), which keeps the map measure-preserving and stratified samples stratified.
    Vec3 pointAt(float u, float v) const {
        if (type == Type::Triangle && u + v > 1.f) {
            u = 1.f - u;
            v = 1.f - v;
        }
        return corner + edge1 * u + edge2 * v;
    }
    /// Corners of an area light in boundary order (3 for a triangle, 4 for a rect); returns the count.
    int vertices(Vec3 out[4]) const {
        out[0] = corner;
        out[1] = corner + edge1;
        if (type == Type::Triangle) {
            out[2] = corner + edge2;
            return 3;
        }
        out[2] = corner + edge1 + edge2;
        out[3] = corner + edge2;
        return 4;
    }
    /// Reference position of the light: the rect's centre, the triangle's centroid or the point's
    /// position. This is the "light position" input of the networks.
    Vec3 center() const { return isArea() ? corner + centerOffset() : position; }
    /// Moves the light so that center() == p, keeping shape, orientation and emission.
    void moveTo(const Vec3& p) {
        if (isArea()) corner = p - centerOffset();
        else position = p;
    }

private:
    Vec3 centerOffset() const { return (edge1 + edge2) * (type == Type::Triangle ? 1.f / 3.f : 0.5f); }
};

struct Scene {
    std::string sourcePath;  ///< file the scene came from (for messages); empty if built in code
    Camera camera;
    std::vector<Material> materials;
    std::vector<Object> objects;
    std::vector<Light> lights;
    /// Index into `lights` of the light that moves for training and interactive re-lighting.
    int movableLight = 0;
    /// Box in which the movable light's centre may be placed (training data, GUI slider range).
    /// Empty box = the light does not move.
    Bounds3 lightRegion;
    /// Non-fatal findings of the loader (e.g. degenerate triangles dropped from an OBJ file).
    std::vector<std::string> warnings;

    /// Bounds of all objects and area lights.
    Bounds3 bounds() const;
    /// Length of the bounds' diagonal; sets the scale of ray offsets.
    float scale() const;
    /// Position of the movable light (its centre), or (0,0,0) if there is no light.
    Vec3 lightPosition() const;
    /// Moves the movable light to `p` (its centre), keeping shape and emission.
    void setLightPosition(const Vec3& p);
    /// Where the movable light's centre may be: the light region, or just the light's current
    /// position when the region is empty (a fixed light).
    Bounds3 lightRange() const;
    /// Hash of everything that changes the rendered radiance (geometry, materials, lights, the
    /// light region; not the camera or the source path). Datasets and models record it.
    uint64_t contentHash() const;
};

}  // namespace rrf
