#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "core/project/project_file.h"
#include "core/project/runs_json.h"
#include "core/project/scene_overrides_json.h"
#include "core/data/sampling_settings_json.h"
#include "core/nn/network_settings_json.h"
#include "core/nn/trainer_config_json.h"
#include "core/predict/prediction_settings_json.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/nn/encoding_settings_json.h"
#include "core/project/project.h"
#include "core/project/scene_edits.h"
#include "core/util/json_reader.h"

namespace test_project {

using namespace rrf;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const std::string kCornellDir = std::string(RRF_SOURCE_DIR) + "/projects/cornell-box";

/// A fresh directory per test so saved files never leak between tests.
std::string freshDir(const std::string& name) {
    const fs::path dir = fs::path(::testing::TempDir()) / "rrf_project_tests" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir.string();
}

std::string writeText(const std::string& path, const std::string& text) {
    std::ofstream(path) << text;
    return path;
}

std::string loadError(const std::string& path) {
    try {
        loadProjectOrScene(path);
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << path << " loaded although it is invalid";
    return "";
}

/// A small embedded scene that loads an OBJ file by relative path.
json embeddedScene() {
    return json::parse(R"({
      "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "fov_y": 45},
      "materials": {"grey": {"type": "lambert", "albedo": [0.5, 0.5, 0.5]}},
      "shapes": [{"type": "obj", "name": "pyramid", "material": "grey", "file": "mesh/pyramid.obj"}],
      "lights": [{"type": "point", "position": [0, 3, 0], "intensity": [1, 1, 1]}]
    })");
}

}  // namespace

TEST(Project, LoadsCornellProject) {
    const Project p = loadProjectOrScene(kCornellDir + "/project.json");
    EXPECT_EQ(p.sceneRef, "scene.json");
    EXPECT_EQ(p.render.spp, 64);
    EXPECT_EQ(p.render.estimator, Estimator::Auto);
    EXPECT_EQ(p.render.width, 0);
    EXPECT_EQ(p.scene.objects.size(), 7u);
    EXPECT_EQ(p.scene.sourcePath, kCornellDir + "/scene.json");
    EXPECT_EQ(p.name, "Cornell box");
    EXPECT_FALSE(p.sampling.has_value()) << "the file has no sampling section";
    EXPECT_FALSE(p.network.has_value()) << "the file has no network or trainer section";
    EXPECT_TRUE(p.warnings.empty());
}

TEST(Project, RoundTripKeepsUnknownSectionsAndRebasesSceneRef) {
    Project p = loadProjectOrScene(kCornellDir + "/project.json");
    NetworkSettings network;
    network.options.hidden = {20, 10};
    p.network = network;
    rrf::Run run;
    run.id = "3";
    run.metrics.rmse = 0.125;
    p.runs = {run};
    p.layout.root.fraction = 0.25f;
    p.render.spp = 256;
    p.render.estimator = Estimator::Naive;
    p.render.seed = 18446744073709551615ULL;
    p.render.exposure = -1.5f;
    p.render.width = 128;

    const std::string dir = freshDir("roundtrip");
    const std::string out = dir + "/sub/copy.json";
    fs::create_directories(dir + "/sub");
    saveProject(p, out);
    EXPECT_EQ(p.path, out);

    const std::string text = readFile(out);
    EXPECT_NE(text.find("\n  \"network\": {\n    \""), std::string::npos) << "expected 2-space indentation:\n" << text;
    for (const auto& entry : fs::directory_iterator(dir + "/sub"))
        EXPECT_EQ(entry.path().extension(), ".json") << "left behind: " << entry.path();

    const Project q = loadProjectOrScene(out);
    EXPECT_FALSE(fs::path(q.sceneRef).is_absolute()) << q.sceneRef;
    EXPECT_TRUE(fs::equivalent(fs::path(out).parent_path() / q.sceneRef, kCornellDir + "/scene.json")) << q.sceneRef;
    EXPECT_EQ(q.scene.objects.size(), 7u);
    EXPECT_EQ(q.render.spp, 256);
    EXPECT_EQ(q.render.estimator, Estimator::Naive);
    EXPECT_EQ(q.render.seed, 18446744073709551615ULL);
    EXPECT_FLOAT_EQ(q.render.exposure, -1.5f);
    EXPECT_EQ(q.render.width, 128);
    EXPECT_EQ(q.render.maxDepth, 64);
    ASSERT_TRUE(q.network.has_value());
    EXPECT_EQ(toJson(*q.network), toJson(*p.network));
    ASSERT_EQ(q.runs.size(), 1u);
    EXPECT_EQ(toJson(q.runs[0]), toJson(p.runs[0]));
    EXPECT_EQ(q.layout, p.layout);
    EXPECT_EQ(q.name, "Cornell box");
}

