// GLSL prediction against the CPU: the G-buffer against the CPU's primary rays, and the shader's
// network outputs against NetworkModel::predict on exactly the inputs the G-buffer holds
// (issue 6: max relative difference ≤ 1e-4 on every covered pixel of the Cornell box).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <glad/gl.h>
#include <gtest/gtest.h>

#include "app/gl/glsl_predictor.h"
#include "core/scene/camera_rays.h"
#include "core/nn/object_training.h"
#include "core/render/path_tracer.h"
#include "core/predict/predictor.h"
#include "tests/gl/gl_test_env.h"
#include "tests/gl/test_models.h"

namespace rrf::test_glsl_predictor {
namespace {

using test::closeEnough;

struct GBufferComparison {
    size_t pixels = 0, idMismatches = 0, idMismatchesOffSilhouette = 0, compared = 0;
    double maxPositionError = 0, maxNormalError = 0;
};

/// G-buffer vs the CPU's pixel-centre primary rays (CameraRays jitter 0.5, PathTracer::intersect,
/// which includes the movable light). Ids must agree except at silhouettes (pixels whose CPU id differs
/// from a 4-neighbour's: there the rasteriser's and Embree's edge rules may pick different sides).
GBufferComparison compareGBuffer(const Scene& scene, const GlGBuffer& g) {
    const Accel accel(scene);
    const PathTracer tracer(scene, accel, Estimator::NEE);
    const CameraRays rays(scene.camera, g.width, g.height);
    std::vector<int> cpuId(g.pixelCount());
    std::vector<Hit> hits(g.pixelCount());
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
            Hit h;
            const size_t i = size_t(y) * size_t(g.width) + size_t(x);
            cpuId[i] = tracer.intersect(rays.generate(x, y, 0.5f, 0.5f), h)
                           ? (h.object >= 0 ? h.object : GlGBuffer::kLightPixel)
                           : GlGBuffer::kBackgroundPixel;
            hits[i] = h;
        }
    GBufferComparison c;
    c.pixels = g.pixelCount();
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
            const size_t i = size_t(y) * size_t(g.width) + size_t(x);
            if (cpuId[i] != g.objectId[i]) {
                ++c.idMismatches;
                bool silhouette = false;
                const int nb[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
                for (const auto& d : nb) {
                    const int nx = x + d[0], ny = y + d[1];
                    if (nx < 0 || ny < 0 || nx >= g.width || ny >= g.height) continue;
                    silhouette |= cpuId[size_t(ny) * size_t(g.width) + size_t(nx)] != cpuId[i];
                }
                if (!silhouette) ++c.idMismatchesOffSilhouette;
                continue;
            }
            if (cpuId[i] == GlGBuffer::kBackgroundPixel) continue;
            ++c.compared;
            const Hit& h = hits[i];
            const Vec3 p(g.position[3 * i], g.position[3 * i + 1], g.position[3 * i + 2]);
            c.maxPositionError = std::max(c.maxPositionError, double(length(p - h.p)));
            if (cpuId[i] >= 0) {
                const Vec3 wo = -rays.generate(x, y, 0.5f, 0.5f).dir;
                const Vec3 ns = h.shading();                    // vertex normals where the mesh has them
                const Vec3 n = dot(wo, ns) >= 0.f ? ns : -ns;  // core/predict/gbuffer.cpp's convention
                const Vec3 gn(g.normal[3 * i], g.normal[3 * i + 1], g.normal[3 * i + 2]);
                c.maxNormalError = std::max(c.maxNormalError, double(length(gn - n)));
            }
        }
    return c;
}

struct PredictionComparison {
    size_t covered = 0, objectPixels = 0, lightPixels = 0, failures = 0;
    double maxRelative = 0;  ///< max |gl − cpu| / max(|cpu|, 1e-2) over all channels and terms
    /// The same measure for the CPU's float prediction against its double prediction: the float
    /// noise floor of these networks, which no float implementation can beat.
    double floatVsDouble = 0;
    double glVsDouble = 0;
    std::string firstFailure;
};

/// Feeds exactly the G-buffer's inputs to NetworkModel::predict and compares every covered pixel.
PredictionComparison comparePrediction(const Scene& scene, const ModelSet& set, const GlslPredictor& gp) {
    const GlGBuffer g = gp.readGBuffer();
    const Image gl[3] = {gp.read(Term::Direct), gp.read(Term::Indirect),
                         gp.read(Term::Global)};
    const RecordLayout layout = RecordLayout::forScene(scene);
    const Vec3 eye = scene.camera.eye, light = gp.lightPosition();
    PredictionComparison r;
    auto check = [&](int term, int x, int y, const Vec3& cpu) {
        const Vec3 v = gl[term].at(x, y);
        for (int ch = 0; ch < 3; ++ch) {
            const double rel = std::fabs(double(v[ch]) - double(cpu[ch])) / std::max(std::fabs(double(cpu[ch])), 1e-2);
            r.maxRelative = std::max(r.maxRelative, rel);
            if (!closeEnough(v[ch], cpu[ch])) {
                if (r.failures++ == 0) {
                    char b[256];
                    std::snprintf(b, sizeof b, "pixel (%d,%d) %s channel %d: GLSL %.9g CPU %.9g", x, y,
                                  termName(Term(term)), ch, double(v[ch]), double(cpu[ch]));
                    r.firstFailure = b;
                }
            }
        }
    };
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
            const int id = g.objectId[size_t(y) * size_t(g.width) + size_t(x)];
            if (id == GlGBuffer::kBackgroundPixel) {
                for (int t = 0; t < 3; ++t) check(t, x, y, Vec3(0.f));
            } else if (id == GlGBuffer::kLightPixel) {
                ++r.covered;
                ++r.lightPixels;
                const Vec3 e = g.emission.at(x, y);
                check(0, x, y, e);
                check(1, x, y, Vec3(0.f));
                check(2, x, y, e);
            }
        }
    for (const ObjectNetworks& on : set.objects) {
        std::vector<std::pair<int, int>> px;
        for (int y = 0; y < g.height; ++y)
            for (int x = 0; x < g.width; ++x)
                if (g.objectId[size_t(y) * size_t(g.width) + size_t(x)] == on.objectId) px.emplace_back(x, y);
        if (px.empty()) continue;
        float brdf[8] = {};
        layout.brdfParameters(scene.materials[size_t(scene.objects[size_t(on.objectId)].material)], brdf);
        MatX<float> raw(layout.inputCount(), Eigen::Index(px.size()));
        for (size_t k = 0; k < px.size(); ++k) {
            const size_t i = size_t(px[k].second) * size_t(g.width) + size_t(px[k].first);
            const Vec3 p(g.position[3 * i], g.position[3 * i + 1], g.position[3 * i + 2]);
            const Vec3 n(g.normal[3 * i], g.normal[3 * i + 1], g.normal[3 * i + 2]);
            const Vec3 f[4] = {p, normalize(eye - p), light, n};
            for (int j = 0; j < 12; ++j) raw(j, Eigen::Index(k)) = f[j / 3][j % 3];
            for (int j = 12; j < layout.inputCount(); ++j) raw(j, Eigen::Index(k)) = brdf[j - 12];
        }
        const test::CpuTerms cpu = test::cpuTerms(on, raw);
        const MatX<double> rawD = raw.cast<double>();
        const test::CpuTermsT<double> exact = test::cpuTerms(on, rawD);
        const MatX<float>* terms[3] = {&cpu.direct, &cpu.indirect, &cpu.global};
        const MatX<double>* exactTerms[3] = {&exact.direct, &exact.indirect, &exact.global};
        for (size_t k = 0; k < px.size(); ++k)
            for (int t = 0; t < 3; ++t) {
                const auto& m = *terms[t];
                const Eigen::Index c = Eigen::Index(k);
                check(t, px[k].first, px[k].second, Vec3(m(0, c), m(1, c), m(2, c)));
                const Vec3 v = gl[t].at(px[k].first, px[k].second);
                for (int ch = 0; ch < 3; ++ch) {
                    const double e = (*exactTerms[t])(ch, c), den = std::max(std::fabs(e), 1e-2);
                    r.floatVsDouble = std::max(r.floatVsDouble, std::fabs(double(m(ch, c)) - e) / den);
                    r.glVsDouble = std::max(r.glVsDouble, std::fabs(double(v[ch]) - e) / den);
                }
            }
        r.covered += px.size();
        r.objectPixels += px.size();
    }
    return r;
}

