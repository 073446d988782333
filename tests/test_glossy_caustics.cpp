// Glossy caustics (core/predict/glossy_caustics.h): light → glossy face → diffuse receiver, against
// the mirrored light's irradiance (a near-mirror), an independent quadrature over the face (finite
// lobes, a face that clips the light's image), and the gather's cosine rays (the same integral
// sampled from the receiver's side).
#include <cmath>

#include <gtest/gtest.h>

#include "core/predict/glossy_caustics.h"
#include "core/predict/phong_lobe_integral.h"
#include "core/predict/prediction_settings_json.h"
#include "core/predict/predictor.h"
#include "core/util/json_reader.h"
#include "model_builders.h"
#include "scene_builders.h"

namespace test_glossy_caustics {

using namespace rrf;
using namespace rrf::test;

namespace {
constexpr float kRho = 0.7f, kKs = 0.9f, kLe = 10.f;

Scene mirrorScene(float exponent, float fx0 = -3.f, float fw = 6.f, float fd = 6.f) {
    return mirrorCausticScene(exponent, kKs, kRho, kLe, 16, fx0, fw, fd);
}

/// Mean and standard error of the caustic at p over `keys` pixel keys.
void causticStats(const GlossyCaustics& c, const Scene& s, const Vec3& p, int keys, double& mean, double& sigma) {
    TraceCounters counters;
    double sum = 0, sum2 = 0;
    for (int k = 0; k < keys; ++k) {
        const double v = c.radiance(p, Vec3(0, -1, 0), Vec3(0, -1, 0), Vec3(kRho), 1, s.lights[0], uint64_t(k), counters).x;
        sum += v;
        sum2 += v * v;
    }
    mean = sum / keys;
    sigma = std::sqrt(std::max(0.0, sum2 / keys - mean * mean) / keys);
}

/// The caustic at p by an independent route: a midpoint rule over the floor face (y uniform by
/// area) of the face's exact unshadowed glossy radiance towards p (phongLobeIntegral over the
/// light), times ρ/π G(p, y).
double faceQuadrature(const Scene& s, const Vec3& p, float exponent, float fx0, float fw, float fd, int n) {
    const Light& l = s.lights[0];
    double sum = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const Vec3 y(fx0 + fw * (float(i) + 0.5f) / float(n), 0.f, -0.5f * fd + fd * (float(j) + 0.5f) / float(n));
            const Vec3 d = p - y;
            const float d2 = lengthSquared(d), dist = std::sqrt(d2);
            const Vec3 wo = d / dist;
            const Vec3 m(0, 1, 0);
            const float g = phongLobeIntegral(l, y, m, reflect(wo, m), exponent);
            const double glossy = double(kLe) * kKs * (exponent + 2.f) * kInv2Pi * g;
            sum += glossy * double(wo.y) * double(wo.y) / double(d2);  // cosθ at y and at p (facing −y)
        }
    return kRho / kPi * sum * double(fw) * double(fd) / double(n * n);
}
}  // namespace

// For a lobe this narrow the face reflects ks · Le · cosθ along the mirror direction, so the
// ceiling's radiance is ρ/π · ks Le ∫_image cos²θ dω over the light's mirror image (y = −1)
// (tests/scene_builders.h, mirroredLightIntegral).
TEST(GlossyCaustics, NearMirrorMatchesTheMirroredLightsIrradiance) {
    const Scene s = mirrorScene(1e4f);
    const Accel accel(s);
    const PathTracer tracer(s, accel, Estimator::NEE, 1);
    const GlossyCaustics caustics(tracer, 16, 50.f, 7);
    ASSERT_TRUE(caustics.casts(0));
    ASSERT_FALSE(caustics.casts(1));
    for (const Vec3 p : {Vec3(0.2f, 1.f, 0.f), Vec3(0.9f, 1.f, 0.6f), Vec3(1.8f, 1.f, -1.2f)}) {
        const double expected = kRho / kPi * kKs * kLe * mirroredLightIntegral(p, 128);
        double mean, sigma;
        causticStats(caustics, s, p, 256, mean, sigma);
        EXPECT_LT(sigma, 0.01 * expected) << "the test must see a 3 % error";
        EXPECT_NEAR(mean, expected, 4 * sigma + 0.005 * expected) << "at " << p.x << ", " << p.z;
    }
}

