#include "core/scene/scene_json.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <optional>
#include <sstream>

#include "core/util/error.h"
#include "core/util/json_reader.h"
#include "core/scene/coordinate_range.h"
#include "core/scene/light_region.h"
#include "core/scene/obj_loader.h"
#include "core/scene/radiometric_range.h"
#include "core/scene/scene_builder.h"
#include "core/scene/scene_parse.h"
#include "core/scene/transform.h"

namespace rrf {

namespace {

const char* const kChannel[3] = {"red", "green", "blue"};

struct DVec {
    double x, y, z;
    explicit DVec(const Vec3& v) : x(v.x), y(v.y), z(v.z) {}
    DVec(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
    DVec operator-(const DVec& o) const { return {x - o.x, y - o.y, z - o.z}; }
    DVec operator+(const DVec& o) const { return {x + o.x, y + o.y, z + o.z}; }
    DVec operator*(double s) const { return {x * s, y * s, z * s}; }
    double dot(const DVec& o) const { return x * o.x + y * o.y + z * o.z; }
    DVec cross(const DVec& o) const { return {y * o.z - z * o.y, z * o.x - x * o.z, x * o.y - y * o.x}; }
    double norm() const { return std::sqrt(dot(*this)); }
};

/// Components finite (the reader guarantees it) and non-negative; names the channel otherwise.
Vec3 nonNegativeColor(const JsonReader& r, const std::string& what) {
    const Vec3 c = r.vec3();
    for (int i = 0; i < 3; ++i)
        if (c[i] < 0)
            r.fail(what + " must be >= 0, but its " + kChannel[i] + " component is " + formatNumber(c[i]));
    return c;
}

Camera parseCamera(const JsonReader& r) {
    r.checkKeys({"eye", "target", "up", "fov_y", "width", "height"});
    Camera cam;
    cam.eye = r.at("eye").vec3();
    cam.target = r.at("target").vec3();
    for (const char* key : {"eye", "target"})
        if (const std::string why = coordinateRangeProblem(key[0] == 'e' ? cam.eye : cam.target); !why.empty())
            r.at(key).fail("camera " + std::string(key) + ": " + why);
    cam.up = r.vec3Or("up", Vec3(0, 1, 0));
    const DVec dir = DVec(cam.target) - DVec(cam.eye);
    if (!(dir.norm() > 0)) r.at("target").fail("camera target must differ from the eye");
    const DVec up(cam.up);
    if (!(up.norm() > 0) || dir.cross(up).norm() <= 1e-6 * dir.norm() * up.norm())
        r.at("up").fail("camera up vector must be non-zero and not parallel to the viewing direction");
    const JsonReader fov = r.at("fov_y");
    cam.fovYDegrees = fov.floatValue();
    if (!(cam.fovYDegrees > 0 && cam.fovYDegrees < 180)) fov.fail("fov_y must be in (0, 180) degrees");
    cam.width = int(r.integerOr("width", 256, 1, kMaxImageSide));
    cam.height = int(r.integerOr("height", 256, 1, kMaxImageSide));
    return cam;
}

Material parseMaterial(const JsonReader& r, const std::string& name) {
    if (name.empty()) r.fail("material names must not be empty");
    r.requireObject();
    const std::string type = r.at("type").string();
    Material m;
    m.name = name;
    if (type == "lambert") {
        r.checkKeys({"type", "albedo"});
        m.type = Material::Type::Lambert;
        m.kd = nonNegativeColor(r.at("albedo"), "albedo");
        m.ks = Vec3(0.f);
    } else if (type == "phong") {
        r.checkKeys({"type", "kd", "ks", "exponent"});
        m.type = Material::Type::Phong;
        m.kd = nonNegativeColor(r.at("kd"), "kd");
        m.ks = nonNegativeColor(r.at("ks"), "ks");
        const JsonReader e = r.at("exponent");
        m.exponent = e.floatValue();
        if (const std::string why = exponentProblem(m.exponent, "exponent"); !why.empty()) e.fail(why);
    } else {
        r.at("type").fail("unknown material type '" + type + "' (known: lambert, phong)");
    }
    for (int i = 0; i < 3; ++i) {
        const double sum = double(m.kd[i]) + double(m.ks[i]);
        if (sum > 1 + kEnergySlack)
            r.fail(std::string(m.type == Material::Type::Lambert ? "albedo" : "kd + ks") + " = " +
                   formatNumber(sum) + " > 1 in the " + kChannel[i] +
                   " channel (energy conservation requires kd + ks <= 1 per channel)");
    }
    return m;
}

/// Parallelogram corner + s*edge1 + t*edge2 as a quad with corners in boundary order.
void parallelogram(const JsonReader& r, Object& o) {
    const Vec3 c = r.at("corner").vec3(), e1 = r.at("edge1").vec3(), e2 = r.at("edge2").vec3();
    const double area = DVec(e1).cross(DVec(e2)).norm();
    const double size = std::max(DVec(e1).dot(DVec(e1)), DVec(e2).dot(DVec(e2)));
    if (!(area > kDegenerateArea * size))
        r.fail("degenerate quad: zero area (edge1 and edge2 are zero or parallel)");
    o.positions = {c, c + e1, c + e1 + e2, c + e2};
}

/// General planar convex quad from 4 points in boundary order; snapped exactly onto its plane.
void pointQuad(const JsonReader& r, Object& o) {
    const JsonReader pts = r.at("points");
    if (pts.requireArray() != 4) pts.fail("expected array of 4 points, got " + JsonReader::describe(pts.value()));
    std::vector<DVec> p;
    for (size_t i = 0; i < 4; ++i) p.push_back(DVec(pts.at(i).vec3()));
    // Newell's normal is robust for slightly non-planar polygons; its length is twice the area.
    DVec n(0, 0, 0);
    for (size_t i = 0; i < 4; ++i) n = n + p[i].cross(p[(i + 1) % 4]);
    const double diag = std::max((p[2] - p[0]).norm(), (p[3] - p[1]).norm());
    const double twiceArea = n.norm();
    if (!(twiceArea > 2 * kDegenerateArea * diag * diag))
        pts.fail("degenerate quad: zero area (or the points are not in boundary order)");
    n = n * (1 / twiceArea);
    const DVec centroid = (p[0] + p[1] + p[2] + p[3]) * 0.25;
    for (size_t i = 0; i < 4; ++i) {
        const double d = std::fabs((p[i] - centroid).dot(n));
        if (d > kPlanarity * diag)
            pts.fail("quad is not planar: point " + std::to_string(i) + " is " + formatNumber(d) +
                     " away from the quad's plane (tolerance " + formatNumber(kPlanarity * diag) + ")");
    }
    for (size_t i = 0; i < 4; ++i) {
        const DVec a = p[(i + 1) % 4] - p[i], b = p[(i + 2) % 4] - p[(i + 1) % 4];
        if (a.cross(b).dot(n) < -kDegenerateArea * diag * diag)
            pts.fail("quad is not convex (or its points are not in order around the boundary) at point " +
                     std::to_string((i + 1) % 4));
    }
    for (const DVec& q : p) {
        const DVec s = q - n * (q - centroid).dot(n);
        o.positions.push_back(Vec3(float(s.x), float(s.y), float(s.z)));
    }
}

void inlineTriangles(const JsonReader& r, Object& o) {
    const JsonReader pos = r.at("positions");
    const size_t n = pos.requireArray();
    if (n < 3) pos.fail("a triangle mesh needs at least 3 positions, got " + std::to_string(n));
    for (size_t i = 0; i < n; ++i) o.positions.push_back(pos.at(i).vec3());
    const JsonReader idx = r.at("indices");
    const size_t m = idx.requireArray();
    if (m == 0) idx.fail("a triangle mesh needs at least one triangle");
    for (size_t t = 0; t < m; ++t) {
        const JsonReader tri = idx.at(t);
        if (!tri.isArray() || tri.value().size() != 3)
            tri.fail("expected array of 3 vertex indices, got " + JsonReader::describe(tri.value()));
        for (size_t k = 0; k < 3; ++k) {
            const JsonReader e = tri.at(k);
            const int64_t v = e.integer(std::numeric_limits<int64_t>::min(), std::numeric_limits<int64_t>::max());
            if (v < 0 || uint64_t(v) >= n)
                e.fail("vertex index " + std::to_string(v) + " out of range: 'positions' has " + std::to_string(n) +
                       " entries (valid 0.." + std::to_string(n - 1) + ")");
            o.indices.push_back(uint32_t(v));
        }
    }
}

void unitBox(Object& o) {
    for (int i = 0; i < 8; ++i) o.positions.push_back(Vec3(i & 1 ? 0.5f : -0.5f, i & 2 ? 0.5f : -0.5f, i & 4 ? 0.5f : -0.5f));
    // Faces -x, +x, -y, +y, -z, +z, each counter-clockwise seen from outside (outward normals).
    o.indices = {0, 4, 6, 2, 1, 3, 7, 5, 0, 1, 5, 4, 2, 6, 7, 3, 0, 2, 3, 1, 4, 5, 7, 6};
}

struct SceneBuilder : SceneBuildState {