void expectEquivalent(const Scene& scene, const ModelSet& set, const GlslPredictor& gp, double minCoveredFraction) {
    const PredictionComparison r = comparePrediction(scene, set, gp);
    const size_t pixels = size_t(gp.width()) * size_t(gp.height());
    std::printf("  light (%.3f %.3f %.3f): %zu covered pixels (%zu object, %zu light); max relative difference "
                "GLSL-CPU %.3g (GLSL-double %.3g, CPU float-double %.3g)\n",
                double(gp.lightPosition().x), double(gp.lightPosition().y), double(gp.lightPosition().z), r.covered,
                r.objectPixels, r.lightPixels, r.maxRelative, r.glVsDouble, r.floatVsDouble);
    EXPECT_EQ(r.failures, 0u) << "first: " << r.firstFailure << " (max relative " << r.maxRelative << ")";
    EXPECT_GE(double(r.objectPixels), minCoveredFraction * double(pixels));
}

/// A small scene with a sphere, a triangle, a floor quad, a Phong material (19 network inputs) and a
/// wide-aspect camera: the paths the Cornell box does not take.
Scene sphereScene() {
    Scene s;
    s.camera.eye = Vec3(0.2f, 0.9f, 3.f);
    s.camera.target = Vec3(0.f, 0.5f, 0.f);
    s.camera.fovYDegrees = 45.f;
    s.camera.width = 160;
    s.camera.height = 96;
    Material lambert;
    lambert.name = "floor";
    lambert.kd = Vec3(0.6f, 0.5f, 0.4f);
    Material phong;
    phong.name = "glossy";
    phong.type = Material::Type::Phong;
    phong.kd = Vec3(0.3f, 0.4f, 0.5f);
    phong.ks = Vec3(0.4f);
    phong.exponent = 80.f;
    s.materials = {lambert, phong};
    Object floor;
    floor.kind = Object::Kind::Quads;
    floor.name = "floor";
    floor.id = 0;
    floor.material = 0;
    floor.positions = {Vec3(-2, 0, -2), Vec3(-2, 0, 2), Vec3(2, 0, 2), Vec3(2, 0, -2)};
    floor.indices = {0, 1, 2, 3};
    Object ball;
    ball.kind = Object::Kind::Sphere;
    ball.name = "ball";
    ball.id = 1;
    ball.material = 1;
    ball.center = Vec3(-0.3f, 0.45f, 0.1f);
    ball.radius = 0.45f;
    ball.closed = true;
    Object tri;
    tri.kind = Object::Kind::Triangles;
    tri.name = "fin";
    tri.id = 2;
    tri.material = 1;
    tri.positions = {Vec3(0.4f, 0.f, -0.5f), Vec3(1.2f, 0.f, 0.2f), Vec3(0.7f, 1.1f, -0.1f)};
    tri.indices = {0, 1, 2};
    s.objects = {floor, ball, tri};
    Light l;
    l.name = "panel";
    l.corner = Vec3(-0.4f, 1.3f, -0.9f);
    l.edge1 = Vec3(0.8f, 0.f, 0.f);  // normal = edge1 × edge2 points down, towards the floor and the eye
    l.edge2 = Vec3(0.f, 0.f, 0.5f);
    l.radiance = Vec3(5.f, 4.f, 3.f);
    s.lights = {l};
    s.movableLight = 0;
    s.lightRegion.expand(Vec3(-1.f, 1.2f, -1.f));
    s.lightRegion.expand(Vec3(1.f, 1.8f, 0.5f));
    return s;
}