// Finite lobes (the glossy box's tall box has exponent 100, its back wall 10) blur the image; a small
// face clips it. The Gaussian on the face is only the importance density: the estimate must still
// be the integral, checked against a quadrature over the face that knows nothing of mirror points.
TEST(GlossyCaustics, FiniteLobesAndAClippingFaceMatchAQuadratureOverTheFace) {
    struct Case {
        float exponent, fx0, fw, fd;
    };
    for (const Case c : {Case{200.f, -3.f, 6.f, 6.f}, Case{30.f, -1.5f, 3.f, 3.f}, Case{300.f, -0.2f, 0.4f, 0.44f}}) {
        const Scene s = mirrorScene(c.exponent, c.fx0, c.fw, c.fd);
        const Accel accel(s);
        const PathTracer tracer(s, accel, Estimator::NEE, 1);
        const GlossyCaustics caustics(tracer, 16, 10.f, 3);
        for (const Vec3 p : {Vec3(0.15f, 1.f, 0.05f), Vec3(0.8f, 1.f, -0.4f)}) {
            const double expected = faceQuadrature(s, p, c.exponent, c.fx0, c.fw, c.fd, 400);
            ASSERT_GT(expected, 0.0);
            double mean, sigma;
            causticStats(caustics, s, p, 512, mean, sigma);
            EXPECT_LT(sigma, 0.02 * expected) << "exponent " << c.exponent;
            EXPECT_NEAR(mean, expected, 4 * sigma + 0.01 * expected) << "exponent " << c.exponent << " at " << p.x;
        }
    }
}

// The same light two ways in the predictor: the ceiling gathered by name with many cosine rays that
// find the floor's glossy reflection of the light themselves ("caustic_samples": 0), and with few
// cosine rays that leave it out plus the caustic sampled from the light. Both estimate one integral.
TEST(GlossyCaustics, GatherFromTheLightSideEqualsTheCosineRays) {
    const Scene s = mirrorScene(200.f);
    const ModelSet models = albedoModels(s, {"indirect"});
    auto ceilingWith = [&](const ModelSet& set, int diffuse, int caustic) {
        const nlohmann::json section = {
            {"direct", "exact"},
            {"gather", {{"objects", {"ceiling"}}, {"diffuse_samples", diffuse}, {"caustic_samples", caustic},
                        {"second_lobe_samples", 0}, {"second_diffuse_samples", 0}}}};
        const Predictor pred(s, set, predictionSettingsFromJson(JsonReader(section, "p.json", "/prediction")));
        const GBuffer g = pred.gbuffer(s.lightPosition(), 16, 16);
        const Prediction out = pred.predict(g);
        EXPECT_EQ(out.nonFinite, 0u);
        double sum = 0;
        for (uint32_t i : g.pixelsByObject[1]) sum += out.image(Term::Indirect).at(int(i % 16), int(i / 16)).x;
        EXPECT_GT(g.pixelsByObject[1].size(), 200u);
        return sum / double(g.pixelsByObject[1].size());
    };
    auto ceiling = [&](int diffuse, int caustic) { return ceilingWith(models, diffuse, caustic); };
    const double cosine = ceiling(2048, 0), light = ceiling(16, 32);
    ASSERT_GT(cosine, 0.0);
    EXPECT_NEAR(light, cosine, 0.04 * cosine);

    // A mirror whose global network answers for its points whole casts nothing here: its light is
    // already in what the cosine rays bring back, and must not be added twice.
    ModelSet global = albedoModels(s, {"indirect"});
    for (ObjectNetworks& o : global.objects)
        if (o.name == "mirror") {
            o.byTarget.clear();
            o.byTarget.emplace("global", copyInputNet(RecordLayout::forScene(s).inputCount(), {12, 13, 14}));
        }
    EXPECT_EQ(ceilingWith(global, 16, 32), ceilingWith(global, 16, 0));
}

TEST(GlossyCaustics, PlanesOfABoxAndOfACurvedMesh) {
    Scene s;
    const int m = addLambert(s, Vec3(0.5f));
    addQuads(s, {{{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}, {{0, 0, 1}, {1, 0, 0}, {0, 0, -1}}, {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}}}, m);
    EXPECT_EQ(GlossyCaustics::planesOf(s.objects[0]).size(), 2u) << "two quads on y = 0 (opposite windings) are one plane";
    Object sphere;
    sphere.kind = Object::Kind::Sphere;
    EXPECT_TRUE(GlossyCaustics::planesOf(sphere).empty());
    Object fan;  // 40 triangles around a cone: too many planes
    fan.kind = Object::Kind::Triangles;
    fan.positions.push_back(Vec3(0, 1, 0));
    for (int k = 0; k < 40; ++k) {
        const float a = 2.f * kPi * float(k) / 40.f;
        fan.positions.push_back(Vec3(std::cos(a), 0, std::sin(a)));
    }
    for (uint32_t k = 0; k < 40; ++k) {
        fan.indices.push_back(0);
        fan.indices.push_back(1 + k);
        fan.indices.push_back(1 + (k + 1) % 40);
    }
    EXPECT_TRUE(GlossyCaustics::planesOf(fan).empty());
}

}  // namespace test_glossy_caustics
