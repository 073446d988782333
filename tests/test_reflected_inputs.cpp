// The reflected-direction input (issue 26, item 5; core/nn/derived_inputs.h): the derived rows
// against reflections worked out by hand, the "reflected" input group of an encoding with its
// gradients against central finite differences, predictions that derive the rows from the raw
// records, the model file round trip (version 4, older files as before), and a lobe around the
// mirror direction that a network learns far better with the input than without.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/nn/derived_inputs_json.h"
#include "core/nn/encoding_json.h"
#include "core/nn/model_file.h"
#include "core/data/dataset_file.h"
#include "core/nn/encoding_presets.h"
#include "core/nn/model.h"
#include "core/util/error.h"
#include "core/util/rng.h"

namespace test_reflected_inputs {

using namespace rrf;
using nlohmann::json;

namespace {

/// One record of 15 inputs (12 geometric and a diffuse BRDF) with view `v` and normal `n`.
std::vector<float> record(const float v[3], const float n[3]) {
    std::vector<float> r = {0.1f, -0.2f, 0.3f, v[0], v[1], v[2], 0.f, 0.9f, 0.f, n[0], n[1], n[2], 0.7f, 0.6f, 0.5f};
    return r;
}

InputEncoding parseWith(const std::string& text, int inputs, DerivedInputs derived) {
    return inputEncodingFromJson(JsonReader(json::parse(text), "project.json", "/network/encoding"), inputs, derived);
}

MatX<double> randomMatrix(int rows, int cols, uint64_t seed) {
    MatX<double> x(rows, cols);
    Rng rng(seed, 0);
    for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = 2.0 * rng.uniformDouble() - 1.0;
    return x;
}

/// loss = Σ w ⊙ encoding(x): ∂loss/∂features = w.
double weightedSum(const InputEncoding& e, const double* params, const MatX<double>& x, const MatX<double>& w) {
    MatX<double> f;
    e.forward(params, x, f);
    return (f.array() * w.array()).sum();
}

/// A unit vector from two uniforms (seeded per column).
Vec3 unitVector(Rng& rng) {
    const float z = 2.f * rng.uniform() - 1.f, phi = 2.f * kPi * rng.uniform();
    const float s = std::sqrt(std::max(0.f, 1.f - z * z));
    return Vec3(s * std::cos(phi), s * std::sin(phi), z);
}

/// A glossy lobe around the mirror direction: 0.05 + exp(12 (r·L − 1)) per channel for a fixed L,
/// r = reflect(view, normal), over random normals, views in the normal's hemisphere and positions.
void lobeRecords(int n, uint64_t seed, MatX<float>& x, MatX<float>& y) {
    const Vec3 light = normalize(Vec3(0.3f, 0.8f, 0.5f));
    x.resize(15, n);
    y.resize(3, n);
    for (int c = 0; c < n; ++c) {
        Rng rng(seed, uint64_t(c));
        const Vec3 nn = unitVector(rng);
        Vec3 v = unitVector(rng);
        if (dot(v, nn) < 0.f) v = -v;
        const Vec3 p(2.f * rng.uniform() - 1.f, 2.f * rng.uniform() - 1.f, 2.f * rng.uniform() - 1.f);
        const Vec3 f[4] = {p, v, Vec3(0.f, 0.9f, 0.f), nn};
        for (int k = 0; k < 12; ++k) x(k, c) = f[k / 3][k % 3];
        x(12, c) = 0.7f, x(13, c) = 0.6f, x(14, c) = 0.5f;
        const Vec3 r = 2.f * dot(nn, v) * nn - v;  // written out here, not core's routine
        const float lobe = 0.05f + std::exp(12.f * (dot(r, light) - 1.f));
        for (int k = 0; k < 3; ++k) y(k, c) = lobe * (1.f - 0.2f * float(k));
    }
}

double lobeError(const DerivedInputs& derived) {
    MatX<float> x, y, xt, yt;
    lobeRecords(6000, 1, x, y);
    lobeRecords(3000, 2, xt, yt);
    const InputEncoding e = networkEncoding(NetworkEncodingSettings{}, 15, derived);
    MlpArch a;
    a.inputs = e.outputs();
    a.hidden = {16, 8};
    TrainerConfig t = TrainerConfig().withType(TrainerType::Adam);
    t.adam.maxEpochs = 120;
    t.adam.batchSize = 128;
    t.adam.learningRate = 5e-3;
    t.adam.minLearningRate = 1e-5;
    const NetworkModel m = fitNetwork(a, e, t, x, y, MatX<float>(), {}, 3);
    return relativeRmse(m.predict(xt), yt);
}

/// A small network behind `encoding` (15 record inputs) fitted for `epochs` on `records` lobe
/// records; `x` receives the records' inputs.
NetworkModel smallModel(const InputEncoding& encoding, int records, int hidden, int epochs, uint64_t seed, MatX<float>& x) {
    MatX<float> y;
    lobeRecords(records, seed, x, y);
    MlpArch a;
    a.inputs = encoding.outputs();
    a.hidden = {hidden};
    TrainerConfig t = TrainerConfig().withType(TrainerType::Adam);
    t.adam.maxEpochs = epochs;
    return fitNetwork(a, encoding, t, x, y, MatX<float>(), {}, seed);
}

}  // namespace

TEST(DerivedInputs, ReflectedDirectionIsTheViewMirroredAboutTheNormal) {
    // n = +y, v = (0.6, 0.8, 0): n·v = 0.8, r = 1.6 n − v = (−0.6, 0.8, 0).
    // n = +z, v = (0.48, 0.6, 0.64): r = 1.28 n − v = (−0.48, −0.6, 0.64).
    // n = (0.6, 0.8, 0), v = (0, 1, 0): n·v = 0.8, r = 1.6 (0.6, 0.8, 0) − (0, 1, 0) = (0.96, 0.28, 0).
    const float cases[3][3][3] = {{{0.6f, 0.8f, 0.f}, {0.f, 1.f, 0.f}, {-0.6f, 0.8f, 0.f}},
                                  {{0.48f, 0.6f, 0.64f}, {0.f, 0.f, 1.f}, {-0.48f, -0.6f, 0.64f}},
                                  {{0.f, 1.f, 0.f}, {0.6f, 0.8f, 0.f}, {0.96f, 0.28f, 0.f}}};
    DerivedInputs d;
    EXPECT_EQ(d.count(), 0);
    d.reflected = true;
    ASSERT_EQ(d.count(), 3);
    EXPECT_EQ(d.rowNames(), (std::vector<std::string>{"reflected_x", "reflected_y", "reflected_z"}));
    MatX<float> rec(15, 3);
    for (int c = 0; c < 3; ++c) {
        const std::vector<float> r = record(cases[c][0], cases[c][1]);
        for (int k = 0; k < 15; ++k) rec(k, c) = r[size_t(k)];
    }
    MatX<float> out;
    d.append<float>(rec, out);
    ASSERT_EQ(out.rows(), 18);
    EXPECT_EQ(out.topRows(15), rec) << "the record rows come first, unchanged";
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(out(15 + i, c), cases[c][2][i], 1e-6f) << "case " << c << " row " << i;
    // Without derived inputs the records pass unchanged; records without normals cannot derive.
    MatX<float> same;
    DerivedInputs().append<float>(rec, same);
    EXPECT_EQ(same, rec);
    MatX<float> tooShort(6, 1);
    EXPECT_THROW(d.append<float>(tooShort, out), std::invalid_argument);
}

TEST(DerivedInputs, JsonReadsBackAndNamesFileAndPointerOfABadValue) {
    const DerivedInputs on = derivedInputsFromJson(JsonReader(json::parse(R"({"reflected": true})"), "p.json", "/network/inputs"));
    EXPECT_TRUE(on.reflected);
    EXPECT_EQ(derivedInputsFromJson(JsonReader(toJson(on), "p.json")), on);
    EXPECT_FALSE(derivedInputsFromJson(JsonReader(json::object(), "p.json")).any());
    for (const char* bad : {R"({"reflected": 1})", R"({"reflectd": true})", R"(true)"}) {
        try {
            derivedInputsFromJson(JsonReader(json::parse(bad), "p.json", "/network/inputs"));
            ADD_FAILURE() << bad << " was accepted";
        } catch (const InputError& e) {
            EXPECT_EQ(e.file(), "p.json") << bad;
            EXPECT_EQ(e.where().rfind("/network/inputs", 0), 0u) << bad << ": " << e.what();
        }
    }
}

TEST(DerivedInputs, ReflectedGroupFollowsTheRecordInputsAndNeedsTheInput) {
    const InputEncoding e =
        parseWith(R"([{"type": "frequency", "inputs": "reflected", "frequencies": 2, "include_input": false}])", 19,
                  DerivedInputs{true});
    ASSERT_EQ(e.components.size(), 1u);
    EXPECT_EQ(e.components[0].inputs, (std::vector<int>{19, 20, 21}));
    EXPECT_EQ(e.scaledInputs(), 22);
    EXPECT_EQ(e.outputs(), 3 * 4 + 19);
    EXPECT_EQ(e.describe(), "frequency(reflected) +reflected");
    // Not encoded: the three rows pass through after the record inputs.
    const InputEncoding id = networkEncoding(NetworkEncodingSettings{}, 15, DerivedInputs{true});
    EXPECT_TRUE(id.isIdentity());
    EXPECT_EQ(id.outputs(), 18);
    const InputEncoding other = parseWith(R"([{"type": "one_blob", "inputs": "view", "bins": 4}])", 15, DerivedInputs{true});
    EXPECT_EQ(other.passThrough().back(), 17);
    EXPECT_NE(other, parseWith(R"([{"type": "one_blob", "inputs": "view", "bins": 4}])", 15, DerivedInputs{}));
    // A network that does not derive it has no such group: the error names file, pointer and the fix.
    try {
        parseWith(R"([{"type": "one_blob", "inputs": ["view", "reflected"]}])", 15, DerivedInputs{});
        ADD_FAILURE() << "reflected accepted without the input";
    } catch (const InputError& err) {
        EXPECT_EQ(err.file(), "project.json");
        EXPECT_EQ(err.where(), "/network/encoding/0/inputs/1");
        EXPECT_NE(err.detail().find("\"reflected\": true"), std::string::npos) << err.what();
    }
}

TEST(DerivedInputs, EncodingGradientsOnTheReflectedRowsMatchFiniteDifferences) {
    // Fixed encodings: frequency on the reflected rows and one-blob on the view (input gradients);
    // then the trainable path, a hash grid over the reflected rows (parameter gradients).
    const InputEncoding e = parseWith(R"([{"type": "frequency", "inputs": "reflected", "frequencies": 3},
                                          {"type": "one_blob", "inputs": "view", "bins": 4}])",
                                      15, DerivedInputs{true});
    const MatX<double> x = randomMatrix(18, 20, 7) * 0.95;
    const MatX<double> w = randomMatrix(e.outputs(), 20, 8);
    MatX<double> dX;
    e.backwardInputs(static_cast<const double*>(nullptr), x, w, dX);
    ASSERT_EQ(dX.rows(), 18);
    MatX<double> xp = x;
    const double h = 1e-6;
    double worst = 0;
    for (Eigen::Index i = 0; i < x.size(); ++i) {
        xp.data()[i] = x.data()[i] + h;
        const double up = weightedSum(e, nullptr, xp, w);
        xp.data()[i] = x.data()[i] - h;
        const double down = weightedSum(e, nullptr, xp, w);
        xp.data()[i] = x.data()[i];
        worst = std::max(worst, std::fabs((up - down) / (2 * h) - dX.data()[i]));
    }
    EXPECT_LT(worst, 1e-6);
    EXPECT_GT(dX.bottomRows(3).cwiseAbs().maxCoeff(), 0.1) << "the reflected rows receive the frequency gradient";

    const InputEncoding g = parseWith(R"([{"type": "hash_grid", "inputs": "reflected", "levels": 2, "log2_table_size": 10,
                                           "features_per_level": 2, "base_resolution": 3, "growth": 2}])",
                                      15, DerivedInputs{true});
    std::vector<double> params(size_t(g.numParams()));
    Rng rng(9, 1);
    for (double& p : params) p = 2.0 * rng.uniformDouble() - 1.0;
    const MatX<double> xs = x.leftCols(3), ws = randomMatrix(g.outputs(), 3, 10);
    std::vector<double> grad(params.size(), 0.0);
    g.backwardParams(params.data(), xs, ws, grad.data(), nullptr);
    int nonzero = 0;
    for (size_t i = 0; i < params.size(); ++i) {
        const double p0 = params[i];
        params[i] = p0 + 1e-3;
        const double up = weightedSum(g, params.data(), xs, ws);
        params[i] = p0 - 1e-3;
        const double down = weightedSum(g, params.data(), xs, ws);
        params[i] = p0;
        EXPECT_NEAR(grad[i], (up - down) / 2e-3, 1e-9) << "param " << i;
        nonzero += grad[i] != 0;
    }
    EXPECT_GT(nonzero, 0);
}