TEST(GlContext, IsOpenGL33Core) {
    RRF_REQUIRE_GL();
    GLint major = 0, minor = 0, profile = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    EXPECT_GE(major * 10 + minor, 33);
    EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
    std::printf("  renderer: %s\n", test::glContext()->renderer().c_str());
}

TEST(GlslPredictor, GBufferMatchesCpuPrimaryRaysCornellBox) {
    RRF_REQUIRE_GL();
    const Scene scene = test::cornellBox();
    GlslPredictor gp(scene, test::mixedModelSet(scene));
    gp.render();
    const GlGBuffer g = gp.readGBuffer();
    const GBufferComparison c = compareGBuffer(scene, g);
    std::printf("  %zu pixels, %zu id mismatches (%zu off silhouettes), max |dp| %.3g, max |dn| %.3g\n", c.pixels,
                c.idMismatches, c.idMismatchesOffSilhouette, c.maxPositionError, c.maxNormalError);
    EXPECT_EQ(c.idMismatchesOffSilhouette, 0u);
    EXPECT_LE(double(c.idMismatches), 0.01 * double(c.pixels));
    EXPECT_GT(double(c.compared), 0.9 * double(c.pixels));
    EXPECT_LE(c.maxPositionError, 1e-5 * double(scene.scale()));
    EXPECT_LE(c.maxNormalError, 1e-6);
    // The ceiling light faces down, towards the camera's view of it: full radiance.
    size_t lightPixels = 0;
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x)
            if (g.objectId[size_t(y) * size_t(g.width) + size_t(x)] == GlGBuffer::kLightPixel) {
                ++lightPixels;
                EXPECT_EQ(g.emission.at(x, y), scene.lights[0].radiance);
            }
    EXPECT_GT(lightPixels, 0u);
}

