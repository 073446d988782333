// CPU predictor with hand-built networks whose output is one of their inputs: the images must be
// exactly the expected inputs; target modes, missing networks, exact direct light, determinism.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "core/project/project_file.h"
#include "core/predict/prediction_settings_json.h"
#include "core/util/error.h"
#include "core/eval/evaluation.h"
#include "core/nn/ensemble.h"
#include "core/predict/footprint_mask.h"
#include "core/predict/predictor.h"
#include "core/util/json_reader.h"
#include "core/project/project.h"
#include "model_builders.h"

namespace test_predictor {

using namespace rrf;
using rrf::test::copyInputNet;

namespace {
const std::string kCornell = std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/project.json";

/// Every object gets the networks `make(objectId)` returns.
template <typename F>
ModelSet modelsFor(const Scene& s, F make) {
    ModelSet set;
    set.inputLayout = RecordLayout::forScene(s).inputs;
    for (const Object& o : s.objects) {
        ObjectNetworks n;
        n.objectId = o.id;
        n.name = o.name;
        for (auto& [target, net] : make(o.id)) n.byTarget.emplace(target, std::move(net));
        if (!n.byTarget.empty()) set.objects.push_back(std::move(n));
    }
    return set;
}

/// Every object: direct = light position (inputs 6..8), indirect = albedo (inputs 12..14).
ModelSet lightAndAlbedoModels(const Scene& s) {
    return modelsFor(s, [](int) {
        return std::map<std::string, NetworkModel>{{"direct", copyInputNet(15, {6, 7, 8})},
                                                   {"indirect", copyInputNet(15, {12, 13, 14})}};
    });
}

const Vec3 kLight(0.2f, 0.9f, -0.1f);

/// A "prediction" section as the project reader reads it.
PredictionSettings readPrediction(const nlohmann::json& section) {
    return predictionSettingsFromJson(JsonReader(section, "p.json", "/prediction"));
}

/// Direct light from the networks (the default is exact direct light): for the tests of the term rules.
PredictionSettings networkDirect() { return readPrediction({{"direct", "network"}}); }

}  // namespace

TEST(Predictor, CopyNetworksReproduceTheirInputsExactly) {
    const Project p = loadProjectOrScene(kCornell);
    const Scene& s = p.scene;
    const ModelSet models = lightAndAlbedoModels(s);
    const Predictor pred(s, models, networkDirect());
    const GBuffer g = pred.gbuffer(kLight, 64, 64);
    const Prediction out = pred.predict(g);
    EXPECT_TRUE(out.available[0] && out.available[1] && out.available[2]);
    EXPECT_EQ(out.nonFinite, 0u);
    EXPECT_TRUE(out.objectsWithoutNetwork.empty());
    size_t checked = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const size_t i = size_t(y) * 64 + size_t(x);
            if (g.covered(i)) {
                const Vec3 kd = s.materials[size_t(s.objects[size_t(g.object[i])].material)].kd;
                ASSERT_EQ(out.image(Term::Direct).at(x, y), kLight);
                ASSERT_EQ(out.image(Term::Indirect).at(x, y), kd);
                ASSERT_EQ(out.image(Term::Global).at(x, y), kLight + kd);
                ++checked;
            } else if (g.light[i] >= 0) {
                ASSERT_EQ(out.image(Term::Direct).at(x, y), g.emitted[i]);
                ASSERT_EQ(out.image(Term::Indirect).at(x, y), Vec3(0.f));
            } else {
                ASSERT_EQ(out.image(Term::Global).at(x, y), Vec3(0.f));
            }
        }
    EXPECT_GT(checked, 3000u);
    EXPECT_EQ(out.pixelsPredicted, checked);
}