TEST(DerivedInputs, PredictionDerivesTheRowsFromTheRawRecords) {
    MatX<float> x;
    const NetworkModel m = smallModel(networkEncoding(NetworkEncodingSettings{}, 15, DerivedInputs{true}), 400, 6, 3, 5, x);
    EXPECT_EQ(m.arch.inputs, 18);
    EXPECT_EQ(m.rawInputs(), 15);
    EXPECT_EQ(m.scaledInputs(), 18);
    ASSERT_EQ(m.inputScaler.size(), 18) << "the scaler covers the derived rows";
    // The same network fed the 18 rows by hand (the identity over 18 inputs) predicts the same bits.
    NetworkModel plain = m;
    plain.encoding = InputEncoding();
    plain.encoding.inputs = 18;
    MatX<float> extended;
    DerivedInputs{true}.append<float>(x, extended);
    EXPECT_EQ(m.predict(x), plain.predict(extended));
    // The scaler was fitted on the derived rows of the raw records: their ranges are the reflections'.
    const float lo = extended.row(16).minCoeff(), hi = extended.row(16).maxCoeff();
    EXPECT_NEAR(m.inputScaler.offset[16], 0.5 * (double(lo) + double(hi)), 1e-6);
    EXPECT_NEAR(m.inputScaler.scale[16], 2.0 / (double(hi) - double(lo)), 1e-4);
    EXPECT_THROW(m.predict(extended), std::invalid_argument) << "callers pass record inputs";
}