TEST(GlslPredictor, MatchesCpuPredictionCornellBox) {
    RRF_REQUIRE_GL();
    Scene scene = test::cornellBox();
    const ModelSet set = test::mixedModelSet(scene);
    GlslPredictor gp(scene, set);
    EXPECT_EQ(gp.networks().networkCount, 11);  // 1 + 2 + 1 + 3 + 2 + 1 + 1 (mixedModelSet)
    // The scene's own light position, then the corners of the light region (inputs far from the
    // centre of the input scalers' range).
    const Bounds3 r = scene.lightRegion;
    for (const Vec3& p : {scene.lightPosition(), r.lo, r.hi, Vec3(r.lo.x, r.hi.y, r.hi.z)}) {
        gp.setLightPosition(p);
        gp.render();
        expectEquivalent(scene, set, gp, 0.9);
    }
}

TEST(GlslPredictor, MatchesCpuPredictionOfPartitionedModels) {
    RRF_REQUIRE_GL();
    // Every model a kd-tree of three leaves. The first plane is put exactly on the hit x of the
    // image's centre pixel, so pixels lie on it: the shader's x < split must decide as the CPU's does.
    Scene scene = test::cornellBox();
    float splitX = 0.f;
    {
        GlslPredictor probe(scene, test::mixedModelSet(scene));
        probe.render();
        const GlGBuffer g = probe.readGBuffer();
        splitX = g.position[3 * (size_t(g.height / 2) * size_t(g.width) + size_t(g.width / 2))];
    }
    const float splitLight = 0.05f;
    const ModelSet set = test::partitionedModelSet(scene, splitX, splitLight);
    GlslPredictor gp(scene, set);
    EXPECT_EQ(gp.networks().networkCount, 33);  // 11 models × 3 leaves
    EXPECT_EQ(gp.networks().maxTreeDepth, 2);
    int leavesSeen[3] = {0, 0, 0};
    size_t onPlane = 0;
    for (const Vec3& p : {Vec3(-0.1f, 0.9f, 0.05f), Vec3(0.2f, 0.9f, -0.1f)}) {
        gp.setLightPosition(p);
        gp.render();
        expectEquivalent(scene, set, gp, 0.9);
        const GlGBuffer g = gp.readGBuffer();
        for (size_t i = 0; i < g.pixelCount(); ++i) {
            if (g.objectId[i] < 0) continue;
            const float x = g.position[3 * i];
            onPlane += x == splitX;
            ++leavesSeen[x < splitX ? 0 : p.x < splitLight ? 1 : 2];
        }
    }
    std::printf("  pixels per leaf %d %d %d, %zu exactly on the first plane\n", leavesSeen[0], leavesSeen[1], leavesSeen[2],
                onPlane);
    for (int n : leavesSeen) EXPECT_GT(n, 1000);
    EXPECT_GT(onPlane, 0u);
}