TEST(Project, BareSceneGetsDefaultSettings) {
    Project p = loadProjectOrScene(kCornellDir + "/scene.json");
    EXPECT_EQ(p.scene.objects.size(), 7u);
    EXPECT_EQ(p.sceneRef, "scene.json");
    EXPECT_EQ(p.render.spp, RenderSettings().spp);
    EXPECT_EQ(p.name, "scene");
    EXPECT_FALSE(p.sampling.has_value());
    // Saving over the scene file itself would destroy it.
    EXPECT_THROW(saveProject(p, kCornellDir + "/scene.json"), std::runtime_error);

    const std::string dir = freshDir("bare");
    saveProject(p, dir + "/project.json");
    const Project q = loadProjectOrScene(dir + "/project.json");
    EXPECT_EQ(q.scene.contentHash(), p.scene.contentHash());
}

TEST(Project, EmbeddedSceneRebasesObjPathsOnSave) {
    const std::string dir = freshDir("embedded");
    fs::create_directories(dir + "/a/mesh");
    fs::create_directories(dir + "/b");
    fs::copy_file(std::string(RRF_SOURCE_DIR) + "/tests/data/pyramid.obj", dir + "/a/mesh/pyramid.obj");
    const json doc = {{"rrf_project", 1}, {"scene", embeddedScene()}, {"trainer", {{"type", "lm"}}}};
    const std::string first = writeText(dir + "/a/project.json", doc.dump(2));

    Project p = loadProjectOrScene(first);
    EXPECT_TRUE(p.sceneRef.empty());
    EXPECT_EQ(p.scene.objects[0].primitiveCount(), 6u);
    saveProject(p, dir + "/b/moved.json");
    EXPECT_EQ(parseJsonText(p.sceneJson)["shapes"][0]["file"], "../a/mesh/pyramid.obj");

    const Project q = loadProjectOrScene(dir + "/b/moved.json");
    EXPECT_EQ(q.scene.contentHash(), p.scene.contentHash());
    EXPECT_FALSE(q.network.has_value()) << "the file has only a trainer section";
    ASSERT_TRUE(q.trainer.has_value());
    EXPECT_EQ(q.trainer->type, TrainerType::LevenbergMarquardt);
}

TEST(Project, EmbeddedSceneErrorsPointIntoProject) {
    const std::string dir = freshDir("embedded_error");
    json scene = embeddedScene();
    scene["materials"]["grey"]["albedo"] = "grey";
    const std::string path = writeText(dir + "/broken.json", json{{"rrf_project", 1}, {"scene", scene}}.dump());
    const std::string msg = loadError(path);
    EXPECT_NE(msg.find("broken.json: /scene/materials/grey/albedo: expected array of 3 numbers, got string"),
              std::string::npos)
        << msg;
}

TEST(Project, MissingSceneFile) {
    const std::string dir = freshDir("missing_scene");
    const std::string path = writeText(dir + "/p.json", R"({"rrf_project": 1, "scene": "nowhere.json"})");
    const std::string msg = loadError(path);
    EXPECT_NE(msg.find("p.json: /scene: cannot open scene file"), std::string::npos) << msg;
    EXPECT_NE(msg.find("nowhere.json"), std::string::npos) << msg;
}

TEST(Project, RenderSectionIsValidated) {
    const std::string dir = freshDir("render");
    const std::string scene = kCornellDir + "/scene.json";
    auto project = [&](const json& render) {
        return writeText(dir + "/r.json", json{{"rrf_project", 1}, {"scene", scene}, {"render", render}}.dump());
    };
    std::string msg = loadError(project({{"sppp", 4}}));
    EXPECT_NE(msg.find("r.json: /render/sppp: unknown key 'sppp'"), std::string::npos) << msg;
    msg = loadError(project({{"mode", "bidir"}}));
    EXPECT_NE(msg.find("r.json: /render/mode: unknown render mode 'bidir'"), std::string::npos) << msg;
    msg = loadError(project({{"spp", 0}}));
    EXPECT_NE(msg.find("r.json: /render/spp: integer 0 out of range"), std::string::npos) << msg;
    msg = loadError(project({{"seed", -1}}));
    EXPECT_NE(msg.find("r.json: /render/seed: expected non-negative integer"), std::string::npos) << msg;
}

