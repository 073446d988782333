// GLSL evaluation of encoded networks (issue 16: frequency, one-blob, hash grid; shaders/encoding.glsl)
// against the CPU on the Cornell box: the shader's terms must equal NetworkModel::predict (which runs
// InputEncoding::forward) and the C++ mirror evaluateTerms to float rounding (issue 6's bound,
// relative 1e-4 with a 1e-2 floor) on every covered pixel.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "app/gl/glsl_predictor.h"
#include "tests/gl/gl_test_env.h"
#include "tests/gl/glsl_comparison.h"
#include "tests/gl/test_models.h"

namespace rrf::test_glsl_encodings {
namespace {

using nlohmann::json;
using test::closeEnough;

/// The Cornell box at 64 × 64: llvmpipe evaluates a hash grid per pixel in software.
Scene smallCornellBox() {
    Scene s = test::cornellBox();
    s.camera.width = s.camera.height = 64;
    return s;
}

/// Every object pixel of the last render: the shader's terms against evaluateTerms on the same
/// G-buffer inputs. Returns the number of pixel-terms compared.
size_t expectMirrorEqualsShader(const Scene& scene, const GlslPredictor& gp) {
    const GlGBuffer g = gp.readGBuffer();
    const Image gl[3] = {gp.read(Term::Direct), gp.read(Term::Indirect), gp.read(Term::Global)};
    const Vec3 light = gp.lightPosition();
    size_t compared = 0, failures = 0;
    double worst = 0;
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
            const size_t i = size_t(y) * size_t(g.width) + size_t(x);
            const int id = g.objectId[i];
            if (id < 0) continue;
            const Vec3 p(g.position[3 * i], g.position[3 * i + 1], g.position[3 * i + 2]);
            const Vec3 n(g.normal[3 * i], g.normal[3 * i + 1], g.normal[3 * i + 2]);
            const Vec3 f[4] = {p, normalize(scene.camera.eye - p), light, n};
            float in[12];
            for (int j = 0; j < 12; ++j) in[j] = f[j / 3][j % 3];
            const std::array<Vec3, 3> mirror = evaluateTerms(gp.networks(), id, in);
            for (int t = 0; t < 3; ++t) {
                // Emission is the renderer's: object pixels of the Cornell box emit nothing.
                const Vec3 v = gl[t].at(x, y);
                for (int c = 0; c < 3; ++c) {
                    const float m = mirror[size_t(t)][c];
                    worst = std::max(worst, std::fabs(double(v[c]) - double(m)) / std::max(std::fabs(double(m)), 1e-2));
                    failures += !closeEnough(v[c], m);
                }
                ++compared;
            }
        }
    std::printf("  %zu pixel-terms against evaluateTerms, max relative difference %.3g\n", compared, worst);
    EXPECT_EQ(failures, 0u) << "max relative difference " << worst;
    return compared;
}

/// Renders with `set` at the scene's light and at two corners of the light region, and compares
/// with NetworkModel::predict and evaluateTerms.
void expectEncodedEquivalent(const Scene& scene, const ModelSet& set) {
    GlslPredictor gp(scene, set);
    const Bounds3 r = scene.lightRegion;
    for (const Vec3& p : {scene.lightPosition(), r.lo, r.hi}) {
        gp.setLightPosition(p);
        gp.render();
        test::expectEquivalent(scene, set, gp, 0.9);
        EXPECT_GT(expectMirrorEqualsShader(scene, gp), size_t(3 * 0.9 * 64 * 64));
    }
}

TEST(GlslEncodings, FrequencyMatchesCpu) {
    RRF_REQUIRE_GL();
    const Scene scene = smallCornellBox();
    // Up to 2^5 π x: the largest arguments (~100) are where sin and cos implementations part first.
    const json enc = json::parse(R"([{"type": "frequency", "inputs": ["position", "light"], "frequencies": 6,
                                      "include_input": true}])");
    expectEncodedEquivalent(scene, test::mixedModelSet(scene, Activation::Tanh, {16, 8}, 41, enc));
}