TEST(GlslPredictor, MatchesCpuPredictionReluOddWidthsCornellBox) {
    RRF_REQUIRE_GL();
    const Scene scene = test::cornellBox();
    const ModelSet set = test::mixedModelSet(scene, Activation::Relu, {7, 13, 5}, 23);
    GlslPredictor gp(scene, set);
    gp.render();
    expectEquivalent(scene, set, gp, 0.9);
}

TEST(GlslPredictor, MatchesCpuPredictionOfTrainedNetworks) {
    RRF_REQUIRE_GL();
    // Networks from the real trainer (a few LM epochs on a smooth synthetic signal per object), joint
    // targets: trained weights and scalers fitted by fitNetwork, not hand-made ones.
    const Scene scene = test::cornellBox();
    const RecordLayout layout = RecordLayout::forScene(scene);
    std::vector<ObjectSamples> samples;
    test::TestRandom rnd(5);
    const Bounds3 b = scene.bounds();
    for (const Object& o : scene.objects) {
        ObjectSamples s;
        s.objectId = o.id;
        s.name = o.name;
        s.numInputs = layout.inputCount();
        float brdf[8] = {};
        layout.brdfParameters(scene.materials[size_t(o.material)], brdf);
        for (int k = 0; k < 600; ++k) {
            float in[20] = {};
            const Vec3 p(rnd.range(b.lo.x, b.hi.x), rnd.range(b.lo.y, b.hi.y), rnd.range(b.lo.z, b.hi.z));
            const Vec3 l(rnd.range(scene.lightRegion.lo.x, scene.lightRegion.hi.x), rnd.range(0.6f, 0.99f),
                         rnd.range(scene.lightRegion.lo.z, scene.lightRegion.hi.z));
            const Vec3 f[4] = {p, rnd.unitVector(), l, rnd.unitVector()};
            for (int j = 0; j < 12; ++j) in[j] = f[j / 3][j % 3];
            for (int j = 12; j < s.numInputs; ++j) in[j] = brdf[j - 12];
            const float d2 = lengthSquared(p - l);
            const float fall = 0.3f / (0.2f + d2);  // radiance-like: at most ~1.3, as in the Cornell box
            const float direct[3] = {brdf[0] * fall, brdf[1] * fall, brdf[2] * fall};
            const float indirect[3] = {0.1f * direct[0] + 0.05f, 0.1f * direct[1] + 0.04f, 0.1f * direct[2] + 0.03f};
            s.add(in, direct, indirect);
        }
        samples.push_back(std::move(s));
    }
    ObjectTrainingOptions opt;
    // Enough samples per weight that LM does not overfit into huge weights: an overfitted network is
    // so ill-conditioned that its float and double predictions differ by more than 1e-4, and then no
    // float implementation (CPU or GLSL) can agree with another to 1e-4.
    opt.hidden = {6};
    opt.targets = TargetMode::Joint;
    opt.trainer.lm.maxEpochs = 10;
    const std::vector<ObjectModel> trained = trainObjects(samples, opt);
    ModelSet set;
    for (const ObjectModel& m : trained) {
        ASSERT_FALSE(m.skipped) << m.message;
        ObjectNetworks on;
        on.objectId = m.objectId;
        on.name = m.objectName;
        on.byTarget[m.target] = m.model;
        set.objects.push_back(std::move(on));
    }
    GlslPredictor gp(scene, set);
    gp.render();
    expectEquivalent(scene, set, gp, 0.9);
}

