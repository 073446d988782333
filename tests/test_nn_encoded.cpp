// Networks behind input encodings: the MLP's input gradient, model files, the trainer rules, the
// sparse update of hash-grid entries, thread-count independence and the "encoding" setting.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>

#include <unistd.h>

#include "core/nn/encoding_settings_json.h"
#include "core/nn/encoding_presets.h"
#include "core/nn/model.h"
#include "core/nn/network_settings.h"
#include "core/nn/network_settings_json.h"
#include "core/nn/object_training.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/util/rng.h"
#include "tests/training_builders.h"

namespace test_nn_encoded {

using namespace rrf;
namespace fs = std::filesystem;

namespace {

/// A small hash grid over position and frequencies over light (1 + 2·2 features per light input).
NetworkEncodingSettings smallEncoding() {
    return encodingSettingsFromJson(nlohmann::json::array(
        {{{"type", "hash_grid"}, {"inputs", "position"}, {"levels", 3}, {"log2_table_size", 10},
          {"features_per_level", 2}, {"base_resolution", 4}, {"growth", 2.0}},
         {{"type", "frequency"}, {"inputs", "light"}, {"frequencies", 2}, {"include_input", true}}}));
}

/// `n` records of 15 inputs whose positions lie in [lo, hi]³ (raw units), targets smooth in them.
void records(int n, float lo, float hi, uint64_t seed, MatX<float>& x, MatX<float>& y) {
    x.resize(15, n);
    y.resize(3, n);
    for (int c = 0; c < n; ++c) {
        Rng rng(seed, uint64_t(c));
        for (int r = 0; r < 15; ++r) x(r, c) = r < 3 ? lo + (hi - lo) * rng.uniform() : 2.f * rng.uniform() - 1.f;
        for (int k = 0; k < 3; ++k) y(k, c) = 1.f + std::sin(3.f * x(0, c) + float(k)) * std::cos(2.f * x(1, c)) + 0.2f * x(6, c);
    }
}

MlpArch archFor(const InputEncoding& e) {
    MlpArch a;
    a.inputs = e.outputs();
    a.hidden = {16};
    a.outputs = 3;
    return a;
}

TrainerConfig adam(int epochs) {
    TrainerConfig t = TrainerConfig().withType(TrainerType::Adam);
    t.adam.maxEpochs = epochs;
    t.adam.batchSize = 64;
    return t;
}

std::string tempFile(const std::string& name) {
    return (fs::temp_directory_path() / ("rrf_nn_encoded_" + std::to_string(::getpid()) + "_" + name)).string();
}

}  // namespace

TEST(Mlp, InputGradientMatchesCentralDifferences) {
    for (Activation act : {Activation::Tanh, Activation::Relu}) {
        MlpArch a;
        a.inputs = 6;
        a.hidden = {9, 5};
        a.outputs = 2;
        a.activation = act;
        const VecX<double> w = initialParams(a, 3);
        MatX<double> x(6, 4), y(2, 4);
        Rng rng(8, 0);
        for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = 2.0 * rng.uniformDouble() - 1.0;
        for (Eigen::Index i = 0; i < y.size(); ++i) y.data()[i] = rng.uniformDouble();
        std::vector<MatX<double>> acts, deltas;
        auto loss = [&](const MatX<double>& in) {
            mlpForward<double>(a, w.data(), in, acts);
            return 0.5 * (acts.back() - y).squaredNorm();
        };
        loss(x);
        const MatX<double> dOut = acts.back() - y;
        VecX<double> g(a.numParams());
        MatX<double> dX;
        mlpBackward<double>(a, w.data(), x, acts, dOut, deltas, g.data(), &dX);
        ASSERT_EQ(dX.rows(), 6);
        ASSERT_EQ(dX.cols(), 4);
        const double h = 1e-6;
        for (Eigen::Index i = 0; i < x.size(); ++i) {
            MatX<double> xp = x, xm = x;
            xp.data()[i] += h;
            xm.data()[i] -= h;
            const double fd = (loss(xp) - loss(xm)) / (2 * h);
            EXPECT_NEAR(dX.data()[i], fd, 1e-6 * std::max(1.0, std::abs(fd))) << activationName(act) << " input " << i;
        }
    }
}

TEST(EncodedModel, FileRoundTripPredictsBitIdentically) {
    const InputEncoding e = networkEncoding(smallEncoding(), 15);
    MatX<float> x, y;
    records(400, -2.f, 3.f, 5, x, y);
    NetworkModel m = fitNetwork(archFor(e), e, adam(3), x, y, MatX<float>(), {}, 7);
    ASSERT_EQ(m.encodingParams.size(), 3 * 1024 * 2);
    EXPECT_EQ(m.numParams(), int64_t(m.arch.numParams()) + 3 * 1024 * 2);
    EXPECT_EQ(m.rawInputs(), 15);
    const std::string path = tempFile("m.rrfm"), again = tempFile("again.rrfm");
    saveModel(m, path);
    const NetworkModel l = loadModel(path);
    EXPECT_EQ(l.encoding, m.encoding);
    ASSERT_EQ(l.encodingParams.size(), m.encodingParams.size());
    EXPECT_EQ(std::memcmp(l.encodingParams.data(), m.encodingParams.data(), size_t(m.encodingParams.size()) * 8), 0);
    const MatX<float> pm = m.predict(x), pl = l.predict(x);
    EXPECT_EQ(std::memcmp(pm.data(), pl.data(), size_t(pm.size()) * 4), 0);
    EXPECT_EQ(m.predictDouble(x.cast<double>()), l.predictDouble(x.cast<double>()));
    saveModel(l, again);
    EXPECT_EQ(readFile(path), readFile(again));
    fs::remove(path);
    fs::remove(again);
}

TEST(EncodedModel, PredictionIsScalingThenEncodingThenTheMlp) {
    const InputEncoding e = networkEncoding(smallEncoding(), 15);
    MatX<float> x, y;
    records(300, -1.f, 1.f, 6, x, y);
    const NetworkModel m = fitNetwork(archFor(e), e, adam(2), x, y, MatX<float>(), {}, 3);
    // The pipeline written out by hand from its parts, in double.
    MatX<double> xs = x.cast<double>();
    for (Eigen::Index r = 0; r < xs.rows(); ++r)
        xs.row(r) = ((xs.row(r).array() - m.inputScaler.offset[r]) * m.inputScaler.scale[r]).matrix();
    MatX<double> features;
    m.encoding.forward<double>(m.encodingParams.data(), xs, features);
    std::vector<MatX<double>> acts;
    mlpForward<double>(m.arch, m.params.data(), features, acts);
    MatX<double> want = acts.back();
    for (Eigen::Index r = 0; r < want.rows(); ++r)
        want.row(r) = (want.row(r).array() / m.outputScaler.scale[r] + m.outputScaler.offset[r]).matrix();
    EXPECT_LT((m.predictDouble(x.cast<double>()) - want).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(EncodedModel, ValidateRefusesParametersThatDoNotFitTheEncoding) {
    const InputEncoding e = networkEncoding(smallEncoding(), 15);
    MatX<float> x, y;
    records(100, -1.f, 1.f, 2, x, y);
    NetworkModel m = fitNetwork(archFor(e), e, adam(1), x, y, MatX<float>(), {}, 1);
    m.encodingParams.conservativeResize(m.encodingParams.size() - 1);
    EXPECT_THROW(m.validate(), std::invalid_argument);
}

TEST(EncodedTraining, LevenbergMarquardtRefusesAHashGridNamingTheSetting) {
    ObjectSamples s;
    s.objectId = 0;
    s.numInputs = 15;
    MatX<float> x, y;
    records(50, -1.f, 1.f, 1, x, y);
    for (int c = 0; c < 50; ++c) s.add(x.col(c).data(), y.col(c).data(), y.col(c).data());
    ObjectTrainingOptions o = test::plainTraining();
    o.encoding = smallEncoding();
    o.trainer = TrainerConfig().withType(TrainerType::LevenbergMarquardt);
    o.hidden = {4};
    try {
        trainObjects({s}, o);
        FAIL() << "LM trained a hash grid";
    } catch (const SettingError& e) {
        EXPECT_EQ(e.setting(), "network.encoding");
        EXPECT_NE(std::string(e.what()).find("adam"), std::string::npos) << e.what();
    }
    // A fixed encoding is fine with LM: the features are computed once.
    o.encoding = encodingPresetSettings("frequency");
    o.trainer.lm.maxEpochs = 2;
    const std::vector<ObjectModel> r = trainObjects({s}, o);
    ASSERT_FALSE(r[0].skipped);
    EXPECT_EQ(r[0].model.encoding().describe(), networkEncoding(o.encoding, 15).describe());
    EXPECT_EQ(r[0].model.arch().inputs, networkEncoding(o.encoding, 15).outputs());
}

TEST(EncodedTraining, HashGridEntriesNoRecordTouchesKeepTheirInitialValues) {
    const InputEncoding e = networkEncoding(smallEncoding(), 15);
    MatX<float> x, y;
    // Positions fill [0, 1]³ of the scaler's range [0, 4]³ (one fixed corner record pins the range):
    // the grid's other cells see no record.
    records(300, 0.f, 1.f, 9, x, y);
    x.col(0).head(3).setConstant(4.f);
    const NetworkModel m = fitNetwork(archFor(e), e, adam(4), x, y, MatX<float>(), {}, 2);
    const VecX<double> init = e.initialParams(m.trainer.seed(), 2);
    // Every entry any record reaches (the forward's corners), from the encoding on all records.
    MatX<float> xs = x;
    m.inputScaler.apply(xs);
    const VecX<float> ef = m.encodingParams.cast<float>();
    MatX<float> features, ones;
    e.forward<float>(ef.data(), xs, features);
    ones.setOnes(features.rows(), features.cols());
    std::vector<int64_t> touched;
    VecX<float> grad = VecX<float>::Zero(ef.size());
    e.backwardParams<float>(ef.data(), xs, ones, grad.data(), &touched);
    const std::set<int64_t> reached(touched.begin(), touched.end());
    int64_t kept = 0, moved = 0;
    for (Eigen::Index i = 0; i < init.size(); ++i) {
        if (reached.count(i)) {
            moved += m.encodingParams[i] != init[i];
            continue;
        }
        EXPECT_EQ(m.encodingParams[i], double(float(init[i]))) << "entry " << i << " moved without a record";
        ++kept;
    }
    EXPECT_GT(kept, init.size() / 4);
    EXPECT_GT(moved, 0);
}

TEST(EncodedTraining, ResultIsIdenticalForAnyThreadCount) {
    std::vector<ObjectSamples> objects;
    for (int id = 0; id < 3; ++id) {
        ObjectSamples s;
        s.objectId = id;
        s.numInputs = 15;
        MatX<float> x, y;
        records(120, -1.f, 1.f, uint64_t(10 + id), x, y);
        for (int c = 0; c < 120; ++c) s.add(x.col(c).data(), y.col(c).data(), y.col(c).data());
        objects.push_back(std::move(s));
    }
    ObjectTrainingOptions o = test::plainTraining();
    o.encoding = smallEncoding();
    o.trainer = adam(3);
    o.hidden = {8};
    o.parallel = true;
    const std::vector<ObjectModel> a = trainObjects(objects, o);
    o.parallel = false;
    const std::vector<ObjectModel> b = trainObjects(objects, o);
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].model.leaves[0].params, b[i].model.leaves[0].params);
        EXPECT_EQ(a[i].model.leaves[0].encodingParams, b[i].model.leaves[0].encodingParams);
    }
}