TEST(Predictor, JointGlobalAndMissingNetworks) {
    const Project p = loadProjectOrScene(kCornell);
    const Scene& s = p.scene;
    // Object 0 (floor): joint net (direct = hit point, indirect = normal). Object 1: global only.
    // Others: nothing (black, counted).
    const ModelSet models = modelsFor(s, [](int id) {
        std::map<std::string, NetworkModel> m;
        if (id == 0) m["joint"] = copyInputNet(15, {0, 1, 2, 9, 10, 11});
        if (id == 1) m["global"] = copyInputNet(15, {3, 4, 5});
        return m;
    });
    const Predictor pred(s, models, networkDirect());
    const GBuffer g = pred.gbuffer(kLight, 48, 48);
    const Prediction out = pred.predict(g);
    EXPECT_TRUE(out.available[int(Term::Global)]);
    EXPECT_FALSE(out.available[int(Term::Direct)]);
    EXPECT_FALSE(out.available[int(Term::Indirect)]);
    EXPECT_EQ(out.unavailableWhy.size(), 2u);
    EXPECT_EQ(out.objectsWithoutNetwork.size(), s.objects.size() - 2);
    EXPECT_EQ(out.pixelsWithoutNetwork, g.pixelCount() - g.emitterPixels.size() - g.backgroundPixels -
                                            g.pixelsByObject[0].size() - g.pixelsByObject[1].size());
    for (uint32_t i : g.pixelsByObject[0]) {
        const int x = int(i % 48), y = int(i / 48);
        const float* r = g.input(i);
        ASSERT_EQ(out.image(Term::Direct).at(x, y), Vec3(r[0], r[1], r[2]));
        ASSERT_EQ(out.image(Term::Indirect).at(x, y), Vec3(r[9], r[10], r[11]));
    }
    for (uint32_t i : g.pixelsByObject[1]) {
        const float* r = g.input(i);
        ASSERT_EQ(out.image(Term::Global).at(int(i % 48), int(i / 48)), Vec3(r[3], r[4], r[5]));
    }
    for (uint32_t i : g.pixelsByObject[2]) ASSERT_EQ(out.image(Term::Global).at(int(i % 48), int(i / 48)), Vec3(0.f));
}

TEST(Predictor, BitIdenticalForAnyThreadCount) {
    const Project p = loadProjectOrScene(kCornell);
    const ModelSet models = modelsFor(p.scene, [](int) {
        NetworkModel m = copyInputNet(15, {0, 4, 8});
        for (Eigen::Index k = 0; k < m.params.size(); ++k) m.params[k] += 0.01 * double(k % 7);  // not exact any more
        return std::map<std::string, NetworkModel>{{"global", m}};
    });
    const Predictor pred(p.scene, models);
    Prediction one, two;
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        one = pred.predict(pred.gbuffer(kLight, 96, 80));
    }
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
        two = pred.predict(pred.gbuffer(kLight, 96, 80));
    }
    EXPECT_EQ(one.image(Term::Global).data, two.image(Term::Global).data);
}

TEST(Predictor, ExactDirectMatchesThePathTracersDirectLight) {
    Project p = loadProjectOrScene(kCornell);
    const Scene& s = p.scene;
    const ModelSet models = modelsFor(s, [](int) {
        return std::map<std::string, NetworkModel>{{"indirect", copyInputNet(15, {12, 13, 14})}};
    });
    PredictionSettings settings = readPrediction({{"direct", "exact"}, {"direct_samples", 32}});
    ASSERT_EQ(settings.direct, PredictionSettings::Direct::Exact);
    const Predictor pred(s, models, settings);
    const Prediction out = pred.predict(pred.gbuffer(kLight, 32, 32));
    EXPECT_TRUE(out.available[0] && out.available[1] && out.available[2]);
    RenderOptions ro;
    ro.width = ro.height = 32;
    ro.spp = 64;
    const Reference ref = renderReference(s, kLight, ro);
    // Compare the mean over the back wall's interior (no edge pixels): the box filter of the reference
    // and the pixel centres of the prediction agree there; 32 + 64 samples leave ~1% noise on a mean
    // over ~200 pixels.
    const GBuffer g = pred.gbuffer(kLight, 32, 32);
    double sp = 0, sr = 0;
    for (uint32_t i : g.pixelsByObject[2]) {
        const int x = int(i % 32), y = int(i / 32);
        bool interior = true;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                interior = interior && x + dx >= 0 && x + dx < 32 && y + dy >= 0 && y + dy < 32 &&
                           g.object[size_t(y + dy) * 32 + size_t(x + dx)] == 2;
        if (!interior) continue;
        sp += luminance(out.image(Term::Direct).at(x, y));
        sr += luminance(ref.image(Term::Direct).at(x, y));
    }
    ASSERT_GT(sr, 0.0);
    EXPECT_NEAR(sp / sr, 1.0, 0.03);
    // global = exact direct + predicted indirect.
    for (uint32_t i : g.pixelsByObject[2]) {
        const int x = int(i % 32), y = int(i / 32);
        const Vec3 sum = out.image(Term::Direct).at(x, y) + out.image(Term::Indirect).at(x, y);
        ASSERT_EQ(out.image(Term::Global).at(x, y), sum);
    }
}

