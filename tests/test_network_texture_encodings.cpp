// Encoded networks in the packed network texture (core/predict/network_texture.h, layout version 3),
// without GL: evaluateTerms (the C++ mirror of shaders/encoding.glsl + predict.frag) against closed
// forms of each encoding and against NetworkModel::predict, the layout of the encoding descriptors and
// hash tables, and the row limit.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/nn/encoding_json.h"
#include "core/predict/network_texture.h"
#include "tests/gl/test_models.h"

namespace rrf::test_network_texture_encodings {
namespace {

using nlohmann::json;

constexpr double kPiD = 3.14159265358979323846;

/// A linear network (no hidden layer, identity scalers) whose output channel c is feature
/// `features[c]` of `encoding`: evaluateTerms then returns the encoding's features themselves.
NetworkModel featureProbe(const Scene& scene, const json& encoding, const int (&features)[3]) {
    NetworkModel m;
    const int inputs = RecordLayout::forScene(scene).inputCount();
    m.encoding = inputEncodingFromJson(JsonReader(encoding, "test encoding"), inputs);
    m.arch.inputs = m.encoding.outputs();
    m.arch.hidden = {};
    m.arch.outputs = 3;
    m.params = VecX<double>::Zero(m.arch.numParams());
    for (int c = 0; c < 3; ++c) m.params[m.arch.weightOffset(0) + c + 3 * features[c]] = 1.0;  // W(c, f), column-major
    m.inputScaler = MinMaxScaler::identity(inputs);
    m.outputScaler = MinMaxScaler::identity(3);
    m.encodingParams = VecX<double>::Zero(m.encoding.numParams());
    m.objectId = 0;
    m.target = "global";
    return m;
}

ModelSet single(NetworkModel m) {
    ModelSet set;
    ObjectNetworks on;
    on.objectId = 0;
    on.byTarget["global"] = std::move(m);
    set.objects.push_back(std::move(on));
    return set;
}

/// Geometric inputs of sample k: every coordinate in [−1.3, 1.3], so that some normalised inputs of
/// these identity-scaled probes lie outside [−1, 1] (the encodings clamp u to [0, 1]).
void probeInputs(test::TestRandom& rnd, float in[12]) {
    for (int j = 0; j < 12; ++j) in[j] = rnd.range(-1.3f, 1.3f);
}

double unit(double x) { return std::min(std::max((x + 1.0) * 0.5, 0.0), 1.0); }

TEST(NetworkTextureEncodings, FrequencyFeaturesAreSinCosOfPowersOfTwo) {
    const Scene scene = test::cornellBox();
    const json enc = json::parse(R"([{"type": "frequency", "inputs": "view", "frequencies": 3, "include_input": true}])");
    // Per view input 7 features [x, sin πx, cos πx, sin 2πx, cos 2πx, sin 4πx, cos 4πx]; then the
    // 12 pass-through inputs 0 1 2 6 7 … 14, so feature 21 + 3 is input 6 (light x).
    const NetworkTexture tex = packNetworkTexture(scene, single(featureProbe(scene, enc, {5, 9, 24})));
    test::TestRandom rnd(1);
    for (int k = 0; k < 200; ++k) {
        float in[12];
        probeInputs(rnd, in);
        const Vec3 y = evaluateTerms(tex, 0, in)[2];
        EXPECT_NEAR(y[0], std::sin(4.0 * kPiD * double(in[3])), 2e-6) << in[3];
        EXPECT_NEAR(y[1], std::cos(kPiD * double(in[4])), 2e-6) << in[4];
        EXPECT_EQ(y[2], in[6]);
    }
}

TEST(NetworkTextureEncodings, OneBlobFeaturesAreGaussianBins) {
    const Scene scene = test::cornellBox();
    const json enc = json::parse(R"([{"type": "one_blob", "inputs": "light", "bins": 4}])");
    // Feature 4j + k: bin k of light input j.
    const NetworkTexture tex = packNetworkTexture(scene, single(featureProbe(scene, enc, {0, 6, 11})));
    test::TestRandom rnd(2);
    auto bin = [](double x, int k) {
        const double z = (unit(x) - (k + 0.5) / 4.0) * 4.0;
        return std::exp(-0.5 * z * z);
    };
    for (int k = 0; k < 200; ++k) {
        float in[12];
        probeInputs(rnd, in);
        const Vec3 y = evaluateTerms(tex, 0, in)[2];
        EXPECT_NEAR(y[0], bin(in[6], 0), 1e-6);
        EXPECT_NEAR(y[1], bin(in[7], 2), 1e-6);
        EXPECT_NEAR(y[2], bin(in[8], 3), 1e-6);
    }
}

TEST(NetworkTextureEncodings, HashGridDenseLevelsInterpolateLinearTables) {
    // Levels of resolution 4 and 8 index 2^12 entries densely ((res+1)^3 ≤ 4096). Their tables hold
    // linear functions of the vertex (v0 in feature 0, v1 + 2 v2 in feature 1), which trilinear
    // interpolation reproduces exactly: feature 0 of level l is u0 · res_l.
    const Scene scene = test::cornellBox();
    const json enc = json::parse(R"([{"type": "hash_grid", "inputs": "position", "levels": 2, "log2_table_size": 12,
                                      "features_per_level": 2, "base_resolution": 4, "growth": 2.0}])");
    NetworkModel m = featureProbe(scene, enc, {0, 2, 3});
    const int res[2] = {4, 8};
    for (int l = 0; l < 2; ++l)
        for (int v2 = 0; v2 <= res[l]; ++v2)
            for (int v1 = 0; v1 <= res[l]; ++v1)
                for (int v0 = 0; v0 <= res[l]; ++v0) {
                    const int idx = v0 + (res[l] + 1) * (v1 + (res[l] + 1) * v2);
                    m.encodingParams[(l * 4096 + idx) * 2] = v0;
                    m.encodingParams[(l * 4096 + idx) * 2 + 1] = v1 + 2 * v2;
                }
    const NetworkTexture tex = packNetworkTexture(scene, single(std::move(m)));
    test::TestRandom rnd(3);
    for (int k = 0; k < 300; ++k) {
        float in[12];
        probeInputs(rnd, in);
        const Vec3 y = evaluateTerms(tex, 0, in)[2];
        const double u0 = unit(in[0]), u1 = unit(in[1]), u2 = unit(in[2]);
        EXPECT_NEAR(y[0], 4.0 * u0, 2e-6);
        EXPECT_NEAR(y[1], 8.0 * u0, 4e-6);
        EXPECT_NEAR(y[2], 8.0 * u1 + 16.0 * u2, 2e-5);
    }
}