TEST(Project, VersionAndKindAreChecked) {
    const std::string dir = freshDir("version");
    std::string msg = loadError(writeText(dir + "/v2.json", R"({"rrf_project": 2, "scene": "x.json"})"));
    EXPECT_NE(msg.find("v2.json: /rrf_project: unsupported project version 2"), std::string::npos) << msg;
    msg = loadError(writeText(dir + "/none.json", R"({"name": "neither"})"));
    EXPECT_NE(msg.find("none.json: neither a project"), std::string::npos) << msg;
    msg = loadError(writeText(dir + "/noversion.json", R"({"scene": "x.json"})"));
    EXPECT_NE(msg.find("noversion.json: missing required field 'rrf_project'"), std::string::npos) << msg;
}

namespace {
/// Writes a project with `sections` added to the Cornell box project and returns its path.
std::string cornellWith(const std::string& dir, const std::string& name, const json& sections) {
    json doc = {{"rrf_project", 1}, {"scene", kCornellDir + "/scene.json"}};
    for (auto it = sections.begin(); it != sections.end(); ++it) doc[it.key()] = it.value();
    return writeText(dir + "/" + name, doc.dump(2));
}
}  // namespace

TEST(Project, EveryTypedSectionAndUnknownSectionsSurviveARoundTrip) {
    const std::string dir = freshDir("typed_roundtrip");
    Project p = loadProjectOrScene(kCornellDir + "/project.json");
    p.name = "typed";
    SamplingSettings sampling;
    sampling.nx = 3;
    sampling.ny = 4;
    sampling.nz = 5;
    sampling.directions = 77;
    sampling.spp = 9;
    sampling.seed = 18446744073709551615ULL;
    sampling.fixedLight = true;
    sampling.estimator = Estimator::Naive;
    sampling.maxDepth = 7;
    p.sampling = sampling;
    NetworkSettings network;
    network.options.hidden = {8, 4, 2};
    network.options.activation = Activation::Relu;
    network.options.targets = TargetMode::Joint;
    network.options.inputs.reflected = true;
    network.options.encoding =
        encodingSettingsFromJson(json::parse(R"([{"type": "frequency", "inputs": "reflected", "frequencies": 2}])"));
    ObjectNetworkOverride tall;
    tall.hidden = std::vector<int>{16, 8};
    ObjectNetworkOverride floor;
    floor.inputs = DerivedInputs{false};
    floor.encoding = NetworkEncodingSettings{};
    network.options.perObject = {{"tall-box", tall}, {"floor", floor}};
    TrainerConfig trainer = TrainerConfig::projectDefault().withType("adam");
    trainer.adam.learningRate = 3e-3;
    trainer.adam.loss = AdamLoss::RelativeL2;
    p.network = network;
    p.trainer = trainer;
    p.prediction.direct = PredictionSettings::Direct::Exact;
    p.prediction.directSamples = 12;
    p.prediction.seed = 5;
    rrf::Run run;
    run.id = "train-1";
    run.kind = "train";
    run.loss = {{0, 1.0, 2.0, 0.5}};
    run.curves = {{0, "floor", "global", {{0, 1.0, 2.0, 0.5}}}};
    run.artifacts = {"runs/train-1/models/models.json"};
    run.extra = jsonText({{"future", true}});
    p.runs = {run};
    p.layout.root = PaneLayout::defaultRoot(0.4f, 0.2f);
    const Vec3 light = moveLight(p, Vec3(0.1f, 0.99f, -0.05f));
    Material white = p.scene.materials[0];
    white.kd = Vec3(0.5f, 0.4f, 0.3f);
    editMaterial(p, 0, white, true);
    json other = parseJsonText(p.otherSections);
    other["future_section"] = {{"kept", {1, 2, 3}}};
    p.otherSections = jsonText(other);

    const std::string path = dir + "/typed.json";
    saveProject(p, path);
    const Project q = loadProjectOrScene(path);
    EXPECT_TRUE(q.warnings.empty());
    EXPECT_EQ(q.name, "typed");
    ASSERT_TRUE(q.sampling.has_value());
    EXPECT_EQ(toJson(*q.sampling), toJson(sampling));
    ASSERT_TRUE(q.network.has_value());
    EXPECT_EQ(toJson(*q.network), toJson(network));
    EXPECT_EQ(q.network->options.perObject, network.options.perObject);
    EXPECT_EQ(q.network->options.choiceFor("floor").inputs, DerivedInputs{});
    EXPECT_EQ(q.network->options.choiceFor("tall-box").hidden, (std::vector<int>{16, 8}));
    EXPECT_TRUE(q.network->options.choiceFor("tall-box").inputs.reflected) << "the section's";
    ASSERT_TRUE(q.trainer.has_value());
    EXPECT_EQ(toJson(*q.trainer), toJson(trainer));
    EXPECT_EQ(toJson(q.trainerOrDefault()), toJson(trainer));
    EXPECT_EQ(toJson(q.prediction), toJson(p.prediction));
    ASSERT_EQ(q.runs.size(), 1u);
    EXPECT_EQ(toJson(q.runs[0]), toJson(run));
    EXPECT_EQ(q.layout, p.layout);
    EXPECT_EQ(toJson(q.overrides), toJson(p.overrides));
    EXPECT_FLOAT_EQ(q.scene.lightPosition().y, light.y);
    EXPECT_FLOAT_EQ(q.scene.materials[0].kd.x, 0.5f);
    EXPECT_EQ(q.scene.contentHash(), p.scene.contentHash()) << "the overrides are applied at load";
    EXPECT_EQ(q.otherSections, p.otherSections);
    EXPECT_EQ(q.render.spp, p.render.spp);
}