TEST(Predictor, SettingsAreValidated) {
    EXPECT_THROW(readPrediction({{"direct", "magic"}}), InputError);
    EXPECT_THROW(readPrediction({{"direct_samples", 0}}), InputError);
    EXPECT_THROW(readPrediction({{"typo", 1}}), InputError);
    const Project p = loadProjectOrScene(kCornell);
    EXPECT_EQ(p.prediction.direct, PredictionSettings::Direct::Exact) << "exact direct light by default (issue 11)";
    // A network with the wrong number of inputs is refused up front, not at the first frame.
    const ModelSet bad = modelsFor(p.scene, [](int) {
        return std::map<std::string, NetworkModel>{{"global", copyInputNet(14, {0, 1, 2})}};
    });
    EXPECT_THROW(Predictor(p.scene, bad), std::invalid_argument);
}

TEST(Evaluation, FootprintPixelsAreLeftOutAndCounted) {
    // Reference = the copy networks' exact prediction, except that every pixel the footprint mask
    // leaves out (core/predict/footprint_mask.h) is off by 1000 — what the box-filtered ground truth
    // does at the light's edge. The errors must be exactly 0 and the left-out pixels counted, and
    // they include every silhouette of the older 4-neighbour object-id rule; a kept pixel off by 1
    // must show up.
    const Project p = loadProjectOrScene(kCornell);
    const Scene& s = p.scene;
    const ModelSet models = lightAndAlbedoModels(s);
    const Predictor pred(s, models, networkDirect());
    const int w = 48, h = 48;
    const GBuffer g = pred.gbuffer(kLight, w, h);
    const FootprintMask mask = footprintMask(g);
    const Prediction exact = pred.predict(g);
    Reference ref;
    ref.lightPosition = kLight;
    for (int t = 0; t < kTermCount; ++t) ref.images[t] = exact.images[t];
    uint64_t silhouettes = 0, leftOut = 0;
    int interiorX = -1, interiorY = -1;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            const int32_t id = g.object[i];
            if (id < 0) continue;
            bool edge = false;
            const int dx[4] = {-1, 1, 0, 0}, dy[4] = {0, 0, -1, 1};
            for (int k = 0; k < 4; ++k) {
                const int nx = x + dx[k], ny = y + dy[k];
                if (nx >= 0 && ny >= 0 && nx < w && ny < h && g.object[size_t(ny) * size_t(w) + size_t(nx)] != id) edge = true;
            }
            if (edge) {
                ++silhouettes;
                EXPECT_FALSE(mask.isKept(i)) << "silhouette pixel (" << x << ", " << y << ") kept";
            }
            if (!mask.isKept(i)) {
                ++leftOut;
                for (int t = 0; t < kTermCount; ++t) ref.images[t].set(x, y, ref.images[t].at(x, y) + Vec3(1000.f));
            } else if (interiorX < 0) {
                interiorX = x;
                interiorY = y;
            }
        }
    ASSERT_GT(silhouettes, 0u);
    ASSERT_GT(leftOut, silhouettes);  // creases of the boxes and pixels diagonal to the light besides
    ASSERT_GE(interiorX, 0);
    const Evaluation e = evaluate(pred, ref);
    EXPECT_EQ(e.footprint.counts.total(), leftOut);
    EXPECT_EQ(e.term(Term::Global).overall.pixels, g.pixelCount() - g.emitterPixels.size() - g.backgroundPixels - leftOut);
    EXPECT_EQ(e.term(Term::Global).overall.rmse, 0.0);
    EXPECT_EQ(e.term(Term::Global).overall.maxError, 0.0);

    ref.images[int(Term::Global)].set(interiorX, interiorY, ref.images[int(Term::Global)].at(interiorX, interiorY) + Vec3(1.f));
    const Evaluation moved = evaluate(pred, ref);
    EXPECT_GT(moved.term(Term::Global).overall.maxError, 0.99);
}

}  // namespace test_predictor