TEST(GlslEncodings, OneBlobMatchesCpu) {
    RRF_REQUIRE_GL();
    const Scene scene = smallCornellBox();
    const json enc = json::parse(R"([{"type": "one_blob", "inputs": ["view", "normal"], "bins": 16}])");
    expectEncodedEquivalent(scene, test::mixedModelSet(scene, Activation::Tanh, {16, 8}, 43, enc));
}

TEST(GlslEncodings, HashGridOverPositionMatchesCpu) {
    RRF_REQUIRE_GL();
    const Scene scene = smallCornellBox();
    // Levels at resolution 4, 8 (dense: (res + 1)^3 ≤ 2^12) and 16 … 512 (hashed).
    const json enc = json::parse(R"([{"type": "hash_grid", "inputs": "position", "levels": 8, "log2_table_size": 12,
                                      "features_per_level": 2, "base_resolution": 4, "growth": 2.0}])");
    const ModelSet set = test::mixedModelSet(scene, Activation::Relu, {32, 16}, 47, enc);
    expectEncodedEquivalent(scene, set);
}

TEST(GlslEncodings, ReflectedInputMatchesCpu) {
    RRF_REQUIRE_GL();
    // The shader derives reflect(view, normal) per pixel after the BRDF inputs (core/nn/derived_inputs.h):
    // the diffuse box (inputs 15–17) with the rows raw and with one-blob over view and reflected,
    // and the glossy box (19–21, the sixth vec4) with frequencies of the reflected direction.
    const Scene diffuse = smallCornellBox();
    expectEncodedEquivalent(diffuse, test::mixedModelSet(diffuse, Activation::Tanh, {16, 8}, 59, json::array(),
                                                         DerivedInputs{true}));
    const json blob = json::parse(R"([{"type": "one_blob", "inputs": ["view", "reflected"], "bins": 8}])");
    expectEncodedEquivalent(diffuse, test::mixedModelSet(diffuse, Activation::Tanh, {16, 8}, 61, blob, DerivedInputs{true}));
    Scene glossy = loadScene(std::string(RRF_SOURCE_DIR) + "/projects/cornell-glossy/scene.json");
    glossy.camera.width = glossy.camera.height = 64;
    const json freq = json::parse(R"([{"type": "frequency", "inputs": "reflected", "frequencies": 4}])");
    expectEncodedEquivalent(glossy, test::mixedModelSet(glossy, Activation::Tanh, {16, 8}, 67, freq, DerivedInputs{true}));
}

TEST(GlslEncodings, CombinedEncodingsOfPartitionedModelsMatchCpu) {
    RRF_REQUIRE_GL();
    const Scene scene = smallCornellBox();
    // Three components and pass-through of the normal and kd; 4 features per level (one texel
    // per vertex) and a non-integer growth; every model a kd-tree of three leaves.
    const json enc = json::parse(R"([
        {"type": "hash_grid", "inputs": "position", "levels": 6, "log2_table_size": 10, "features_per_level": 4,
         "base_resolution": 3, "growth": 1.7},
        {"type": "frequency", "inputs": "view", "frequencies": 3, "include_input": false},
        {"type": "one_blob", "inputs": "light", "bins": 8}])");
    ModelSet set = test::partitionedModelSet(scene, 0.f, 0.05f);
    uint64_t seed = 53;
    for (ObjectNetworks& on : set.objects)
        for (auto& [target, model] : on.byTarget)
            for (NetworkModel& leaf : model.leaves)
                leaf = test::encodedNetwork(scene, on.objectId, target, {20, 10}, Activation::Tanh, seed++, enc);
    GlslPredictor gp(scene, set);
    EXPECT_EQ(gp.networks().networkCount, 33);
    expectEncodedEquivalent(scene, set);
}

}  // namespace
}  // namespace rrf::test_glsl_encodings
