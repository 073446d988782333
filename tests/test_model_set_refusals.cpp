// A model set refuses what it must not use: networks trained for another scene, networks whose
// input layout is not the scene's records', and sets with missing files. Every refusal is an error
// naming the file (and the JSON pointer where there is one), never a crash or a silently wrong image.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "core/data/dataset_file.h"
#include "core/data/record_layout.h"
#include "core/nn/model_set.h"
#include "core/nn/trainer_config_json.h"
#include "core/predict/predictor.h"
#include "core/util/error.h"
#include "scene_builders.h"
#include "tests/synthetic_samples.h"
#include "tests/training_builders.h"

namespace test_model_set_refusals {

using namespace rrf;
namespace fs = std::filesystem;

namespace {

constexpr uint64_t kHash = 0xC0FFEE0012345678ULL;

/// A saved set of one global network (object 0, 14 inputs) in a fresh directory.
struct SavedSet {
    fs::path dir;
    std::vector<std::string> layout;
    SavedSet() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = fs::temp_directory_path() / ("rrf_model_set_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
        fs::remove_all(dir);
        ObjectTrainingOptions o = test::plainTraining();
        o.hidden = {3};
        o.trainer = trainerConfigFromJson({{"type", "levenberg_marquardt"}, {"max_epochs", 2}});
        for (int i = 0; i < 14; ++i) layout.push_back("in" + std::to_string(i));
        saveModelSet(dir.string(), trainObjects({syntheticObject(0, 40)}, o), kHash, layout);
    }
    ~SavedSet() { fs::remove_all(dir); }
    std::string index() const { return (dir / "models.json").string(); }
    nlohmann::json readIndex() const { return nlohmann::json::parse(std::ifstream(index())); }
    /// Writes an edited index with its own checksum recomputed (docs/file-formats.md: checksum64 of the
    /// text with the field's 16 digits read as zeros), so the check under test is reached, not the
    /// index checksum.
    void writeIndex(nlohmann::json j) const {
        if (!j.contains("index_checksum64")) {
            std::ofstream(index()) << j.dump(1);
            return;
        }
        j["index_checksum64"] = std::string(16, '0');
        std::string text = j.dump(1);
        const std::string key = "\"index_checksum64\": \"";
        const size_t digits = text.find(key) + key.size();
        char sum[17];
        std::snprintf(sum, sizeof sum, "%016llx", static_cast<unsigned long long>(checksum64(text.data(), text.size())));
        text.replace(digits, 16, sum);
        std::ofstream(index()) << text;
    }
};

/// The message of the InputError that loading `dir` throws (a test failure if it loads or throws
/// anything else).
std::string loadError(const std::string& dir, uint64_t hash = 0) {
    try {
        loadModelSet(dir, hash);
        ADD_FAILURE() << dir << " loaded";
    } catch (const InputError& e) {
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "not an InputError: " << e.what();
    }
    return "";
}

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST(ModelSetRefusals, TheSetLoadsWhenNothingIsWrong) {
    const SavedSet s;
    const ModelSet set = loadModelSet(s.dir.string(), kHash);
    ASSERT_EQ(set.objects.size(), 1u);
    EXPECT_TRUE(set.objects[0].has("global"));
    EXPECT_EQ(set.inputLayout, s.layout);
    EXPECT_EQ(set.sceneHash, kHash);
}

TEST(ModelSetRefusals, AnotherScene) {
    const SavedSet s;
    const std::string e = loadError(s.dir.string(), kHash ^ 1);
    EXPECT_TRUE(has(e, s.index())) << e;
    EXPECT_TRUE(has(e, "/scene_hash")) << e;
    EXPECT_TRUE(has(e, "different scene")) << e;
    EXPECT_NO_THROW(loadModelSet(s.dir.string(), 0)) << "0 = any scene";
}

TEST(ModelSetRefusals, AnotherInputLayout) {
    const SavedSet s;
    // The index lists 13 inputs, the network has 14: the network file is named.
    nlohmann::json j = s.readIndex();
    j["input_layout"].erase(j["input_layout"].end() - 1);
    s.writeIndex(j);
    const std::string e = loadError(s.dir.string());
    EXPECT_TRUE(has(e, (s.dir / modelFileName(0, "global")).string())) << e;
    EXPECT_TRUE(has(e, "14 inputs")) << e;

    // A set whose layout is not the scene's is refused by prediction, before any pixel is computed.
    const Scene scene = test::cornellLike(1.f, 8);
    ModelSet set;
    set.dir = s.dir.string();
    set.inputLayout = RecordLayout::forScene(scene).inputs;
    std::swap(set.inputLayout.front(), set.inputLayout.back());
    try {
        const Predictor p(scene, set);
        ADD_FAILURE() << "a set with another input layout was accepted";
    } catch (const InputError& err) {
        EXPECT_TRUE(has(err.what(), "/input_layout")) << err.what();
        EXPECT_TRUE(has(err.what(), set.dir)) << err.what();
    }
}

TEST(ModelSetRefusals, MissingFiles) {
    {
        const SavedSet s;
        fs::remove(s.dir / modelFileName(0, "global"));
        const std::string e = loadError(s.dir.string());
        EXPECT_TRUE(has(e, (s.dir / modelFileName(0, "global")).string())) << e;
    }
    {
        const SavedSet s;
        fs::remove(s.index());
        const std::string e = loadError(s.dir.string());
        EXPECT_TRUE(has(e, s.index())) << e;
        EXPECT_TRUE(has(e, "no model index")) << e;
    }
    const std::string nowhere = (fs::temp_directory_path() / ("rrf_no_such_set_" + std::to_string(::getpid()))).string();
    EXPECT_TRUE(has(loadError(nowhere), nowhere));
}

TEST(ModelSetRefusals, IndexFromANewerBuild) {
    const SavedSet s;
    nlohmann::json j = s.readIndex();
    j["version"] = kModelSetVersion + 1;
    s.writeIndex(j);
    const std::string e = loadError(s.dir.string());
    EXPECT_TRUE(has(e, "/version")) << e;
    EXPECT_TRUE(has(e, s.index())) << e;
}

}  // namespace test_model_set_refusals