TEST(GlslPredictor, SphereTrianglePhongAndWideCamera) {
    RRF_REQUIRE_GL();
    const Scene scene = sphereScene();
    ASSERT_EQ(RecordLayout::forScene(scene).inputCount(), 19);
    const ModelSet set = test::mixedModelSet(scene, Activation::Tanh, {16, 9}, 31);
    GlslPredictor gp(scene, set);
    gp.render();
    const GlGBuffer g = gp.readGBuffer();
    ASSERT_EQ(g.width, 160);
    ASSERT_EQ(g.height, 96);
    const GBufferComparison c = compareGBuffer(scene, g);
    std::printf("  %zu id mismatches (%zu off silhouettes), max |dp| %.3g, max |dn| %.3g\n", c.idMismatches,
                c.idMismatchesOffSilhouette, c.maxPositionError, c.maxNormalError);
    EXPECT_EQ(c.idMismatchesOffSilhouette, 0u);
    EXPECT_LE(c.maxPositionError, 1e-5 * double(scene.scale()));
    EXPECT_LE(c.maxNormalError, 1e-5);  // sphere normals: (p − c)/r from slightly different p
    size_t sphere = 0, background = 0;
    for (int id : g.objectId) {
        sphere += id == 1;
        background += id == GlGBuffer::kBackgroundPixel;
    }
    EXPECT_GT(sphere, 500u);
    EXPECT_GT(background, 0u);
    size_t lights = 0;
    for (int id : g.objectId) lights += id == GlGBuffer::kLightPixel;
    EXPECT_GT(lights, 0u);
    expectEquivalent(scene, set, gp, 0.3);
}

TEST(GlslPredictor, SmoothMeshNormalsInterpolateLikeTheCpu) {
    // The fin becomes a smooth triangle: vertex normals tilted ~0.3 rad from its face normal in
    // three different directions, so a G-buffer that kept the flat normal would be ~0.3 off.
    RRF_REQUIRE_GL();
    Scene scene = sphereScene();
    Object& fin = scene.objects[2];
    const Vec3 face = normalize(cross(fin.positions[1] - fin.positions[0], fin.positions[2] - fin.positions[0]));
    fin.normals = {normalize(face + Vec3(0.3f, 0.f, 0.f)), normalize(face + Vec3(0.f, 0.3f, 0.f)),
                   normalize(face + Vec3(0.f, 0.f, -0.3f))};
    GlslPredictor gp(scene, test::mixedModelSet(scene, Activation::Tanh, {16, 9}, 31));
    gp.render();
    const GlGBuffer g = gp.readGBuffer();
    const GBufferComparison c = compareGBuffer(scene, g);
    std::printf("  %zu pixels compared, max |dn| %.3g\n", c.compared, c.maxNormalError);
    EXPECT_EQ(c.idMismatchesOffSilhouette, 0u);
    EXPECT_LE(c.maxNormalError, 1e-5);
    size_t finPixels = 0;
    double spread = 0;  // largest angle between a fin pixel's normal and the face normal
    for (size_t i = 0; i < g.objectId.size(); ++i) {
        if (g.objectId[i] != 2) continue;
        ++finPixels;
        const Vec3 n(g.normal[3 * i], g.normal[3 * i + 1], g.normal[3 * i + 2]);
        spread = std::max(spread, std::acos(std::min(1.0, std::fabs(double(dot(n, face))))));
    }
    EXPECT_GT(finPixels, 100u);
    EXPECT_GT(spread, 0.1) << "the fin's normals must vary across it";
}