TEST(DerivedInputs, ModelFileRoundTripKeepsTheInputAndOlderFilesReadAsBefore) {
    MatX<float> x;
    const InputEncoding e = parseWith(R"([{"type": "one_blob", "inputs": "reflected", "bins": 6}])", 15, DerivedInputs{true});
    const NetworkModel m = smallModel(e, 300, 5, 2, 7, x);
    const std::string bytes = modelFileBytes(m);
    uint32_t version = 0;
    std::memcpy(&version, bytes.data() + 8, 4);
    EXPECT_EQ(version, 4u);
    EXPECT_EQ(modelHeader(m).at("input_encoding").at("derived"), json({{"reflected", true}}));
    const NetworkModel back = parseModel(bytes, "m.rrfm");
    EXPECT_EQ(back.encoding, m.encoding);
    EXPECT_TRUE(back.encoding.derived.reflected);
    EXPECT_EQ(back.inputScaler.offset, m.inputScaler.offset);
    EXPECT_EQ(back.params, m.params);
    EXPECT_EQ(back.predict(x), m.predict(x));
    // The payload holds both scaler vectors over the 18 rows.
    EXPECT_EQ(modelPayloadBytes(m), int64_t(8 * (m.arch.numParams() + 2 * 18 + 2 * 3)));
    // The version 3 golden file (tests/data/golden) derives nothing.
    const NetworkModel v3 = loadModel(std::string(RRF_SOURCE_DIR) + "/tests/data/golden/small.rrfm");
    EXPECT_FALSE(v3.encoding.derived.any());
    EXPECT_EQ(v3.scaledInputs(), v3.rawInputs());
}

