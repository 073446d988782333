// The workbench's stored evaluation (app/gui/stored_evaluation_file.h, issue 29 item 7): the Objects table
// comes back exactly as it was for the same ground truth and model set, is stale (not shown) for
// another light or a retrained set, and a damaged file is a warning naming it, never a crash.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "app/gui/stored_evaluation_file.h"

namespace rrf::test::test_stored_evaluation {

namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("rrf_gui_eval_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

EvaluationSource source() {
    EvaluationSource s;
    s.key.sceneHash = 0x1234;
    s.key.cameraHash = 0x5678;
    s.key.lightPosition = Vec3(0.1f, 0.9f, 0.f);
    s.key.width = s.key.height = 64;
    s.models = "runs/train-1/models";
    s.modelsChecksum = "00000000deadbeef";
    return s;
}

panels::EvaluationInfo evaluation() {
    panels::EvaluationInfo e;
    e.valid = true;
    e.lightPosition = Vec3(0.1f, 0.9f, 0.f);
    e.referenceSpp = 64;
    e.referenceNoiseKnown = true;
    e.footprint.objectEdge = 7;
    e.seconds = 1.5;
    for (Term t : kTerms) {
        const int i = int(t);
        e.available[i] = t != Term::Direct;
        e.overall[i].pixels = 1000;
        e.overall[i].relativeRmse = 0.05 + i;
        for (int k = 0; k < 3; ++k) {
            panels::ObjectErrorRow row;
            row.objectId = k;
            row.name = "object " + std::to_string(k);
            row.stats.pixels = uint64_t(100 + k);
            row.stats.relativeRmse = 0.01 * (k + 1);
            row.stats.noiseKnown = true;
            row.stats.relativeRmseNoiseFloor = 0.001;
            row.stats.relativeRmseCorrected = 0.009 * (k + 1);
            row.flip = t == Term::Global ? 0.1 * k : std::nan("");
            row.samples = 500;
            row.trainSeconds = 0.25;
            e.rows[i].push_back(row);
        }
    }
    e.flipHdr = 0.2;
    e.spreadSpearmanPerObject = {{"object 0", 0.5}};
    return e;
}

}  // namespace

TEST(StoredEvaluation, ComesBackAsItWasForTheSameGroundTruthAndModels) {
    const fs::path dir = scratch("same");
    const std::string file = (dir / kEvaluationFile).string();
    storeEvaluation(file, evaluation(), source());
    const StoredEvaluation s = loadEvaluation(file, source());
    ASSERT_TRUE(s.info) << s.why;
    const panels::EvaluationInfo& e = *s.info;
    const panels::EvaluationInfo want = evaluation();
    EXPECT_TRUE(e.valid);
    EXPECT_EQ(e.referenceSpp, 64);
    EXPECT_EQ(e.footprint.objectEdge, 7u);
    for (Term t : kTerms) {
        const int i = int(t);
        EXPECT_EQ(e.available[i], want.available[i]);
        ASSERT_EQ(e.rows[i].size(), want.rows[i].size());
        for (size_t k = 0; k < e.rows[i].size(); ++k) {
            EXPECT_EQ(e.rows[i][k].name, want.rows[i][k].name);
            EXPECT_EQ(e.rows[i][k].stats.pixels, want.rows[i][k].stats.pixels);
            EXPECT_DOUBLE_EQ(e.rows[i][k].stats.relativeRmse, want.rows[i][k].stats.relativeRmse);
            EXPECT_DOUBLE_EQ(e.rows[i][k].stats.relativeRmseCorrected, want.rows[i][k].stats.relativeRmseCorrected);
            // Unknown figures stay unknown (NaN), never 0.
            EXPECT_EQ(std::isnan(e.rows[i][k].flip), std::isnan(want.rows[i][k].flip));
        }
    }
    EXPECT_DOUBLE_EQ(e.flipHdr, 0.2);
    EXPECT_TRUE(std::isnan(e.flipLdr));
    ASSERT_EQ(e.spreadSpearmanPerObject.size(), 1u);
}

TEST(StoredEvaluation, AnotherLightOrARetrainedSetIsStaleNotShown) {
    const fs::path dir = scratch("stale");
    const std::string file = (dir / kEvaluationFile).string();
    storeEvaluation(file, evaluation(), source());
    EvaluationSource moved = source();
    moved.key.lightPosition.x += 0.1f;
    StoredEvaluation s = loadEvaluation(file, moved);
    EXPECT_FALSE(s.info);
    EXPECT_FALSE(s.damaged);
    EXPECT_NE(s.why.find("light"), std::string::npos) << s.why;
    EvaluationSource retrained = source();
    retrained.modelsChecksum = "0000000000000001";
    s = loadEvaluation(file, retrained);
    EXPECT_FALSE(s.info);
    EXPECT_FALSE(s.damaged);
    EXPECT_NE(s.why.find("model set"), std::string::npos) << s.why;
}

TEST(StoredEvaluation, NothingStoredIsNoProblemAndADamagedFileIsNamed) {
    const fs::path dir = scratch("damaged");
    const std::string file = (dir / kEvaluationFile).string();
    StoredEvaluation s = loadEvaluation(file, source());
    EXPECT_FALSE(s.info);
    EXPECT_TRUE(s.why.empty());
    for (const std::string& text : {std::string("{\"format\": \"rrf-evaluation-1\""), std::string("[1, 2]"),
                                   std::string("{\"format\": \"rrf-evaluation-1\", \"key\": 3}")}) {
        std::ofstream(file, std::ios::trunc) << text;
        s = loadEvaluation(file, source());
        EXPECT_FALSE(s.info) << text;
        EXPECT_TRUE(s.damaged) << text;
        EXPECT_NE(s.why.find(file), std::string::npos) << s.why;
    }
    // A valid file with a row cut short names the member that is missing.
    storeEvaluation(file, evaluation(), source());
    std::ifstream in(file);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t at = text.find("\"train_seconds\"");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 15, "\"train_secs\"");
    std::ofstream(file, std::ios::trunc) << text;
    s = loadEvaluation(file, source());
    EXPECT_FALSE(s.info);
    EXPECT_TRUE(s.damaged);
    EXPECT_NE(s.why.find("train_secs"), std::string::npos) << s.why;
}

}  // namespace rrf::test::test_stored_evaluation