TEST(Project, EncodingIsWrittenAsItWasRead) {
    // Typed at load, the setting still writes the JSON it read: the keys the file left out stay out
    // (their defaults apply), a lone group keeps its spelling, and so do the objects' entries.
    const std::string dir = freshDir("encoding_spelling");
    const json encoding = json::parse(R"([{"type": "hash_grid", "inputs": ["position"], "levels": 4, "growth": 2.5},
                                           {"type": "one_blob", "inputs": "view"},
                                           {"type": "frequency", "inputs": ["light", "normal"], "include_input": false}])");
    const json entry = json::parse(R"([{"type": "one_blob", "inputs": ["normal"], "bins": 8}])");
    Project p = loadProjectOrScene(cornellWith(
        dir, "spelled.json", {{"network", {{"encoding", encoding}, {"objects", {{"floor", {{"encoding", entry}}}}}}}}));
    ASSERT_TRUE(p.network.has_value());
    const NetworkEncodingSettings& e = p.network->options.encoding;
    ASSERT_EQ(e.size(), 3u);
    EXPECT_EQ(std::get<HashGridSettings>(e[0].params).levels, 4);
    EXPECT_EQ(std::get<HashGridSettings>(e[0].params).log2TableSize, HashGridSettings().log2TableSize) << "a default";
    EXPECT_EQ(std::get<OneBlobSettings>(e[1].params).bins, OneBlobSettings().bins);
    EXPECT_FALSE(std::get<FrequencySettings>(e[2].params).includeInput);
    EXPECT_EQ(toJson(*p.network).at("encoding"), encoding);
    saveProject(p, dir + "/saved.json");
    const json saved = readJsonFile(dir + "/saved.json");
    EXPECT_EQ(saved.at("network").at("encoding"), encoding);
    EXPECT_EQ(saved.at("network").at("objects").at("floor").at("encoding"), entry);
}

TEST(Project, AbsentSectionsStayAbsentOnSave) {
    const std::string dir = freshDir("absent");
    Project p = loadProjectOrScene(kCornellDir + "/project.json");
    saveProject(p, dir + "/p.json");
    const json doc = json::parse(readFile(dir + "/p.json"));
    EXPECT_FALSE(doc.contains("sampling")) << "absent: the front ends' own defaults apply";
    EXPECT_FALSE(doc.contains("network"));
    EXPECT_FALSE(doc.contains("trainer"));
    EXPECT_FALSE(doc.contains("runs"));
    EXPECT_FALSE(doc.contains("scene_overrides"));
}