    int lookupMaterial(const JsonReader& r) const {
        const std::string name = r.string();
        const auto it = materialIndex.find(name);
        if (it != materialIndex.end()) return it->second;
        std::string known;
        for (const auto& kv : materialIndex) known += (known.empty() ? "" : ", ") + kv.first;
        r.fail("unknown material '" + name + "' (known: " + (known.empty() ? "none" : known) + ")");
    }

    Object shape(const JsonReader& r, size_t index) {
        r.requireObject();
        const std::string type = r.at("type").string();
        Object o;
        o.id = int(index);
        o.name = r.stringOr("name", type + "-" + std::to_string(index));
        if (o.name.empty()) r.at("name").fail("object names must not be empty");
        if (type == "quad") {
            if (r.has("points")) {
                r.checkKeys({"type", "name", "material", "closed", "points"});
                pointQuad(r, o);
            } else {
                r.checkKeys({"type", "name", "material", "closed", "corner", "edge1", "edge2"});
                parallelogram(r, o);
            }
            o.kind = Object::Kind::Quads;
            o.indices = {0, 1, 2, 3};
            o.closed = r.booleanOr("closed", false);
        } else if (type == "triangles") {
            r.checkKeys({"type", "name", "material", "closed", "positions", "indices", "transform"});
            o.kind = Object::Kind::Triangles;
            inlineTriangles(r, o);
        } else if (type == "obj") {
            // With a "material" the OBJ is one object of that material (its MTL is not read);
            // without one, objFile() below makes objects, materials and lights from the OBJ + MTL.
            r.checkKeys({"type", "name", "material", "closed", "file", "transform"});
            o.kind = Object::Kind::Triangles;
            const JsonReader file = r.at("file");
            ObjFile obj = loadObjFile(resolvePath(baseDir, file.string()), file.file(), file.pointer(), ObjSplit::Groups, false);
            for (const ObjPart& part : obj.parts) {
                const uint32_t base = uint32_t(o.positions.size());
                o.positions.insert(o.positions.end(), part.positions.begin(), part.positions.end());
                std::vector<uint32_t> tris;
                for (size_t f = 0, first = 0; f < part.faceSizes.size(); first += part.faceSizes[f++])
                    fanTriangulate(part.indices, first, part.faceSizes[f], tris);
                for (uint32_t i : tris) o.indices.push_back(base + i);
            }
            for (std::string& w : obj.warnings) scene.warnings.push_back(std::move(w));
        } else if (type == "sphere") {
            r.checkKeys({"type", "name", "material", "center", "radius"});
            o.kind = Object::Kind::Sphere;
            o.center = r.at("center").vec3();
            const JsonReader rad = r.at("radius");
            o.radius = rad.floatValue();
            if (!(o.radius > 0)) rad.fail("sphere radius must be > 0, got " + formatNumber(o.radius));
            o.closed = true;
        } else if (type == "box") {
            r.checkKeys({"type", "name", "material", "transform"});
            o.kind = Object::Kind::Quads;
            unitBox(o);
            o.closed = true;
        } else {
            r.at("type").fail("unknown shape type '" + type + "' (known: quad, triangles, obj, sphere, box)");
        }
        if (auto t = r.find("transform")) applyTransform(parseTransform(*t), o);
        for (const Vec3& p : o.positions)
            if (const std::string why = coordinateRangeProblem(p); !why.empty())
                r.fail("shape '" + o.name + "' has a point outside the scene's coordinate range after its transform: " + why);
        if (o.kind == Object::Kind::Sphere)
            for (int i = 0; i < 3; ++i) {
                // In double: centre ± radius may overflow float (radius 3e38).
                const double far = std::fabs(double(o.center[i])) + double(o.radius);
                if (far > double(kMaxCoordinate))
                    r.fail("sphere '" + o.name + "' reaches |" + "xyz"[i] + "| = " + formatNumber(far) +
                           ", outside [-" + formatNumber(kMaxCoordinate) + ", " + formatNumber(kMaxCoordinate) +
                           "], the coordinate range in which rays stay valid");
            }
        if (type == "box") {
            // A near-zero scale factor flattens faces just like a degenerate declared quad.
            for (size_t q = 0; q < 6; ++q) {
                const DVec v0(o.positions[o.indices[4 * q]]), v1(o.positions[o.indices[4 * q + 1]]),
                    v3(o.positions[o.indices[4 * q + 3]]);
                const DVec e1 = v1 - v0, e2 = v3 - v0;
                if (!(e1.cross(e2).norm() > kDegenerateArea * std::max(e1.dot(e1), e2.dot(e2))))
                    r.at("transform").fail("the transform flattens the box (a face has zero area)");
            }
        }
        if (o.kind == Object::Kind::Triangles) {
            o.closed = r.booleanOr("closed", false);
            dropDegenerateTriangles(r, o, scene.warnings);
        }
        o.material = lookupMaterial(r.at("material"));
        claimObjectName(r, o.name);
        return o;
    }