TEST(NetworkTextureEncodings, HashGridHashedLevelUsesTheDocumentedHash) {
    // One level of resolution 16 in a table of 2^10 entries: hashed (17^3 > 1024). The expected
    // feature is the trilinear blend of the table entries at (v0 · 1 ^ v1 · 2654435761 ^ v2 ·
    // 805459861) mod 1024, computed here in double from the documented formula.
    const Scene scene = test::cornellBox();
    const json enc = json::parse(R"([{"type": "hash_grid", "inputs": "position", "levels": 1, "log2_table_size": 10,
                                      "features_per_level": 1, "base_resolution": 16, "growth": 1.5}])");
    NetworkModel m = featureProbe(scene, enc, {0, 0, 0});
    test::TestRandom rnd(4);
    for (Eigen::Index i = 0; i < m.encodingParams.size(); ++i) m.encodingParams[i] = double(rnd.range(-1.f, 1.f));
    const VecX<double> table = m.encodingParams;
    const NetworkTexture tex = packNetworkTexture(scene, single(std::move(m)));
    const uint32_t primes[3] = {1u, 2654435761u, 805459861u};
    for (int k = 0; k < 300; ++k) {
        float in[12];
        probeInputs(rnd, in);
        double expected = 0;
        int cell[3];
        double f[3];
        for (int i = 0; i < 3; ++i) {
            const double pos = unit(in[i]) * 16.0;
            cell[i] = std::min(int(std::floor(pos)), 15);
            f[i] = pos - cell[i];
        }
        for (int corner = 0; corner < 8; ++corner) {
            double w = 1;
            uint32_t h = 0;
            for (int i = 0; i < 3; ++i) {
                const int up = (corner >> i) & 1;
                w *= up ? f[i] : 1 - f[i];
                h ^= uint32_t(cell[i] + up) * primes[i];
            }
            expected += w * table[h % 1024];
        }
        EXPECT_NEAR(evaluateTerms(tex, 0, in)[2][0], expected, 1e-5);
    }
}

