// The packed network texture (core/predict/network_texture.h) without GL: the layout read back by the CPU
// mirror of the shader must reproduce NetworkModel::predict, and models that do not fit the scene
// must be rejected with a message.

#include <gtest/gtest.h>

#include "core/predict/network_texture.h"
#include "tests/gl/test_models.h"

namespace rrf::test_network_texture {
namespace {

using test::closeEnough;

void expectMirrorMatchesPredict(const Scene& scene, const ModelSet& set) {
    const NetworkTexture tex = packNetworkTexture(scene, set);
    const RecordLayout layout = RecordLayout::forScene(scene);
    test::TestRandom rnd(3);
    const Bounds3 b = scene.bounds();
    int checked = 0;
    for (const ObjectNetworks& on : set.objects) {
        float brdf[8] = {};
        layout.brdfParameters(scene.materials[size_t(scene.objects[size_t(on.objectId)].material)], brdf);
        const int n = 200;
        MatX<float> raw(layout.inputCount(), n);
        for (int c = 0; c < n; ++c) {
            const Vec3 f[4] = {Vec3(rnd.range(b.lo.x, b.hi.x), rnd.range(b.lo.y, b.hi.y), rnd.range(b.lo.z, b.hi.z)),
                               rnd.unitVector(), scene.lightPosition(), rnd.unitVector()};
            for (int k = 0; k < 12; ++k) raw(k, c) = f[k / 3][k % 3];
            for (int k = 12; k < layout.inputCount(); ++k) raw(k, c) = brdf[k - 12];
        }
        const test::CpuTerms ref = test::cpuTerms(on, raw);
        for (int c = 0; c < n; ++c) {
            const std::array<Vec3, 3> t = evaluateTerms(tex, on.objectId, &raw(0, c));
            const MatX<float>* r[3] = {&ref.direct, &ref.indirect, &ref.global};
            for (int term = 0; term < 3; ++term)
                for (int ch = 0; ch < 3; ++ch) {
                    ASSERT_TRUE(closeEnough(t[size_t(term)][ch], (*r[term])(ch, c)))
                        << "object " << on.objectId << " term " << term << " sample " << c << ": packed "
                        << t[size_t(term)][ch] << " vs predict " << (*r[term])(ch, c);
                    ++checked;
                }
        }
    }
    EXPECT_GT(checked, 0);
}

TEST(NetworkTexture, HeaderObjectTableAndOffsets) {
    const Scene scene = test::cornellBox();
    const ModelSet set = test::mixedModelSet(scene);
    const NetworkTexture tex = packNetworkTexture(scene, set);
    ASSERT_EQ(tex.width, kNetworkTextureWidth);
    ASSERT_EQ(tex.texels.size(), 4 * tex.texelCount());
    EXPECT_EQ(tex.texels[0], float(kNetworkTextureVersion));
    EXPECT_EQ(tex.texels[1], float(scene.objects.size()));
    EXPECT_EQ(tex.texels[2], 15.f);  // Lambert-only: 12 + kd
    EXPECT_EQ(tex.texels[3], 20.f);  // widest layer: the 20-neuron hidden layer
    // Object 2 has only a global net, object 4 no direct one, object 5 only a direct one.
    EXPECT_FALSE(tex.termAvailable[0] || tex.termAvailable[1] || tex.termAvailable[2]);
    const std::array<bool, 3> expected[7] = {{true, true, true},   {true, true, true},  {false, false, true},
                                             {true, true, true},   {false, true, true}, {true, false, false},
                                             {true, true, true}};
    for (int o = 0; o < 7; ++o) EXPECT_EQ(tex.provides[size_t(o)], expected[o]) << "object " << o;
    int networks = 0;
    for (const ObjectNetworks& on : set.objects) {
        const float* entry = &tex.texels[4 * (1 + 3 * size_t(on.objectId))];
        const char* names[4] = {"direct", "indirect", "global", "joint"};
        for (int s = 0; s < 4; ++s) {
            EXPECT_EQ(on.has(names[s]), entry[s] >= 0.f) << on.objectId << " " << names[s];
            EXPECT_EQ(int(entry[s]), tex.offsets[size_t(on.objectId)][size_t(s)]);
            if (entry[s] < 0.f) continue;
            ++networks;
            // The entry points at the model's tree block: one node, a leaf naming its network block.
            const NetworkModel& m = on.byTarget.at(names[s]).leaves[0];
            const float* tree = &tex.texels[4 * size_t(entry[s])];
            EXPECT_EQ(tree[0], 1.f);
            EXPECT_EQ(tree[1], 1.f);
            EXPECT_EQ(tree[4], -1.f);
            const float* h = &tex.texels[4 * size_t(tree[5])];
            EXPECT_EQ(h[0], float(m.arch.inputs));
            EXPECT_EQ(h[1], float(m.arch.outputs));
            EXPECT_EQ(h[2], float(m.arch.numLayers()));
            EXPECT_EQ(h[3], 0.f);  // tanh
        }
        // BRDF parameters: kd of the object's material, zero-padded.
        const Vec3 kd = scene.materials[size_t(scene.objects[size_t(on.objectId)].material)].kd;
        EXPECT_EQ(entry[4], kd.x);
        EXPECT_EQ(entry[5], kd.y);
        EXPECT_EQ(entry[6], kd.z);
        EXPECT_EQ(entry[7], 0.f);
    }
    EXPECT_EQ(networks, tex.networkCount);
}

TEST(NetworkTexture, MirrorOfShaderMatchesPredictTanh) {
    const Scene scene = test::cornellBox();
    expectMirrorMatchesPredict(scene, test::mixedModelSet(scene));
}

TEST(NetworkTexture, MirrorOfShaderMatchesPredictPartitioned) {
    // Three-leaf kd-trees: the mirror walks the tree block as the shader does (hit x splits at 0; the
    // light sits just below the light-x plane, so leaves 0 and 1 are used).
    const Scene scene = test::cornellBox();
    const ModelSet set = test::partitionedModelSet(scene, 0.f, scene.lightPosition().x + 0.01f);
    EXPECT_EQ(packNetworkTexture(scene, set).networkCount, 33);
    expectMirrorMatchesPredict(scene, set);
}

TEST(NetworkTexture, MirrorOfShaderMatchesPredictReluOddWidths) {
    // Widths that are not multiples of 4 exercise the zero padding of rows, biases and scalers.
    const Scene scene = test::cornellBox();
    expectMirrorMatchesPredict(scene, test::mixedModelSet(scene, Activation::Relu, {7, 13, 5}, 11));
}

TEST(NetworkTexture, ObjectsWithoutNetworksAndEmptySet) {
    const Scene scene = test::cornellBox();
    const NetworkTexture tex = packNetworkTexture(scene, ModelSet{});
    EXPECT_EQ(tex.networkCount, 0);
    EXPECT_FALSE(tex.termAvailable[0] || tex.termAvailable[1] || tex.termAvailable[2]);
    const float in[12] = {0, 0, 0, 0, 0, 1, 0, 0.9f, 0, 0, 0, 1};
    for (const Vec3& t : evaluateTerms(tex, 0, in)) EXPECT_TRUE(t.isZero());
}

TEST(NetworkTexture, RejectsModelsThatDoNotFitTheScene) {
    const Scene scene = test::cornellBox();
    auto expectThrow = [&](ModelSet set, const std::string& needle) {
        try {
            packNetworkTexture(scene, set);
            ADD_FAILURE() << "expected an error mentioning '" << needle << "'";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
        }
    };
    ModelSet base = test::mixedModelSet(scene);

    ModelSet badId = base;
    badId.objects[0].objectId = int(scene.objects.size());
    expectThrow(badId, "not an object of the scene");

    ModelSet badInputs = base;
    Scene phong = scene;  // 19 inputs: networks for the 15-input scene no longer fit
    phong.materials[0].type = Material::Type::Phong;
    phong.materials[0].kd = Vec3(0.4f);
    phong.materials[0].ks = Vec3(0.3f);
    try {
        packNetworkTexture(phong, base);
        ADD_FAILURE() << "15-input networks accepted for a 19-input scene";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("inputs"), std::string::npos) << e.what();
    }

    ModelSet badJoint = base;
    badJoint.objects[0].byTarget["joint"] = test::randomNetwork(scene, 0, "global", {4}, Activation::Tanh, 1);
    expectThrow(badJoint, "outputs, expected 6");

    ModelSet wide = base;
    wide.objects[1].byTarget["direct"] = test::randomNetwork(scene, 1, "direct", {300}, Activation::Tanh, 1);
    expectThrow(wide, "wider than");

    ModelSet nonFinite = base;
    nonFinite.objects[2].byTarget.begin()->second.leaves[0].params[0] = NAN;
    expectThrow(nonFinite, "non-finite");

    EXPECT_THROW(packNetworkTexture(scene, base, 256, 1), std::invalid_argument);  // one row is too few
}

}  // namespace
}  // namespace rrf::test_network_texture