namespace test_predictor_spread {
using namespace rrf;

/// A merged ensemble of `k` members of 15-6-`outputs` tanh networks (identity scalers).
NetworkModel ensembleNet(int outputs, int k, uint64_t seed) {
    MlpArch member;
    member.inputs = 15;
    member.hidden = {6};
    member.outputs = outputs;
    std::vector<VecX<double>> p;
    for (int m = 0; m < k; ++m) p.push_back(initialParams(member, seed + uint64_t(m), 1));
    NetworkModel e;
    e.arch = ensembleArch(member, k);
    e.params = mergeEnsemble(member, p);
    e.memberOutputBias = memberOutputBiases(member, p);
    e.inputScaler = MinMaxScaler::identity(15);
    e.outputScaler = MinMaxScaler::identity(outputs);
    e.encoding.inputs = 15;
    e.training.members = k;
    return e;
}

TEST(Predictor, SpreadIsTheMembersDisagreementOnTheirObjectsPixelsOnly) {
    const Project proj = loadProjectOrScene(std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/project.json");
    const Scene& s = proj.scene;
    // Object 0: a joint ensemble of 3 with learned direct light (the spread of direct + indirect per
    // member); object 1: a single network (no spread); the others: nothing.
    ModelSet models;
    models.inputLayout = RecordLayout::forScene(s).inputs;
    for (int id : {0, 1}) {
        ObjectNetworks n;
        n.objectId = id;
        n.name = s.objects[size_t(id)].name;
        if (id == 0) n.byTarget.emplace("joint", ensembleNet(6, 3, 5));
        else n.byTarget.emplace("global", rrf::test::copyInputNet(15, {3, 4, 5}));
        models.objects.push_back(std::move(n));
    }
    const Predictor pred(s, models, predictionSettingsFromJson(JsonReader(nlohmann::json{{"direct", "network"}}, "p.json", "/prediction")));
    const GBuffer g = pred.gbuffer(Vec3(0.2f, 0.9f, -0.1f), 32, 32);
    const Prediction out = pred.predict(g);
    ASSERT_FALSE(out.spread.empty());
    EXPECT_EQ(out.spreadPixels, g.pixelsByObject[0].size());
    const PartitionedNetwork& joint = models.find(0)->byTarget.at("joint");
    for (uint32_t i : g.pixelsByObject[0]) {
        ASSERT_EQ(out.spreadKnown[i], 1);
        // By hand: every member's direct + indirect at this pixel, their standard deviation (1/K).
        const MatX<float> x = Eigen::Map<const MatX<float>>(g.input(i), 15, 1);
        const std::vector<MatX<float>> m = joint.predictMembers(x);
        ASSERT_EQ(m.size(), 3u);
        for (int c = 0; c < 3; ++c) {
            double sum = 0, sq = 0;
            for (const MatX<float>& y : m) {
                const double v = double(y(c, 0)) + double(y(c + 3, 0));
                sum += v;
                sq += v * v;
            }
            const double mean = sum / 3, sd = std::sqrt(std::max(0.0, sq / 3 - mean * mean));
            ASSERT_NEAR(out.spread.at(int(i % 32), int(i / 32))[c], sd, 1e-5);
        }
    }
    for (uint32_t i : g.pixelsByObject[1]) ASSERT_EQ(out.spreadKnown[i], 0);
    for (uint32_t i : g.emitterPixels) ASSERT_EQ(out.spreadKnown[i], 0);
    // A model set without members' outputs predicts no spread at all.
    ModelSet single;
    single.inputLayout = models.inputLayout;
    single.objects.push_back(models.objects[1]);
    EXPECT_TRUE(Predictor(s, single).predict(g).spread.empty());
}
}  // namespace test_predictor_spread