    Light light(const JsonReader& r, size_t index) {
        r.requireObject();
        const std::string type = r.at("type").string();
        Light l;
        l.name = r.stringOr("name", "light-" + std::to_string(index));
        if (type == "rect") {
            r.checkKeys({"type", "name", "corner", "edge1", "edge2", "radiance", "one_sided", "movable", "material"});
            l.type = Light::Type::Rect;
            l.corner = r.at("corner").vec3();
            l.edge1 = r.at("edge1").vec3();
            l.edge2 = r.at("edge2").vec3();
            const double area = DVec(l.edge1).cross(DVec(l.edge2)).norm();
            const double size = std::max(DVec(l.edge1).dot(DVec(l.edge1)), DVec(l.edge2).dot(DVec(l.edge2)));
            if (!(area > kDegenerateArea * size) || !(area > 0))
                r.fail("rect light has zero area (edge1 and edge2 are zero or parallel)");
            if (const std::string why = lightSizeProblem(l.edge1, l.edge2); !why.empty()) r.fail("light '" + l.name + "': " + why);
            l.radiance = nonNegativeColor(r.at("radiance"), "radiance");
            if (const std::string why = emissionProblem(l.radiance, "radiance"); !why.empty())
                r.at("radiance").fail("light '" + l.name + "': " + why);
            l.oneSided = r.booleanOr("one_sided", true);
            // Emitters are black unless they name a material (reflective emitters, e.g. furnace tests).
            if (auto m = r.find("material")) l.material = lookupMaterial(*m);
        } else if (type == "point") {
            r.checkKeys({"type", "name", "position", "intensity", "movable"});
            l.type = Light::Type::Point;
            l.position = r.at("position").vec3();
            l.intensity = nonNegativeColor(r.at("intensity"), "intensity");
            if (const std::string why = emissionProblem(l.intensity, "intensity"); !why.empty())
                r.at("intensity").fail("light '" + l.name + "': " + why);
        } else {
            r.at("type").fail("unknown light type '" + type + "' (known: rect, point)");
        }
        if (const std::string why = lightPlacementProblem(l, l.center()); !why.empty()) r.fail(why);
        return l;
    }

