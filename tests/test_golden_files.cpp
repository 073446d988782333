// Golden known-answer files (tests/data/golden/): a small dataset (.rrfd) and a small model (.rrfm)
// checked into the repository. A round trip cannot see a format that silently changes (writer and
// reader agreeing on new bytes, old files no longer loading); these files can. The dataset must be
// written byte for byte again; the model must decode to its known values (the model file's header
// may gain fields, so only its decoded values are pinned).
//
// After a deliberate format change, regenerate both files with the current build and commit them:
//
//     RRF_WRITE_GOLDEN=1 build/rrf_tests --gtest_filter='GoldenFiles.*'

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>

#include "core/data/dataset_file.h"
#include "core/nn/model.h"
#include "core/nn/training_samples.h"

namespace test_golden_files {

using namespace rrf;
namespace fs = std::filesystem;

namespace {

const std::string kGoldenDir = std::string(RRF_SOURCE_DIR) + "/tests/data/golden";
constexpr uint64_t kGoldenSceneHash = 0x0123456789ABCDEFULL;

bool writeGolden() {
    const char* v = std::getenv("RRF_WRITE_GOLDEN");
    return v && std::string(v) == "1";
}

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

fs::path scratchDir() {
    const fs::path d = fs::temp_directory_path() / ("rrf_golden_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

// ---- the dataset: 2 inputs, direct RGB, indirect RGB; object 3 "lamp" (2 records), 5 "table" (1) --

nlohmann::json goldenDatasetHeader() {
    return {{"format", "rrf-dataset"},
            {"settings", {{"spp", 16}, {"seed", 1}}},
            {"shard", {{"index", 0}, {"count", 1}, {"cell_begin", 0}, {"cell_end", 4}, {"cells_total", 4}}},
            {"stats", {{"records", 3}}},
            {"input_layout", {"u", "v"}},
            {"target_layout", {"direct_r", "direct_g", "direct_b", "indirect_r", "indirect_g", "indirect_b"}},
            {"floats_per_record", 8},
            {"objects", {{{"id", 3}, {"name", "lamp"}}, {{"id", 5}, {"name", "table"}}}}};
}

/// Records of 8 floats (u, v, direct RGB, indirect RGB), every value exact in binary; direct and
/// indirect differ in every record, so reading one for the other shows.
const std::vector<std::vector<float>>& goldenRecords() {
    static const std::vector<std::vector<float>> r = {
        {0.25f, -0.5f, 1.5f, 1.25f, 1.f, 0.125f, 0.0625f, 0.03125f,  //
         0.75f, 0.5f, 2.5f, 2.25f, 2.f, 0.375f, 0.1875f, 0.09375f},
        {-1.f, 1.f, 0.5f, 0.5f, 0.5f, 4.f, 3.f, 2.f}};
    return r;
}

// ---- the model: 2 inputs, one hidden layer of 3 tanh units, 2 outputs (P = 9 + 8 = 17) -------------

NetworkModel goldenModel() {
    NetworkModel m;
    m.arch.inputs = 2;
    m.arch.hidden = {3};
    m.arch.outputs = 2;
    m.params.resize(m.arch.numParams());
    for (Eigen::Index i = 0; i < m.params.size(); ++i) m.params[i] = (i % 2 ? -0.125 : 0.25) * double(i + 1) / 8.0;
    m.inputScaler.offset = (VecX<double>(2) << 0.5, -1.0).finished();
    m.inputScaler.scale = (VecX<double>(2) << 2.0, 0.25).finished();
    m.outputScaler.offset = (VecX<double>(2) << 3.0, 0.125).finished();
    m.outputScaler.scale = (VecX<double>(2) << 0.5, 4.0).finished();
    m.objectId = 3;
    m.objectName = "lamp";
    m.target = "direct";
    m.training.epochs = 2;
    m.training.bestEpoch = 1;
    m.training.stopReason = "maximum epoch reached";
    m.training.history = {EpochRecord{0, 0.5, 0.75, 1e-3, 0}, EpochRecord{1, 0.25, 0.5, 1e-4, 0},
                          EpochRecord{2, 0.125, 0.625, 1e-5, 0}};
    m.training.trainLoss = 0.125;
    m.training.validationLoss = 0.5;
    m.training.testLoss = 0.5625;
    m.training.trainSamples = 7;
    m.training.validationSamples = 2;
    m.training.testSamples = 1;
    m.training.trainSamplesUsed = 7;
    m.errors = {0.25, 0.375, 0.4375};
    return m;
}

/// The golden model's prediction by hand: x̂ = (x − o)·s, h = tanh(W1 x̂ + b1), ŷ = W2 h + b2,
/// y = ŷ / s + o, with W_l column-major (out × in) followed by b_l in the flat vector.
std::vector<double> handPrediction(const NetworkModel& m, double x0, double x1) {
    const VecX<double>& p = m.params;
    const double xn[2] = {(x0 - 0.5) * 2.0, (x1 + 1.0) * 0.25};
    double h[3];
    for (int j = 0; j < 3; ++j) h[j] = std::tanh(p[0 * 3 + j] * xn[0] + p[1 * 3 + j] * xn[1] + p[6 + j]);
    std::vector<double> y(2);
    for (int k = 0; k < 2; ++k) {
        double yn = p[9 + 6 + k];
        for (int j = 0; j < 3; ++j) yn += p[9 + j * 2 + k] * h[j];
        y[size_t(k)] = yn / m.outputScaler.scale[k] + m.outputScaler.offset[k];
    }
    return y;
}

}  // namespace

TEST(GoldenFiles, DatasetIsWrittenByteForByteAndDecodesToItsRecords) {
    const std::string golden = kGoldenDir + "/small.rrfd";
    if (writeGolden()) {
        fs::create_directories(kGoldenDir);
        writeDataset(golden, goldenDatasetHeader(), kGoldenSceneHash, goldenRecords());
    }
    ASSERT_TRUE(fs::exists(golden)) << golden << " is missing (see this file's header to regenerate it)";
    const fs::path dir = scratchDir();
    const std::string fresh = (dir / "fresh.rrfd").string();
    writeDataset(fresh, goldenDatasetHeader(), kGoldenSceneHash, goldenRecords());
    EXPECT_EQ(readBytes(fresh), readBytes(golden)) << "the .rrfd bytes changed: a format change needs a new version";
    fs::remove_all(dir);

    const Dataset d(golden, true, kGoldenSceneHash);
    EXPECT_EQ(d.version(), kDatasetVersion);
    EXPECT_EQ(d.sceneHash(), kGoldenSceneHash);
    EXPECT_EQ(d.inputCount(), 2);
    EXPECT_EQ(d.targetCount(), 6);
    ASSERT_EQ(d.objects().size(), 2u);
    EXPECT_EQ(d.objects()[0].id, 3);
    EXPECT_EQ(d.objects()[0].name, "lamp");
    EXPECT_EQ(d.objects()[1].count, 1u);
    for (size_t o = 0; o < 2; ++o) {
        const std::vector<float>& want = goldenRecords()[o];
        ASSERT_EQ(d.objects()[o].count * 8, want.size());
        for (size_t i = 0; i < want.size(); ++i) EXPECT_EQ(d.records(o)[i], want[i]) << "object " << o << " float " << i;
    }
    // The trainer's view: direct from columns 2–4, indirect from 5–7.
    const std::vector<ObjectSamples> s = samplesFromDataset(d);
    ASSERT_EQ(s.size(), 2u);
    EXPECT_EQ(s[0].direct, (std::vector<float>{1.5f, 1.25f, 1.f, 2.5f, 2.25f, 2.f}));
    EXPECT_EQ(s[0].indirect, (std::vector<float>{0.125f, 0.0625f, 0.03125f, 0.375f, 0.1875f, 0.09375f}));
    EXPECT_EQ(s[1].direct, (std::vector<float>{0.5f, 0.5f, 0.5f}));
    EXPECT_EQ(s[1].indirect, (std::vector<float>{4.f, 3.f, 2.f}));
    EXPECT_EQ(s[1].inputs, (std::vector<float>{-1.f, 1.f}));
}

TEST(GoldenFiles, ModelFileDecodesToItsKnownValues) {
    const std::string golden = kGoldenDir + "/small.rrfm";
    const NetworkModel want = goldenModel();
    if (writeGolden()) {
        fs::create_directories(kGoldenDir);
        saveModel(want, golden);
    }
    ASSERT_TRUE(fs::exists(golden)) << golden << " is missing (see this file's header to regenerate it)";
    const NetworkModel m = loadModel(golden);
    EXPECT_EQ(m.arch.inputs, 2);
    EXPECT_EQ(m.arch.hidden, std::vector<int>{3});
    EXPECT_EQ(m.arch.outputs, 2);
    EXPECT_EQ(m.params, want.params);
    EXPECT_EQ(m.inputScaler.offset, want.inputScaler.offset);
    EXPECT_EQ(m.inputScaler.scale, want.inputScaler.scale);
    EXPECT_EQ(m.outputScaler.offset, want.outputScaler.offset);
    EXPECT_EQ(m.outputScaler.scale, want.outputScaler.scale);
    EXPECT_EQ(m.objectId, 3);
    EXPECT_EQ(m.objectName, "lamp");
    EXPECT_EQ(m.target, "direct");
    EXPECT_EQ(m.training.epochs, 2);
    EXPECT_EQ(m.training.bestEpoch, 1);
    EXPECT_EQ(m.training.stopReason, "maximum epoch reached");
    ASSERT_EQ(m.training.history.size(), 3u);
    EXPECT_EQ(m.training.history[1].trainLoss, 0.25);
    EXPECT_EQ(m.training.history[2].validationLoss, 0.625);
    EXPECT_EQ(m.errors.validation, 0.375);
    // The loaded network predicts what the hand computation says.
    for (const auto& [x0, x1] : {std::pair{0.5, -1.0}, std::pair{1.25, 2.0}, std::pair{-0.75, -3.5}}) {
        const std::vector<double> y = handPrediction(m, x0, x1);
        const MatX<double> p = m.predictDouble((MatX<double>(2, 1) << x0, x1).finished());
        EXPECT_NEAR(p(0, 0), y[0], 1e-12 * std::fabs(y[0]));
        EXPECT_NEAR(p(1, 0), y[1], 1e-12 * std::fabs(y[1]));
    }
}

}  // namespace test_golden_files