TEST(NetworkTextureEncodings, MirrorMatchesPredictForEachEncoding) {
    // Random networks of every target mix (tests/gl/test_models.h) at hit points in and beyond the
    // box: the mirror of the shader against NetworkModel::predict (InputEncoding::forward + MLP).
    const Scene scene = test::cornellBox();
    const RecordLayout layout = RecordLayout::forScene(scene);
    const char* encodings[] = {
        R"([{"type": "frequency", "inputs": ["position", "normal"], "frequencies": 5, "include_input": true}])",
        R"([{"type": "one_blob", "inputs": ["view", "light"], "bins": 12}])",
        R"([{"type": "hash_grid", "inputs": "position", "levels": 6, "log2_table_size": 11, "features_per_level": 2,
             "base_resolution": 4, "growth": 1.8}])",
        R"([{"type": "hash_grid", "inputs": "position", "levels": 4, "log2_table_size": 10, "features_per_level": 4,
             "base_resolution": 3, "growth": 2.5},
            {"type": "frequency", "inputs": "view", "frequencies": 2, "include_input": false},
            {"type": "one_blob", "inputs": "light", "bins": 6}])"};
    uint64_t seed = 61;
    for (const char* e : encodings) {
        const ModelSet set = test::mixedModelSet(scene, Activation::Tanh, {16, 8}, seed++, json::parse(e));
        const NetworkTexture tex = packNetworkTexture(scene, set);
        test::TestRandom rnd(seed);
        const Bounds3 b = scene.bounds();
        size_t checked = 0;
        double worst = 0;
        for (const ObjectNetworks& on : set.objects) {
            float brdf[8] = {};
            layout.brdfParameters(scene.materials[size_t(scene.objects[size_t(on.objectId)].material)], brdf);
            const int n = 100;
            MatX<float> raw(layout.inputCount(), n);
            for (int c = 0; c < n; ++c) {
                const Vec3 ext = (b.hi - b.lo) * 0.2f;  // up to 20 % beyond the box on each side
                const Vec3 p(rnd.range(b.lo.x - ext.x, b.hi.x + ext.x), rnd.range(b.lo.y - ext.y, b.hi.y + ext.y),
                             rnd.range(b.lo.z - ext.z, b.hi.z + ext.z));
                const Vec3 f[4] = {p, rnd.unitVector(), scene.lightPosition() + rnd.unitVector() * 0.1f, rnd.unitVector()};
                for (int k = 0; k < 12; ++k) raw(k, c) = f[k / 3][k % 3];
                for (int k = 12; k < layout.inputCount(); ++k) raw(k, c) = brdf[k - 12];
            }
            const test::CpuTerms ref = test::cpuTerms(on, raw);
            const MatX<float>* r[3] = {&ref.direct, &ref.indirect, &ref.global};
            for (int c = 0; c < n; ++c) {
                const std::array<Vec3, 3> t = evaluateTerms(tex, on.objectId, &raw(0, c));
                for (int term = 0; term < 3; ++term)
                    for (int ch = 0; ch < 3; ++ch) {
                        const float a = t[size_t(term)][ch], want = (*r[term])(ch, c);
                        worst = std::max(worst, double(std::fabs(a - want)) / std::max(double(std::fabs(want)), 1e-2));
                        ASSERT_TRUE(test::closeEnough(a, want)) << e << "\nobject " << on.objectId << " term " << term
                                                                << " sample " << c << ": packed " << a << " vs predict " << want;
                        ++checked;
                    }
            }
        }
        std::printf("  %s: %zu values, max relative difference %.3g\n", set.objects[0].byTarget.begin()->second.leaves[0]
                                                                              .encoding.describe().c_str(),
                    checked, worst);
        EXPECT_GT(checked, 1000u);
    }
}