TEST(Project, NetworkWithoutTrainerStaysWithoutTrainerOnSave) {
    const std::string dir = freshDir("network_only");
    Project p = loadProjectOrScene(cornellWith(dir, "n.json", {{"network", {{"hidden", {8, 4}}}}}));
    ASSERT_TRUE(p.network.has_value());
    EXPECT_FALSE(p.trainer.has_value()) << "the file has no trainer section";
    EXPECT_EQ(p.networkOrDefault().options.hidden, (std::vector<int>{8, 4}));
    // The trainer in effect is the project default (README): Adam, relative L2, error goal 0.02, 600 epochs.
    const TrainerConfig t = p.trainerOrDefault();
    EXPECT_EQ(t.type, TrainerType::Adam);
    EXPECT_EQ(t.adam.loss, AdamLoss::RelativeL2);
    EXPECT_DOUBLE_EQ(t.adam.errorGoal, 0.02);
    EXPECT_EQ(t.adam.maxEpochs, 600);

    // An edit of the network section alone must not add a trainer section.
    NetworkSettings edited = p.networkOrDefault();
    edited.options.hidden = {6};
    p.network = edited;
    saveProject(p, dir + "/saved.json");
    const json doc = json::parse(readFile(dir + "/saved.json"));
    EXPECT_EQ(doc["network"]["hidden"], json::array({6}));
    EXPECT_FALSE(doc.contains("trainer")) << doc.dump(2);
    EXPECT_FALSE(loadProjectOrScene(dir + "/saved.json").trainer.has_value());
}

TEST(Project, TrainerWithoutNetworkStaysWithoutNetworkOnSave) {
    const std::string dir = freshDir("trainer_only");
    Project p = loadProjectOrScene(cornellWith(dir, "t.json", {{"trainer", {{"type", "adam"}, {"max_epochs", 7}}}}));
    EXPECT_FALSE(p.network.has_value());
    ASSERT_TRUE(p.trainer.has_value());
    EXPECT_EQ(p.trainerOrDefault().maxEpochs(), 7);
    saveProject(p, dir + "/saved.json");
    const json doc = json::parse(readFile(dir + "/saved.json"));
    EXPECT_FALSE(doc.contains("network")) << doc.dump(2);
    EXPECT_EQ(doc["trainer"]["max_epochs"], 7);
}