TEST(NetworkSettingsEncoding, JsonRoundTripsAndNamesBadValues) {
    NetworkSettings s;
    s.options.encoding = encodingPresetSettings("hash_grid_one_blob");
    const nlohmann::json j = toJson(s);
    const NetworkSettings back = networkSettingsFromJson(JsonReader(j, "project.json", "/network"));
    EXPECT_EQ(back.options.encoding, s.options.encoding);
    EXPECT_EQ(toJson(back), j);
    EXPECT_EQ(encodingPresetName(back.options.encoding), "hash_grid_one_blob");
    EXPECT_EQ(encodingPresetName(NetworkEncodingSettings{}), "raw");

    nlohmann::json bad = j;
    bad["encoding"][0]["levls"] = 4;
    try {
        networkSettingsFromJson(JsonReader(bad, "project.json", "/network"));
        FAIL() << "an unknown key was accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), "project.json");
        EXPECT_NE(e.where().find("/network/encoding/0"), std::string::npos) << e.what();
    }
    EXPECT_THROW(encodingPresetSettings("nerf"), SettingError);
}

TEST(NetworkSettingsEncoding, NamedEncodingsWriteTheArraysTheyStandFor) {
    // The named encodings are typed values; what a project, model index or run record stores of
    // them is the array each stood for when it was written as JSON.
    const std::pair<const char*, const char*> arrays[] = {
        {"raw", "[]"},
        {"frequency", R"([{"type": "frequency", "inputs": ["position", "light"], "frequencies": 4, "include_input": true}])"},
        {"one_blob", R"([{"type": "one_blob", "inputs": ["position", "view", "light", "normal"], "bins": 16}])"},
        {"hash_grid", R"([{"type": "hash_grid", "inputs": "position", "levels": 8, "log2_table_size": 12,
                           "features_per_level": 2, "base_resolution": 4, "growth": 1.5}])"},
        {"hash_grid_one_blob", R"([{"type": "hash_grid", "inputs": "position", "levels": 8, "log2_table_size": 12,
                                    "features_per_level": 2, "base_resolution": 4, "growth": 1.5},
                                   {"type": "one_blob", "inputs": ["view", "light", "normal"], "bins": 16}])"},
    };
    ASSERT_EQ(encodingPresets().size(), std::size(arrays));
    for (const auto& [name, text] : arrays) {
        const nlohmann::json written = nlohmann::json::parse(text);
        EXPECT_EQ(encodingSettingsJson(encodingPresetSettings(name)).dump(), written.dump()) << name;
        EXPECT_EQ(encodingSettingsFromJson(written), encodingPresetSettings(name)) << name << ": read back";
        EXPECT_EQ(encodingPresetName(encodingSettingsFromJson(written)), name);
    }
}

}  // namespace test_nn_encoded
