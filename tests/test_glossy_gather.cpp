// Glossy gather (core/predict/glossy_gather.h): the gathered indirect light against the closed form
// of a Phong plane in a box of constant radiance, the switch, determinism, the project section.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "core/predict/glossy_gather.h"
#include "core/predict/prediction_settings_json.h"
#include "core/predict/predictor.h"
#include "core/project/project_file.h"
#include "core/util/error.h"
#include "core/project/project.h"
#include "core/util/json_reader.h"
#include "model_builders.h"
#include "scene_builders.h"

namespace test_glossy_gather {

using namespace rrf;
using namespace rrf::test;

namespace {
constexpr float kExponent = 200.f;
const Vec3 kFloorKd(0.2f, 0.25f, 0.3f), kFloorKs(0.5f, 0.4f, 0.3f), kWall(0.6f, 0.5f, 0.4f);

/// The closed cube [-1, 1]³: a Phong floor (object 0) and five white walls (object 1), lit by a
/// point light (no emitter for a gather ray to reach). The camera sits under the ceiling looking
/// straight down with a 4° field, so every pixel sees the floor within 2° of normal incidence.
Scene glossyFloorBox(int size) {
    Scene s;
    const int glossy = addPhong(s, kFloorKd, kFloorKs, kExponent, "glossy");
    const int white = addLambert(s, kWall, "white");
    std::vector<QuadSpec> faces = inwardCubeFaces(1.f);
    const QuadSpec floor = faces[2];
    faces.erase(faces.begin() + 2);
    addQuads(s, {floor}, glossy, "floor");
    addQuads(s, faces, white, "walls");
    addPointLight(s, Vec3(0.3f, 0.5f, 0.2f), Vec3(2.f));
    s.camera.eye = Vec3(0, 0.95f, 0);
    s.camera.target = Vec3(0, -1, 0);
    s.camera.up = Vec3(0, 0, -1);
    s.camera.fovYDegrees = 4.f;
    s.camera.width = s.camera.height = size;
    return s;
}

/// Every object: direct and indirect networks that both answer the albedo kd (BRDF inputs 12..14),
/// so the radiance leaving any wall towards anything is 2·kd exactly.
ModelSet albedoModels(const Scene& s) { return rrf::test::albedoModels(s, {"direct", "indirect"}); }

PredictionSettings settings(const nlohmann::json& section) {
    return predictionSettingsFromJson(JsonReader(section, "p.json", "/prediction"));
}
}  // namespace

// Under normal incidence ∫ ks (e+2)/(2π) cos^e α cosθ dω = ks (the lobe about the normal holds its
// energy) and ∫ kd/π cosθ dω = kd, so a floor that sees 2·kd_wall everywhere gathers
// 2·kd_wall·(kd + ks). The walls are Lambert: they keep their network's kd.
TEST(GlossyGather, PhongPlaneInABoxOfConstantRadianceGathersItsAlbedo) {
    const Scene s = glossyFloorBox(8);
    const ModelSet models = albedoModels(s);
    const Predictor pred(s, models, settings({{"direct", "network"}, {"gather", {{"min_exponent", 50}}}}));
    const GBuffer g = pred.gbuffer(s.lightPosition(), 8, 8);
    const Prediction out = pred.predict(g);
    EXPECT_EQ(out.nonFinite, 0u);
    EXPECT_EQ(out.pixelsGathered, g.pixelsByObject[0].size());
    ASSERT_EQ(g.pixelsByObject[0].size(), 64u);
    const Vec3 expected = 2.f * kWall * (kFloorKd + kFloorKs);
    for (uint32_t i : g.pixelsByObject[0]) {
        const Vec3 got = out.image(Term::Indirect).at(int(i % 8), int(i / 8));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 3e-3 * expected[c]) << "pixel " << i << " channel " << c;
        EXPECT_EQ(out.image(Term::Global).at(int(i % 8), int(i / 8)), kFloorKd + got);
    }
}