TEST(GlslPredictor, OneSidedLightIsDarkFromBehind) {
    RRF_REQUIRE_GL();
    Scene scene = sphereScene();
    std::swap(scene.lights[0].edge1, scene.lights[0].edge2);  // the light now faces up, away from the eye
    GlslPredictor gp(scene, test::mixedModelSet(scene));
    gp.render();
    const GlGBuffer g = gp.readGBuffer();
    const Image direct = gp.read(Term::Direct);
    size_t lightPixels = 0;
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x)
            if (g.objectId[size_t(y) * size_t(g.width) + size_t(x)] == GlGBuffer::kLightPixel) {
                ++lightPixels;
                EXPECT_TRUE(g.emission.at(x, y).isZero());
                EXPECT_TRUE(direct.at(x, y).isZero());
            }
    EXPECT_GT(lightPixels, 0u);  // the light still occludes what lies behind it
}

TEST(GlslPredictor, MovingTheLightChangesInputAndGeometry) {
    RRF_REQUIRE_GL();
    const Scene scene = test::cornellBox();
    GlslPredictor gp(scene, test::mixedModelSet(scene));
    gp.render();
    const Image before = gp.read(Term::Global);
    const std::vector<int> idsBefore = gp.readGBuffer().objectId;
    gp.setLightPosition(Vec3(0.4f, 0.7f, 0.3f));
    gp.render();
    const Image after = gp.read(Term::Global);
    const std::vector<int> idsAfter = gp.readGBuffer().objectId;
    size_t changed = 0;
    for (size_t i = 0; i < before.data.size(); ++i) changed += before.data[i] != after.data[i];
    EXPECT_GT(changed, before.data.size() / 2);
    EXPECT_NE(idsBefore, idsAfter);  // the light's quad moved
}

TEST(GlslPredictor, ResizeWithSetCamera) {
    RRF_REQUIRE_GL();
    Scene scene = test::cornellBox();
    const ModelSet set = test::mixedModelSet(scene);
    GlslPredictor gp(scene, set);
    Camera cam = scene.camera;
    cam.width = 97;
    cam.height = 61;
    gp.setCamera(cam);
    scene.camera = cam;
    gp.render();
    EXPECT_EQ(gp.read(Term::Global).width, 97);
    expectEquivalent(scene, set, gp, 0.5);  // the wide frame shows background beside the box
    cam.width = 0;
    EXPECT_THROW(gp.setCamera(cam), std::invalid_argument);
}