TEST(Project, SectionReadersNameTheirPointerBelowAnyBase) {
    // Section readers take the pointer of where the section sits, e.g. inside a run's settings.
    const json run = {{"network", {{"hidden", {0}}}}, {"trainer", {{"typo", 1}}}, {"sampling", {{"grid", {1, 2}}}}};
    const JsonReader settings(run, "p.json", "/runs/3/settings");
    auto message = [](auto read) {
        try {
            read();
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    std::string msg = message([&] { networkSettingsFromJson(settings.at("network")); });
    EXPECT_NE(msg.find("p.json: /runs/3/settings/network/hidden/0: integer 0 out of range"), std::string::npos) << msg;
    msg = message([&] { trainerConfigFromJson(settings.at("trainer")); });
    EXPECT_NE(msg.find("p.json: /runs/3/settings/trainer/typo: unknown key"), std::string::npos) << msg;
    msg = message([&] { samplingSettingsFromJson(settings.at("sampling")); });
    EXPECT_NE(msg.find("p.json: /runs/3/settings/sampling/grid: expected an array of 3 integers"), std::string::npos)
        << msg;
}

TEST(Project, SectionReadersKeepTheBaseForOmittedKeys) {
    SamplingSettings base;
    base.nx = 3;
    base.directions = 17;
    base.fixedLight = true;
    const json section = {{"spp", 5}};
    const SamplingSettings s = samplingSettingsFromJson(JsonReader(section, "script.json", "/2"), base);
    EXPECT_EQ(s.nx, 3);
    EXPECT_EQ(s.directions, 17);
    EXPECT_TRUE(s.fixedLight);
    EXPECT_EQ(s.spp, 5);

    NetworkSettings n;
    n.options.hidden = {9, 9};
    n.options.activation = Activation::Relu;
    const json targets = {{"targets", "joint"}};
    const NetworkSettings m = networkSettingsFromJson(JsonReader(targets, "script.json", "/3"), n);
    EXPECT_EQ(m.options.hidden, (std::vector<int>{9, 9}));
    EXPECT_EQ(m.options.activation, Activation::Relu);
    EXPECT_EQ(m.options.targets, TargetMode::Joint);
}

TEST(Project, SwitchingTheTrainerKeepsBothTrainersParameters) {
    TrainerConfig c;
    c.lm.maxEpochs = 40;
    c.adam.learningRate = 2e-3;
    const TrainerConfig adam = c.withType("adam");
    EXPECT_EQ(adam.type, TrainerType::Adam);
    EXPECT_EQ(adam.adam.learningRate, 2e-3);
    EXPECT_EQ(adam.maxEpochs(), AdamConfig().maxEpochs) << "Adam runs with its own epoch limit";
    const TrainerConfig back = adam.withType(TrainerType::LevenbergMarquardt);
    EXPECT_EQ(toJson(back), toJson(c)) << "switching back loses nothing";
    EXPECT_EQ(toJson(c.withType("lm")), toJson(c));
    EXPECT_THROW(c.withType("sgd"), SettingError);
}

TEST(Project, BadValueInEachSettingsSectionIsReportedAtLoad) {
    const std::string dir = freshDir("bad_sections");
    const std::pair<json, std::string> cases[] = {
        {{{"render", {{"max_depth", 0}}}}, "/render/max_depth: integer 0 out of range"},
        {{{"sampling", {{"grid", {4, 0, 4}}}}}, "/sampling/grid/1: integer 0 out of range"},
        {{{"sampling", {{"directions", "many"}}}}, "/sampling/directions: expected integer, got string"},
        {{{"sampling", {{"gird", {4, 4, 4}}}}}, "/sampling/gird: unknown key 'gird'"},
        {{{"network", {{"hidden", {20, 5000}}}}}, "/network/hidden/1: integer 5000 out of range [1, 4096]"},
        {{{"network", {{"activation", "sigmoid"}}}}, "/network/activation: expected one of \"tanh\", \"relu\""},
        {{{"trainer", {{"type", "adam"}, {"learning_rate", 0}}}}, "/trainer/learning_rate: value 0 out of range (0, 1000]"},
        {{{"trainer", {{"mu_decrease", 0.1}}}}, "/trainer/mu_decrease: unknown key 'mu_decrease'"},
        {{{"prediction", {{"direct", "magic"}}}}, "/prediction/direct: expected one of \"network\", \"exact\""},
        {{{"prediction", {{"direct_samples", 0}}}}, "/prediction/direct_samples: integer 0 out of range"},
        {{{"name", 3}}, "/name: expected string, got number"},
        // Derived inputs and per-object networks (nn/derived_inputs.h, nn/object_network_overrides.h).
        {{{"network", {{"inputs", {{"reflected", "yes"}}}}}}, "/network/inputs/reflected: expected true or false, got string"},
        {{{"network", {{"encoding", {{{"type", "one_blob"}, {"inputs", "reflected"}}}}}}},
         "/network/encoding/0/inputs: input group 'reflected' is not an input of this network"},
        {{{"network", {{"objects", {{"mirror", {{"hidden", {8}}}}}}}}},
         "/network/objects/mirror: no object named \"mirror\" in the scene (expected one of \"floor\", \"ceiling\""},
        {{{"network", {{"objects", {{"tall-box", {{"hiden", {8}}}}}}}}}, "/network/objects/tall-box/hiden: unknown key 'hiden' (allowed here: hidden, inputs, encoding)"},
        {{{"network", {{"objects", {{"tall-box", {{"hidden", {0}}}}}}}}},
         "/network/objects/tall-box/hidden/0: integer 0 out of range [1, 4096]"},
        {{{"network", {{"objects", {{"tall-box", {{"encoding", {{{"type", "one_blob"}, {"inputs", "reflected"}}}}}}}}}}},
         "/network/objects/tall-box/encoding/0/inputs: input group 'reflected' is not an input of this network"},
        {{{"network", {{"inputs", {{"reflected", true}}},
                       {"encoding", {{{"type", "one_blob"}, {"inputs", "reflected"}}}},
                       {"objects", {{"floor", {{"inputs", {{"reflected", false}}}}}}}}}},
         "/network/objects/floor/inputs: the section's \"encoding\" reads an input this entry turns off"},
        // The encoding setting is typed at load (nn/encoding_settings_json.h): unknown and mistyped keys
        // of a component are errors naming their pointer, in the section and in an "objects" entry.
        {{{"network", {{"encoding", {{{"type", "one_blob"}, {"inputs", "view"}, {"bin", 8}}}}}}},
         "/network/encoding/0/bin: unknown key 'bin'"},
        {{{"network", {{"encoding", {{{"type", "hash_grid"}, {"inputs", "position"}, {"levels", "many"}}}}}}},
         "/network/encoding/0/levels: expected integer, got string"},
        {{{"network", {{"encoding", {{{"type", "fourier"}, {"inputs", "view"}}}}}}},
         "/network/encoding/0/type: unknown encoding type 'fourier'"},
        {{{"network", {{"objects", {{"tall-box", {{"encoding", {{{"type", "frequency"}, {"inputs", "view"}, {"include_input", 1}}}}}}}}}}},
         "/network/objects/tall-box/encoding/0/include_input: expected true or false, got number"},
        {{{"network", {{"objects", {{"tall-box", {{"encoding", {{{"type", "one_blob"}, {"inputs", "view"}, {"levels", 4}}}}}}}}}}},
         "/network/objects/tall-box/encoding/0/levels: unknown key 'levels'"},
    };
    int i = 0;
    for (const auto& [sections, expected] : cases) {
        const std::string name = "bad" + std::to_string(i++) + ".json";
        const std::string msg = loadError(cornellWith(dir, name, sections));
        EXPECT_NE(msg.find(name + ": " + expected), std::string::npos) << msg;
    }
}

TEST(Project, DamagedWorkbenchSectionsAreWarningsNamingTheirPointer) {
    const std::string dir = freshDir("damaged_sections");
    const std::string path = cornellWith(
        dir, "d.json",
        {{"layout", {{"left", "wide"}}},
         {"runs", json::array({{{"id", "ok"}}, {{"id", "bad"}, {"loss", "none"}}})},
         {"scene_overrides", {{"light_position", {0, 1}}, {"materials", {{"white", {{"kd", {0.5, 0.5, 0.5}}}}}}}}});
    const Project p = loadProjectOrScene(path);
    ASSERT_EQ(p.runs.size(), 1u);
    EXPECT_EQ(p.runs[0].id, "ok");
    ASSERT_EQ(p.warnings.size(), 3u);
    EXPECT_NE(p.warnings[0].find("d.json: /runs/1/loss: expected array, got string"), std::string::npos) << p.warnings[0];
    EXPECT_NE(p.warnings[1].find("d.json: /layout/left: expected number, got string"), std::string::npos) << p.warnings[1];
    EXPECT_NE(p.warnings[2].find("d.json: /scene_overrides/light_position: expected array of 3 numbers"),
              std::string::npos)
        << p.warnings[2];
    EXPECT_FLOAT_EQ(p.layout.root.fraction, PaneLayout::kDefaultLeft);
    EXPECT_TRUE(p.overrides.materials.count("white")) << "the other overrides still apply";
    for (const Material& m : p.scene.materials)
        if (m.name == "white") {
            EXPECT_FLOAT_EQ(m.kd.x, 0.5f);
        }
}

TEST(SceneEdits, MoveLightClampsAndRecords) {
    Project p = loadProjectOrScene(kCornellDir + "/project.json");
    ASSERT_FALSE(p.scene.lightRegion.empty());
    const Vec3 used = moveLight(p, Vec3(100.f, 100.f, 100.f));
    EXPECT_TRUE(p.scene.lightRegion.contains(used));
    ASSERT_TRUE(p.overrides.lightPosition.has_value());
    EXPECT_FLOAT_EQ(p.overrides.lightPosition->x, p.scene.lightPosition().x);
    EXPECT_FLOAT_EQ(p.scene.lightPosition().x, used.x);
}

TEST(SceneEdits, EditMaterialEnforcesEnergyConservationAndRecords) {
    Project p = loadProjectOrScene(kCornellDir + "/project.json");
    Material m = p.scene.materials[0];
    m.kd = Vec3(0.9f);
    m.ks = Vec3(0.5f);
    m.exponent = 20.f;
    EXPECT_TRUE(editMaterial(p, 0, m, true)) << "kd + ks > 1 is limited";
    const Material& e = p.scene.materials[0];
    EXPECT_NEAR(e.ks.x, 0.1f, 1e-6f);
    EXPECT_EQ(e.type, Material::Type::Phong);
    const MaterialOverride& o = p.overrides.materials.at(e.name);
    EXPECT_NEAR(o.ks->y, 0.1f, 1e-6f);
    EXPECT_FLOAT_EQ(*o.exponent, 20.f);
    EXPECT_FALSE(editMaterial(p, 99, m, true)) << "no such material";
}

}  // namespace test_project