TEST(DerivedInputs, AModelFileWithABadDerivedEntryNamesItsField) {
    MatX<float> x;
    const NetworkModel m = smallModel(networkEncoding(NetworkEncodingSettings{}, 15, DerivedInputs{true}), 50, 3, 1, 9, x);
    // Turning the input off in the header leaves a payload three scaler rows too long: refused, not
    // misread; a value of the wrong type or an unknown key names the field.
    const std::string bytes = modelFileBytes(m);
    uint32_t hlen = 0;
    std::memcpy(&hlen, bytes.data() + 12, 4);
    json stored = json::parse(bytes.substr(24, hlen));
    for (const json& derived : {json({{"reflected", false}}), json({{"reflected", "yes"}}), json({{"mirror", true}})}) {
        stored["input_encoding"]["derived"] = derived;
        const std::string h = stored.dump(1);
        std::string b = bytes.substr(0, 24) + h + bytes.substr(24 + hlen);
        const uint32_t n = uint32_t(h.size());
        std::memcpy(&b[12], &n, 4);
        const uint64_t sum = checksum64(h.data(), h.size());
        std::memcpy(&b[16], &sum, 8);
        try {
            parseModel(b, "m.rrfm");
            ADD_FAILURE() << derived.dump() << " was accepted";
        } catch (const InputError& e) {
            EXPECT_EQ(e.file(), "m.rrfm");
            EXPECT_NE(e.where().find("header"), std::string::npos) << e.what();
        }
    }
}

TEST(DerivedInputs, ALobeAroundTheMirrorDirectionIsLearntFarBetterWithTheInput) {
    const double with = lobeError(DerivedInputs{true}), without = lobeError(DerivedInputs{});
    std::printf("held-out relative RMSE of the mirror lobe: with the reflected input %.4f, without %.4f\n", with, without);
    EXPECT_LT(3 * with, without);
}

}  // namespace test_reflected_inputs