TEST(NetworkTextureEncodings, DescriptorAndTableLayout) {
    const Scene scene = test::cornellBox();  // 15 inputs: 12 geometric + kd
    const json enc = json::parse(R"([{"type": "hash_grid", "inputs": "position", "levels": 3, "log2_table_size": 12,
                                      "features_per_level": 2, "base_resolution": 4, "growth": 2.0}])");
    NetworkModel m = featureProbe(scene, enc, {0, 1, 2});
    for (Eigen::Index i = 0; i < m.encodingParams.size(); ++i) m.encodingParams[i] = double(i % 1000) * 0.25;
    const NetworkTexture tex = packNetworkTexture(scene, single(m));
    EXPECT_EQ(tex.texels[0], 4.f);  // layout version
    EXPECT_EQ(tex.maxLayerWidth, 18);  // 3 · 2 features + 12 pass-through inputs
    EXPECT_EQ(tex.tableTexels, size_t(3 * 4096 * 2 / 4));
    auto texel = [&](size_t t) { return &tex.texels[4 * t]; };
    const size_t tree = size_t(tex.offsets[0][kSlotGlobal]);
    const size_t n = size_t(texel(tree + 1)[1]);  // the single leaf's network block
    EXPECT_EQ(texel(n)[0], 15.f);
    EXPECT_EQ(texel(n + 1)[0], 1.f);   // one component
    EXPECT_EQ(texel(n + 1)[1], 18.f);  // features
    EXPECT_EQ(texel(n + 1)[2], 12.f);  // pass-through inputs
    EXPECT_EQ(texel(n + 1)[3], 0.f);   // no derived inputs
    const size_t c = n + 2 + 2 * 4 + 2 * 1;  // after the header texels and the scalers (15 inputs, 3 outputs)
    EXPECT_EQ(std::vector<float>(texel(c), texel(c) + 4), (std::vector<float>{2.f, 3.f, 0.f, 6.f}));
    EXPECT_EQ(std::vector<float>(texel(c + 1), texel(c + 1) + 4), (std::vector<float>{0.f, 1.f, 2.f, 0.f}));
    const float* s = texel(c + 2);
    EXPECT_EQ(s[0], 3.f);
    EXPECT_EQ(s[1], 12.f);
    EXPECT_EQ(s[2], 2.f);
    // Resolutions 4, 8, 16: (res+1)^3 = 125, 729 fit 4096 entries, 4913 do not.
    EXPECT_EQ(std::vector<float>(texel(c + 3), texel(c + 3) + 4), (std::vector<float>{4.f, 1.f, 8.f, 1.f}));
    EXPECT_EQ(std::vector<float>(texel(c + 4), texel(c + 4) + 2), (std::vector<float>{16.f, 0.f}));
    // Pass-through indices 3 … 14.
    for (int q = 0; q < 12; ++q) EXPECT_EQ(texel(c + 5 + size_t(q / 4))[q % 4], float(3 + q));
    // The table: every parameter as a float, in order, from texel s[3].
    const size_t table = size_t(s[3]);
    EXPECT_GT(table, c + 8);
    for (Eigen::Index i = 0; i < m.encodingParams.size(); i += 997)
        EXPECT_EQ(tex.texels[4 * table + size_t(i)], float(m.encodingParams[i])) << i;
}