// The second bounce: the walls gathered by name (Lambert, kd = c like the floor's), so a floor ray
// lands on a wall that gathers again, whose own rays land where the networks answer 2c. A wall then
// sends c (its direct network) + c·2c (its gathered indirect light) and the floor gathers
// (kd + ks)·(c + 2c²).
TEST(GlossyGather, SecondBounceGathersAgainWhereTheFirstLands) {
    Scene s = glossyFloorBox(4);
    const float c = 0.5f;
    s.materials[0].kd = Vec3(c);
    s.materials[1].kd = Vec3(c);
    const ModelSet models = albedoModels(s);
    const Predictor pred(s, models, settings({{"direct", "network"}, {"gather", {{"objects", {"walls"}}}}}));
    const GBuffer g = pred.gbuffer(s.lightPosition(), 4, 4);
    const Prediction out = pred.predict(g);
    const Vec3 expected = (Vec3(c) + kFloorKs) * (c + 2.f * c * c);
    for (uint32_t i : g.pixelsByObject[0]) {
        const Vec3 got = out.image(Term::Indirect).at(int(i % 4), int(i / 4));
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(got[ch], expected[ch], 3e-3 * expected[ch]);
    }
    // Without the second bounce the walls' rays answer their networks: (kd + ks)·2c.
    const Predictor once(s, models,
                         settings({{"direct", "network"},
                                   {"gather", {{"objects", {"walls"}}, {"second_lobe_samples", 0}, {"second_diffuse_samples", 0}}}}));
    const Prediction flat = once.predict(g);
    const Vec3 one = (Vec3(c) + kFloorKs) * (2.f * c);
    for (uint32_t i : g.pixelsByObject[0])
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(flat.image(Term::Indirect).at(int(i % 4), int(i / 4))[ch], one[ch], 3e-3 * one[ch]);
}

// More pixels than one batch (the secondary buffer's rows, batch seeds): the closed form still holds.
TEST(GlossyGather, ManyBatchesKeepTheClosedForm) {
    const Scene s = glossyFloorBox(96);
    const ModelSet models = albedoModels(s);
    const Predictor pred(s, models, settings({{"direct", "network"}}));
    const GBuffer g = pred.gbuffer(s.lightPosition(), 96, 96);
    const Prediction out = pred.predict(g);
    ASSERT_GT(out.pixelsGathered * 128u, uint64_t(1) << 18) << "the test must span several batches";
    const Vec3 expected = 2.f * kWall * (kFloorKd + kFloorKs);
    for (uint32_t i : g.pixelsByObject[0]) {
        const Vec3 got = out.image(Term::Indirect).at(int(i % 96), int(i / 96));
        for (int ch = 0; ch < 3; ++ch) ASSERT_NEAR(got[ch], expected[ch], 3e-3 * expected[ch]) << "pixel " << i;
    }
}

// Only the lobe's term, only the diffuse term: each lobe is sampled on its own, so each term alone
// is its part of the albedo.
TEST(GlossyGather, EachLobeGathersItsOwnPart) {
    const Scene s = glossyFloorBox(4);
    const ModelSet models = albedoModels(s);
    for (const bool lobeOnly : {true, false}) {
        const Predictor pred(s, models,
                             settings({{"direct", "network"},
                                       {"gather", {{"lobe_samples", lobeOnly ? 32 : 0}, {"diffuse_samples", lobeOnly ? 0 : 32}}}}));
        const GBuffer g = pred.gbuffer(s.lightPosition(), 4, 4);
        const Prediction out = pred.predict(g);
        const Vec3 expected = 2.f * kWall * (lobeOnly ? kFloorKs : kFloorKd);
        for (uint32_t i : g.pixelsByObject[0]) {
            const Vec3 got = out.image(Term::Indirect).at(int(i % 4), int(i / 4));
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 3e-3 * expected[c]) << (lobeOnly ? "lobe" : "diffuse");
        }
    }
}

// Below the threshold (or with "min_exponent": 0) nothing is gathered and the images are the
// networks' own; the walls' pixels never change.
TEST(GlossyGather, ThresholdAndSwitch) {
    const Scene s = glossyFloorBox(8);
    const ModelSet models = albedoModels(s);
    const Predictor off(s, models, settings({{"direct", "network"}, {"gather", {{"min_exponent", 0}}}}));
    const Predictor above(s, models, settings({{"direct", "network"}, {"gather", {{"min_exponent", 201}}}}));
    const Predictor on(s, models, settings({{"direct", "network"}}));
    const GBuffer g = off.gbuffer(s.lightPosition(), 8, 8);
    const Prediction a = off.predict(g), b = above.predict(g), c = on.predict(g);
    EXPECT_EQ(a.pixelsGathered, 0u);
    EXPECT_EQ(b.pixelsGathered, 0u);
    EXPECT_GT(c.pixelsGathered, 0u);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            EXPECT_EQ(a.image(Term::Indirect).at(x, y), b.image(Term::Indirect).at(x, y));
            if (g.object[size_t(y) * 8 + size_t(x)] == 0) {
                EXPECT_EQ(a.image(Term::Indirect).at(x, y), kFloorKd);
            }
        }
}