    void lightRegion(const JsonReader& r) {
        r.checkKeys({"min", "max"});
        const Vec3 lo = r.at("min").vec3(), hi = r.at("max").vec3();
        for (int i = 0; i < 3; ++i)
            if (lo[i] > hi[i])
                r.fail(std::string("min > max on the ") + "xyz"[i] + " axis (" + formatNumber(lo[i]) + " > " +
                       formatNumber(hi[i]) + ")");
        if (scene.lights.empty()) r.fail("a light_region needs a light to move, but the scene has no lights");
        scene.lightRegion.lo = lo;
        scene.lightRegion.hi = hi;
        // The light moves anywhere in the region; its extremes are at the region's corners lo and hi.
        const Light& movable = scene.lights[size_t(scene.movableLight)];
        for (const Vec3& c : {lo, hi})
            if (const std::string why = lightPlacementProblem(movable, c); !why.empty())
                r.fail("the light moved to the region's corner: " + why);
        // Tolerance: the centre is computed in float from corner + edges.
        const Vec3 c = scene.lightPosition();
        const float tol = 1e-5f * std::max(1.f, scene.scale());
        Bounds3 grown = scene.lightRegion;
        grown.lo -= Vec3(tol);
        grown.hi += Vec3(tol);
        if (!grown.contains(c)) {
            std::ostringstream msg;
            msg << "the light region must contain the movable light's current centre " << c << " (light '"
                << scene.lights[size_t(scene.movableLight)].name << "')";
            r.fail(msg.str());
        }
    }
};

}  // namespace

void SceneBuildState::claimObjectName(const JsonReader& r, const std::string& name) {
    const auto [it, fresh] = objectNames.emplace(name, r.pointer());
    if (!fresh) r.fail("duplicate object name '" + name + "' (first used at " + it->second + ")");
}

void applyTransform(const Transform& t, Object& o) {
    for (Vec3& p : o.positions) p = t.apply(p);
    if (!o.normals.empty()) {
        // Normals map with the inverse transpose, so they stay perpendicular to the surface.
        const Eigen::Matrix3d m = t.linear.inverse().transpose();
        for (Vec3& n : o.normals) {
            const Eigen::Vector3d q = m * Eigen::Vector3d(n.x, n.y, n.z);
            n = normalize(Vec3(float(q.x()), float(q.y()), float(q.z())));
        }
    }
    if (!t.flipsOrientation()) return;
    // A mirror turns counter-clockwise into clockwise; reverse each primitive to keep normals outward.
    const size_t k = size_t(o.verticesPerPrimitive());
    for (size_t i = 0; i + k <= o.indices.size(); i += k)
        std::reverse(o.indices.begin() + long(i + 1), o.indices.begin() + long(i + k));
}

void dropDegenerateTriangles(const JsonReader& r, Object& o, std::vector<std::string>& warnings) {
    std::vector<uint32_t> kept;
    kept.reserve(o.indices.size());
    size_t dropped = 0;
    for (size_t i = 0; i + 3 <= o.indices.size(); i += 3) {
        const DVec a(o.positions[o.indices[i]]), b(o.positions[o.indices[i + 1]]), c(o.positions[o.indices[i + 2]]);
        const DVec e0 = b - a, e1 = c - a, e2 = c - b;
        const double size = std::max({e0.dot(e0), e1.dot(e1), e2.dot(e2)});
        if (e0.cross(e1).norm() > kDegenerateArea * size) {
            kept.insert(kept.end(), o.indices.begin() + long(i), o.indices.begin() + long(i + 3));
        } else {
            ++dropped;
        }
    }
    if (kept.empty()) r.fail("mesh '" + o.name + "' has no triangles with non-zero area");
    if (dropped)
        warnings.push_back(r.file() + ": " + r.pointer() + ": dropped " + std::to_string(dropped) +
                           " zero-area triangle" + (dropped == 1 ? "" : "s") + " from '" + o.name + "'");
    o.indices = std::move(kept);
}

std::string directoryOf(const std::string& path) {
    return std::filesystem::path(path).parent_path().string();
}

std::string resolvePath(const std::string& baseDir, const std::string& ref) {
    const std::filesystem::path p(ref);
    if (p.is_absolute() || baseDir.empty()) return p.string();
    return (std::filesystem::path(baseDir) / p).string();
}

Scene parseSceneAt(const JsonReader& root, const std::string& baseDir) {
    root.checkKeys({"camera", "materials", "shapes", "lights", "light_region"});
    Scene scene;
    scene.sourcePath = root.file();
    SceneBuilder b{{scene, baseDir, {}, {}}};
    scene.camera = parseCamera(root.at("camera"));

    // "materials" may be left out when every shape takes its materials from an OBJ's MTL.
    if (auto mats = root.find("materials")) {
        mats->requireObject();
        for (auto it = mats->value().begin(); it != mats->value().end(); ++it) {
            b.materialIndex[it.key()] = int(scene.materials.size());
            scene.materials.push_back(parseMaterial(mats->at(it.key()), it.key()));
        }
    }

    const JsonReader shapes = root.at("shapes");
    const size_t shapeCount = shapes.requireArray();
    const bool objEmitters = !root.has("lights");
    std::vector<Light> objLights;
    for (size_t i = 0; i < shapeCount; ++i) {
        const JsonReader s = shapes.at(i);
        s.requireObject();
        if (s.has("type") && s.at("type").value().is_string() && s.at("type").string() == "obj" && !s.has("material")) {
            addObjFileShapes(b, s, objEmitters, objLights);
        } else {
            scene.objects.push_back(b.shape(s, i));
            scene.objects.back().id = int(scene.objects.size() - 1);
        }
    }
    if (!objLights.empty()) adoptObjLights(scene, std::move(objLights));

    if (auto lights = root.find("lights")) {
        const size_t n = lights->requireArray();
        std::map<std::string, std::string> names;
        int movable = -1;
        for (size_t i = 0; i < n; ++i) {
            const JsonReader r = lights->at(i);
            scene.lights.push_back(b.light(r, i));
            const auto [it, fresh] = names.emplace(scene.lights.back().name, r.pointer());
            if (!fresh) r.fail("duplicate light name '" + it->first + "' (first used at " + it->second + ")");
            if (r.booleanOr("movable", false)) {
                if (movable >= 0)
                    r.at("movable").fail("only one light can be movable, but " + JsonReader::child(lights->pointer(), size_t(movable)) +
                                         " is movable too");
                movable = int(i);
            }
        }
        scene.movableLight = std::max(movable, 0);
    }
    if (auto region = root.find("light_region")) b.lightRegion(*region);
    else if (!scene.lights.empty() && !root.has("lights")) scene.lightRegion = deriveLightRegion(scene, scene.movableLight);
    if (scene.lights.empty()) scene.warnings.push_back(root.file() + ": the scene has no lights (it renders black)");
    return scene;
}

Scene parseScene(const nlohmann::json& doc, const std::string& file, const std::string& baseDir) {
    return parseSceneAt(JsonReader(doc, file), baseDir);
}

Scene loadScene(const std::string& path) {
    const nlohmann::json doc = readJsonFile(path);
    return parseScene(doc, path, directoryOf(path));
}

}  // namespace rrf