TEST(NetworkTextureEncodings, ReflectedInputIsFlaggedScaledAndMirrorsPredict) {
    // The diffuse box (15 record inputs) and the glossy one (19: the reflected rows fill slots 19–21
    // of the shader's 24), each with the reflected input raw, frequency-encoded and one-blob-encoded
    // together with the view.
    const Scene scenes[2] = {test::cornellBox(), loadScene(std::string(RRF_SOURCE_DIR) + "/projects/cornell-glossy/scene.json")};
    const char* encodings[] = {"[]", R"([{"type": "frequency", "inputs": "reflected", "frequencies": 4}])",
                               R"([{"type": "one_blob", "inputs": ["view", "reflected"], "bins": 8}])"};
    uint64_t seed = 71;
    for (const Scene& scene : scenes) {
        const RecordLayout layout = RecordLayout::forScene(scene);
        for (const char* e : encodings) {
            const ModelSet set = test::mixedModelSet(scene, Activation::Tanh, {12, 6}, seed++, json::parse(e), DerivedInputs{true});
            const NetworkTexture tex = packNetworkTexture(scene, set);
            auto texel = [&](size_t t) { return &tex.texels[4 * t]; };
            const size_t n = size_t(texel(size_t(tex.offsets[0][kSlotJoint]) + 1)[1]);  // object 0: a joint net
            EXPECT_EQ(texel(n)[0], float(layout.inputCount() + 3)) << "scaled inputs: the record's and the reflected";
            EXPECT_EQ(texel(n + 1)[3], 1.f) << "the reflected flag";
            test::TestRandom rnd(seed);
            size_t checked = 0;
            for (const ObjectNetworks& on : set.objects) {
                float brdf[8] = {};
                layout.brdfParameters(scene.materials[size_t(scene.objects[size_t(on.objectId)].material)], brdf);
                MatX<float> raw(layout.inputCount(), 60);
                for (int c = 0; c < raw.cols(); ++c) {
                    const Vec3 nn = rnd.unitVector();
                    Vec3 v = rnd.unitVector();
                    if (dot(v, nn) < 0.f) v = -v;
                    const Vec3 f[4] = {Vec3(rnd.range(-1, 1), rnd.range(-1, 1), rnd.range(-1, 1)), v, scene.lightPosition(), nn};
                    for (int k = 0; k < 12; ++k) raw(k, c) = f[k / 3][k % 3];
                    for (int k = 12; k < layout.inputCount(); ++k) raw(k, c) = brdf[k - 12];
                }
                const test::CpuTerms ref = test::cpuTerms(on, raw);
                const MatX<float>* r[3] = {&ref.direct, &ref.indirect, &ref.global};
                for (int c = 0; c < raw.cols(); ++c) {
                    const std::array<Vec3, 3> t = evaluateTerms(tex, on.objectId, &raw(0, c));
                    for (int term = 0; term < 3; ++term)
                        for (int ch = 0; ch < 3; ++ch) {
                            ASSERT_TRUE(test::closeEnough(t[size_t(term)][ch], (*r[term])(ch, c)))
                                << e << " object " << on.objectId << " term " << term << ": packed " << t[size_t(term)][ch]
                                << " vs predict " << (*r[term])(ch, c);
                            ++checked;
                        }
                }
            }
            EXPECT_GT(checked, 1000u);
        }
    }
}

TEST(NetworkTextureEncodings, TablesBeyondTheRowLimitAreRejected) {
    const Scene scene = test::cornellBox();
    // 16 levels of 2^16 entries with 2 features: 512 rows of 1024 texels per network.
    const json enc = json::parse(R"([{"type": "hash_grid", "inputs": "position", "levels": 16, "log2_table_size": 16,
                                      "features_per_level": 2, "base_resolution": 16, "growth": 1.5}])");
    const ModelSet set = single(featureProbe(scene, enc, {0, 1, 2}));
    EXPECT_NO_THROW(packNetworkTexture(scene, set, 256, 600));
    try {
        packNetworkTexture(scene, set, 256, 400);
        ADD_FAILURE() << "a texture of more than 400 rows was packed";
    } catch (const std::invalid_argument& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("hash-grid tables"), std::string::npos) << msg;
        EXPECT_NE(msg.find("log2_table_size"), std::string::npos) << msg;
        EXPECT_NE(msg.find("400"), std::string::npos) << msg;
    }
}

}  // namespace
}  // namespace rrf::test_network_texture_encodings