TEST(GlslPredictor, RestoresCallerGlState) {
    RRF_REQUIRE_GL();
    const Scene scene = test::cornellBox();
    GlslPredictor gp(scene, test::mixedModelSet(scene));
    GLuint fbo = 0, tex = 0, vao = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 8, 8, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glViewport(1, 2, 3, 4);
    glEnable(GL_BLEND);
    glActiveTexture(GL_TEXTURE2);
    gp.render();
    (void)gp.read(Term::Direct);
    GLint v[4], drawFbo, readFbo, boundVao, active, unit0;
    glGetIntegerv(GL_VIEWPORT, v);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFbo);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFbo);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &boundVao);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    glActiveTexture(GL_TEXTURE0);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &unit0);
    EXPECT_EQ(v[0], 1);
    EXPECT_EQ(v[3], 4);
    EXPECT_EQ(GLuint(drawFbo), fbo);
    EXPECT_EQ(GLuint(readFbo), fbo);
    EXPECT_EQ(GLuint(boundVao), vao);
    EXPECT_EQ(active, GL_TEXTURE2);
    EXPECT_EQ(GLuint(unit0), tex);
    EXPECT_TRUE(glIsEnabled(GL_BLEND));
    EXPECT_FALSE(glIsEnabled(GL_DEPTH_TEST));
    glDisable(GL_BLEND);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindVertexArray(0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
    glDeleteVertexArrays(1, &vao);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST(GlslPredictor, ShaderErrorsNameTheFile) {
    RRF_REQUIRE_GL();
    const Scene scene = test::cornellBox();
    const ModelSet set = test::mixedModelSet(scene);
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("rrf_gl_shaders_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    for (const char* f : {"gbuffer.vert", "gbuffer.frag", "fullscreen.vert", "predict.frag", "direct_light.glsl"})
        fs::copy_file(fs::path(RRF_SOURCE_DIR) / "shaders" / f, dir / f, fs::copy_options::overwrite_existing);
    {
        std::ofstream bad(dir / "predict.frag", std::ios::app);
        bad << "\nvoid broken() { undeclared_identifier = 1; }\n";
    }
    try {
        GlslPredictor gp(scene, set, dir.string());
        ADD_FAILURE() << "a broken shader compiled";
    } catch (const GlError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("predict.frag"), std::string::npos) << msg;
        EXPECT_NE(msg.find("does not compile"), std::string::npos) << msg;
    }
    fs::remove(dir / "gbuffer.vert");
    try {
        GlslPredictor gp(scene, set, dir.string());
        ADD_FAILURE() << "a missing shader was not reported";
    } catch (const GlError& e) {
        EXPECT_NE(std::string(e.what()).find("gbuffer.vert"), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

}  // namespace
}  // namespace rrf::test_glsl_predictor

namespace rrf::test_glsl_predictor {
namespace {

TEST(GlslPredictor, AgreesWithCorePredictorImages) {
    RRF_REQUIRE_GL();
    // End to end against core/predictor (its own ray-cast G-buffer): the same conventions for view
    // direction, normal side, light position, emitters and term rules. Inputs differ only by the two
    // G-buffers' float rounding (hit points ~1e-6 apart), which moves these networks' outputs far less
    // than 1e-4 (3e-5 measured on llvmpipe), so the bound holds end to end. Silhouette pixels
    // (where rasteriser and ray tracer may pick different objects) are left out.
    const Scene scene = test::cornellBox();
    const ModelSet set = test::mixedModelSet(scene);
    PredictionSettings learned;  // a new GlslPredictor takes direct light from the networks
    learned.direct = PredictionSettings::Direct::Network;
    const Predictor cpu(scene, set, learned);
    GlslPredictor gp(scene, set);
    const Vec3 light(0.2f, 0.8f, -0.1f);
    gp.setLightPosition(light);
    gp.render();
    const int w = gp.width(), h = gp.height();
    const GBuffer cgb = cpu.gbuffer(light, w, h);
    const Prediction pred = cpu.predict(cgb);
    const GlGBuffer g = gp.readGBuffer();
    auto cpuId = [&](int x, int y) {
        const size_t i = size_t(y) * size_t(w) + size_t(x);
        return cgb.object[i] >= 0 ? cgb.object[i] : (cgb.light[i] >= 0 ? GlGBuffer::kLightPixel : GlGBuffer::kBackgroundPixel);
    };
    size_t compared = 0, failures = 0;
    double worst = 0;
    for (int t = 0; t < 3; ++t) {
        const Image gl = gp.read(Term(t));
        for (int y = 1; y + 1 < h; ++y)
            for (int x = 1; x + 1 < w; ++x) {
                const int id = cpuId(x, y);
                if (id != g.objectId[size_t(y) * size_t(w) + size_t(x)] || id != cpuId(x - 1, y) ||
                    id != cpuId(x + 1, y) || id != cpuId(x, y - 1) || id != cpuId(x, y + 1))
                    continue;
                const Vec3 a = gl.at(x, y), b = pred.images[t].at(x, y);
                for (int c = 0; c < 3; ++c) {
                    const double rel = std::fabs(double(a[c]) - double(b[c])) / std::max(std::fabs(double(b[c])), 1e-2);
                    worst = std::max(worst, rel);
                    failures += rel > 1e-4;
                }
                ++compared;
            }
    }
    std::printf("  %zu pixel-terms compared with core/predictor, max relative difference %.3g\n", compared, worst);
    EXPECT_GT(compared, size_t(3 * 0.9 * w * h));
    EXPECT_EQ(failures, 0u) << "max relative difference " << worst;
}

}  // namespace
}  // namespace rrf::test_glsl_predictor