// Exact direct light at the secondary points, the second bounce and any thread count: the same image.
TEST(GlossyGather, SameImageForAnyThreadCount) {
    const Scene s = glossyFloorBox(12);
    const ModelSet models = albedoModels(s);
    const Predictor pred(s, models, settings({{"gather", {{"lobe_samples", 16}, {"diffuse_samples", 8}}}}));
    const GBuffer g = pred.gbuffer(s.lightPosition(), 12, 12);
    Prediction one, two;
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        one = pred.predict(g);
    }
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
        two = pred.predict(g);
    }
    EXPECT_GT(one.pixelsGathered, 0u);
    for (int t = 0; t < kTermCount; ++t)
        for (int y = 0; y < 12; ++y)
            for (int x = 0; x < 12; ++x) ASSERT_EQ(one.images[t].at(x, y), two.images[t].at(x, y));
}

TEST(GlossyGather, SectionReadsWritesAndRefuses) {
    const PredictionSettings d;
    EXPECT_TRUE(d.gather.on());
    const PredictionSettings r = settings(toJson(d));
    EXPECT_EQ(toJson(r), toJson(d));
    const PredictionSettings s = settings({{"gather", {{"min_exponent", 0}}}});
    EXPECT_FALSE(s.gather.on());
    EXPECT_TRUE(settings({{"gather", {{"min_exponent", 0}, {"objects", {"walls"}}}}}).gather.on()) << "named objects";
    EXPECT_THROW(settings({{"gather", {{"lobe", 3}}}}), InputError);
    EXPECT_THROW(settings({{"gather", {{"lobe_samples", -1}}}}), InputError);
    EXPECT_THROW(settings({{"gather", {{"min_exponent", "high"}}}}), InputError);
    try {
        settings({{"gather", {{"diffuse_samples", 1e9}}}});
        FAIL() << "expected an InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("/prediction/gather/diffuse_samples"), std::string::npos) << e.what();
    }
}

}  // namespace test_glossy_gather

namespace test_glossy_gather {

// "objects" gathers a diffuse receiver by name; the project refuses a name the scene lacks.
TEST(GlossyGather, NamedObjectsAreGatheredAndCheckedAgainstTheScene) {
    const Scene s = glossyFloorBox(4);
    const PredictionSettings named = settings({{"gather", {{"min_exponent", 0}, {"objects", {"walls"}}}}});
    EXPECT_FALSE(GlossyGather::gathers(s, s.objects[0], named)) << "the exponent rule is off";
    EXPECT_TRUE(GlossyGather::gathers(s, s.objects[1], named));
    EXPECT_TRUE(gatherApplies(s, named));
    EXPECT_FALSE(gatherApplies(s, settings({{"gather", {{"min_exponent", 0}}}})));
    // With networks: an object with only a global network keeps it (nothing to add gathered light to).
    ModelSet models = albedoModels(s);
    EXPECT_EQ(gatheredObjects(s, models, named), std::vector<int>{1});
    models.objects[1].byTarget.clear();
    models.objects[1].byTarget.emplace("global", rrf::test::copyInputNet(RecordLayout::forScene(s).inputCount(), {12, 13, 14}));
    EXPECT_TRUE(gatheredObjects(s, models, named).empty());

    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / "rrf_glossy_gather_tests";
    fs::create_directories(dir);
    fs::copy_file(fs::path(RRF_SOURCE_DIR) / "projects/cornell-glossy/scene.json", dir / "scene.json",
                  fs::copy_options::overwrite_existing);
    std::ofstream(dir / "project.json") << R"({"rrf_project": 1, "scene": "scene.json",
        "prediction": {"gather": {"objects": ["ceiling", "celing"]}}})";
    try {
        loadProjectOrScene((dir / "project.json").string());
        FAIL() << "expected an InputError";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("/prediction/gather/objects/1"), std::string::npos) << what;
        EXPECT_NE(what.find("celing"), std::string::npos) << what;
        EXPECT_NE(what.find("project.json"), std::string::npos) << what;
    }
    std::ofstream(dir / "project.json") << R"({"rrf_project": 1, "scene": "scene.json",
        "prediction": {"gather": {"objects": ["ceiling"]}}})";
    const Project p = loadProjectOrScene((dir / "project.json").string());
    ASSERT_EQ(p.prediction.gather.objects, std::vector<std::string>{"ceiling"});
    int gathered = 0;
    for (const Object& o : p.scene.objects) gathered += GlossyGather::gathers(p.scene, o, p.prediction);
    EXPECT_EQ(gathered, 3) << "ceiling by name, short and tall box by exponent";
    fs::remove_all(dir);
}

}  // namespace test_glossy_gather
