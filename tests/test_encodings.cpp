// Input encodings (core/nn/encoding*.h): closed-form outputs, the hash grid's table indices worked
// out by hand from the documented formula, gradients against central finite differences, JSON
// reading and writing with errors that name file and pointer, and the feature order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "core/nn/encoding_json.h"
#include "core/nn/encoding.h"
#include "core/nn/encodings/frequency.h"
#include "core/nn/encodings/hash_grid.h"
#include "core/nn/encodings/one_blob.h"
#include "core/util/error.h"
#include "core/util/rng.h"

// The TESTs sit inside the file's namespace too (as tests/test_nn_mlp.cpp): a using-directive at
// global scope would leak these helpers into the other sources of a unity batch.
namespace test_encodings {

using namespace rrf;

namespace {

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
    return inputEncodingFromJson(JsonReader(value, "project.json", "/network/encoding"), inputs);
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


/// Parameters uniform in [−1, 1] (large enough that every path carries a visible gradient).
std::vector<double> randomParams(int64_t count, uint64_t seed) {
    std::vector<double> p(static_cast<size_t>(count));
    Rng rng(seed, 1);
    for (double& v : p) v = 2.0 * rng.uniformDouble() - 1.0;
    return p;
}

/// loss = Σ weights ⊙ encoding(x), so ∂loss/∂features = weights.
double weightedSum(const Encoding& enc, const double* params, const MatX<double>& x, const MatX<double>& weights) {
    MatX<double> out(enc.outputDims(), x.cols());
    enc.forward(params, x, out);
    return (out.array() * weights.array()).sum();
}
double weightedSum(const InputEncoding& enc, const double* params, const MatX<double>& x, const MatX<double>& weights) {
    MatX<double> out;
    enc.forward(params, x, out);
    return (out.array() * weights.array()).sum();
}

/// Central differences of weightedSum with respect to every entry of x.
template <typename E>
MatX<double> numericInputGradient(const E& enc, const double* params, const MatX<double>& x, const MatX<double>& weights,
                                  double h) {
    MatX<double> g(x.rows(), x.cols()), xp = x;
    for (Eigen::Index i = 0; i < x.size(); ++i) {
        xp.data()[i] = x.data()[i] + h;
        const double up = weightedSum(enc, params, xp, weights);
        xp.data()[i] = x.data()[i] - h;
        const double down = weightedSum(enc, params, xp, weights);
        xp.data()[i] = x.data()[i];
        g.data()[i] = (up - down) / (2 * h);
    }
    return g;
}

/// Central differences of weightedSum with respect to every parameter.
template <typename E>
std::vector<double> numericParamGradient(const E& enc, std::vector<double> params, const MatX<double>& x,
                                         const MatX<double>& weights, double h) {
    std::vector<double> g(params.size());
    for (size_t i = 0; i < params.size(); ++i) {
        const double p = params[i];
        params[i] = p + h;
        const double up = weightedSum(enc, params.data(), x, weights);
        params[i] = p - h;
        const double down = weightedSum(enc, params.data(), x, weights);
        params[i] = p;
        g[i] = (up - down) / (2 * h);
    }
    return g;
}

/// True if sample n of x (the grid's inputs, rows first … first + d − 1) lies within `margin` (in
/// cells) of a cell face at some level, or within `margin` of the clamp at ±1: finite differences
/// there straddle a kink.
bool nearKink(const HashGridEncoding& g, const MatX<double>& x, Eigen::Index n, double margin, int first = 0) {
    for (int i = 0; i < g.inputDims(); ++i) {
        const double xi = x(first + i, n);
        if (std::abs(std::abs(xi) - 1.0) < margin) return true;
        const double u = std::clamp((xi + 1) * 0.5, 0.0, 1.0);
        for (int l = 0; l < g.settings().levels; ++l) {
            const double pos = u * g.levelResolution(l), frac = pos - std::floor(pos);
            if (std::abs(xi) < 1 && std::min(frac, 1 - frac) < margin) return true;
        }
    }
    return false;
}

/// Compares analytic and numeric input gradients column by column, skipping columns `skip` rejects;
/// returns the number of columns compared.
int expectInputGradientsMatch(const MatX<double>& analytic, const MatX<double>& numeric,
                              const std::vector<bool>& skip, double tol, const std::string& what) {
    int compared = 0;
    for (Eigen::Index n = 0; n < analytic.cols(); ++n) {
        if (skip[size_t(n)]) continue;
        ++compared;
        for (Eigen::Index i = 0; i < analytic.rows(); ++i)
            EXPECT_NEAR(analytic(i, n), numeric(i, n), tol * (1 + std::abs(numeric(i, n))))
                << what << ": input " << i << " sample " << n;
    }
    return compared;
}

}  // namespace

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
    EXPECT_EQ(FrequencyEncoding::angularFrequency<float>(3), float(8 * kPiD));
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

TEST(Encoding, HashGridTreatsANaNInputAsTheLowerBound) {
    // A NaN coordinate counts as u = 0 (the clamp written with comparisons): finite features, equal to
    // those of x = −1 there, no read outside the tables, and no input gradient for it. Level 0 is
    // dense (res 4), level 1 hashed (res 16: 17^3 > 1024), in float and in double.
    const HashGridEncoding enc(3, grid(2, 10, 1, 4, 4.0));
    ASSERT_TRUE(enc.levelIsDense(0) && !enc.levelIsDense(1));
    const double nan = std::numeric_limits<double>::quiet_NaN();
    MatX<double> x(3, 3), lower(3, 3);
    x << nan, 0.3, nan,  //
        -0.2, nan, nan,  //
        0.7, -0.9, nan;
    lower << -1, 0.3, -1,  //
        -0.2, -1, -1,      //
        0.7, -0.9, -1;
    const std::vector<double> params = randomParams(enc.numParams(), 5);
    MatX<double> out(2, 3), expected(2, 3);
    enc.forward(params.data(), x, out);
    enc.forward(params.data(), lower, expected);
    ASSERT_TRUE(out.allFinite());
    EXPECT_EQ(out, expected);
    const std::vector<float> paramsF(params.begin(), params.end());
    MatX<float> outF(2, 3);
    enc.forward(paramsF.data(), x.cast<float>(), outF);
    EXPECT_TRUE(outF.allFinite());
    EXPECT_LT((outF.cast<double>() - expected).cwiseAbs().maxCoeff(), 1e-5);
    MatX<double> dX(3, 3);
    enc.backwardInputs(params.data(), x, MatX<double>::Ones(2, 3), dX);
    ASSERT_TRUE(dX.allFinite());
    for (Eigen::Index n = 0; n < 3; ++n)
        for (int i = 0; i < 3; ++i)
            if (std::isnan(x(i, n))) {
                EXPECT_EQ(dX(i, n), 0.0) << i << "," << n;
            }
    std::vector<double> grad(size_t(enc.numParams()), 0.0);
    std::vector<int64_t> touched;
    enc.backwardParams(params.data(), x, MatX<double>::Ones(2, 3), grad.data(), &touched);
    for (const int64_t t : touched) ASSERT_TRUE(t >= 0 && t < enc.numParams()) << t;
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

TEST(Encoding, HashGridIndicesFollowTheDocumentedHash) {
    // Worked by hand from the formula idx = (XOR_i uint32(v_i)·π_i) & (T − 1), π = {1, 2654435761,
    // 805459861, 3674653429}, products taken mod 2^32:
    //   v = (8, 4, 12):  8 ^ (4·2654435761 mod 2^32 = 2027808452) ^ (12·805459861 mod 2^32 = 1075583740)
    //                    = 952237104;  & 1023 = 48
    //   v = (9, 4, 12):  9 ^ 2027808452 ^ 1075583740 = 952237105;  & 1023 = 49
    //   v = (3, 7):      3 ^ (7·2654435761 mod 2^32 = 1401181143) = 1401181140;  & 1023 = 980
    //   v = (100, 200, 300, 5), T = 2^14:  h = 2663939705;  & 16383 = 15993
    // Dense (res + 1)^d ≤ T: idx = Σ v_i·(res + 1)^i, e.g. res 4, v = (1, 2, 3): 1 + 2·5 + 3·25 = 86.
    EXPECT_EQ(uint32_t(4u * 2654435761u), 2027808452u);
    EXPECT_EQ(uint32_t(12u * 805459861u), 1075583740u);
    EXPECT_EQ(8u ^ 2027808452u ^ 1075583740u, 952237104u);

    const HashGridEncoding g3(3, grid(1, 10, 1, 16, 1.5));  // 17^3 = 4913 > 1024: hashed
    ASSERT_FALSE(g3.levelIsDense(0));
    const int a[3] = {8, 4, 12}, b[3] = {9, 4, 12};
    EXPECT_EQ(g3.entryIndex(0, a), 48u);
    EXPECT_EQ(g3.entryIndex(0, b), 49u);
    const HashGridEncoding g2(2, grid(1, 10, 1, 32, 1.5));  // 33^2 = 1089 > 1024: hashed
    ASSERT_FALSE(g2.levelIsDense(0));
    const int c[2] = {3, 7};
    EXPECT_EQ(g2.entryIndex(0, c), 980u);
    const HashGridEncoding g4(4, grid(1, 14, 1, 512, 1.5));
    const int d[4] = {100, 200, 300, 5};
    EXPECT_EQ(g4.entryIndex(0, d), 15993u);
    const HashGridEncoding dense(3, grid(1, 10, 1, 4, 1.5));  // 5^3 = 125 ≤ 1024
    ASSERT_TRUE(dense.levelIsDense(0));
    const int e[3] = {1, 2, 3};
    EXPECT_EQ(dense.entryIndex(0, e), 86u);

    // The forward pass reads those entries: u = (0.5, 0.25, 0.75) at res 16 is vertex (8, 4, 12)
    // with weight 1; halfway to (9, 4, 12) it averages entries 48 and 49.
    std::vector<double> params(1024, 0.0);
    params[48] = 1.0;
    params[49] = 3.0;
    MatX<double> x(3, 2), out(1, 2);
    x << 0.0, 2 * (8.5 / 16) - 1, -0.5, -0.5, 0.5, 0.5;
    g3.forward(params.data(), x, out);
    EXPECT_EQ(out(0, 0), 1.0);
    EXPECT_EQ(out(0, 1), 2.0);
}

TEST(Encoding, HashGridLevelResolutionsAreFloorOfBaseTimesGrowthPowers) {
    const HashGridEncoding a(3, grid(4, 14, 2, 16, 1.5));
    const int expectedA[4] = {16, 24, 36, 54};
    for (int l = 0; l < 4; ++l) EXPECT_EQ(a.levelResolution(l), expectedA[l]);
    // 16·1.26 = 20.16, 16·1.5876 = 25.4016, 16·2.000376 = 32.006016
    const HashGridEncoding b(3, grid(4, 14, 2, 16, 1.26));
    const int expectedB[4] = {16, 20, 25, 32};
    for (int l = 0; l < 4; ++l) EXPECT_EQ(b.levelResolution(l), expectedB[l]);
    EXPECT_EQ(b.numParams(), 4 * 16384 * 2);
    EXPECT_EQ(b.outputDims(), 8);
    // (res + 1)^3 against T = 16384: 17^3 = 4913 and 21^3 = 9261 fit (dense), 26^3 = 17576 does not.
    EXPECT_TRUE(b.levelIsDense(0));
    EXPECT_TRUE(b.levelIsDense(1));
    EXPECT_FALSE(b.levelIsDense(2));
}

TEST(Encoding, FrequencyAndOneBlobInputGradientsMatchFiniteDifferences) {
    // Some inputs beyond ±1 exercise one_blob's clamp (zero gradient there).
    const MatX<double> x = randomInputs(3, 30, 21, 1.1);
    const FrequencyEncoding freq(3, {4, true});
    const OneBlobEncoding blob(3, {8});
    for (const Encoding* enc : std::initializer_list<const Encoding*>{&freq, &blob}) {
        const MatX<double> w = randomInputs(enc->outputDims(), x.cols(), 22);
        MatX<double> dX(3, x.cols());
        enc->backwardInputs(static_cast<const double*>(nullptr), x, w, dX);
        const MatX<double> num = numericInputGradient(*enc, nullptr, x, w, 1e-6);
        std::vector<bool> skip(size_t(x.cols()), false);
        for (Eigen::Index n = 0; n < x.cols(); ++n)
            for (int i = 0; i < 3; ++i) skip[size_t(n)] = skip[size_t(n)] || std::abs(std::abs(x(i, n)) - 1) < 1e-4;
        EXPECT_GE(expectInputGradientsMatch(dX, num, skip, 1e-6, enc->typeName()), 25);
        if (enc == &blob)
            for (Eigen::Index n = 0; n < x.cols(); ++n)
                for (int i = 0; i < 3; ++i)
                    if (std::abs(x(i, n)) > 1) {
                    EXPECT_EQ(dX(i, n), 0.0);
                }
    }
}

TEST(Encoding, HashGridInputGradientsMatchFiniteDifferences) {
    // Levels of resolution 4, 8, 16, 32: dense and hashed levels for every d.
    for (int d = 1; d <= 4; ++d) {
        const HashGridEncoding g(d, grid(4, 12, 2, 4, 2.0));
        const std::vector<double> params = randomParams(g.numParams(), 30 + d);
        const MatX<double> x = randomInputs(d, 40, 31 + d, 1.05);
        const MatX<double> w = randomInputs(g.outputDims(), x.cols(), 32 + d);
        MatX<double> dX(d, x.cols());
        g.backwardInputs(params.data(), x, w, dX);
        const MatX<double> num = numericInputGradient(g, params.data(), x, w, 1e-7);
        std::vector<bool> skip(size_t(x.cols()));
        for (Eigen::Index n = 0; n < x.cols(); ++n) skip[size_t(n)] = nearKink(g, x, n, 1e-5);
        EXPECT_GE(expectInputGradientsMatch(dX, num, skip, 1e-6, "hash_grid d=" + std::to_string(d)), 25);
        for (Eigen::Index n = 0; n < x.cols(); ++n)
            for (int i = 0; i < d; ++i)
                if (std::abs(x(i, n)) > 1) {
                    EXPECT_EQ(dX(i, n), 0.0);
                }
    }
}

TEST(Encoding, HashGridParameterGradientsMatchFiniteDifferencesAndTouchedCoversThem) {
    const HashGridEncoding g(3, grid(3, 10, 2, 4, 2.0));  // res 4 dense, 8 and 16 hashed
    ASSERT_TRUE(g.levelIsDense(0));
    ASSERT_FALSE(g.levelIsDense(2));
    const std::vector<double> params = randomParams(g.numParams(), 40);
    const MatX<double> x = randomInputs(3, 6, 41);
    const MatX<double> w = randomInputs(g.outputDims(), x.cols(), 42);
    std::vector<double> grad(params.size(), 1.0);  // backwardParams adds
    std::vector<int64_t> touched;
    g.backwardParams(params.data(), x, w, grad.data(), &touched);
    const std::vector<double> num = numericParamGradient(g, params, x, w, 1e-3);
    EXPECT_EQ(touched.size(), size_t(6 * 3 * 8 * 2));  // samples · levels · corners · features
    const std::set<int64_t> touchedSet(touched.begin(), touched.end());
    int nonzero = 0;
    for (size_t i = 0; i < params.size(); ++i) {
        EXPECT_NEAR(grad[i] - 1.0, num[i], 1e-9) << "param " << i;
        if (num[i] != 0) {
            ++nonzero;
            EXPECT_TRUE(touchedSet.count(int64_t(i))) << "param " << i << " has a gradient but is not touched";
        }
    }
    EXPECT_GT(nonzero, 100);
    // Every touched entry appears with all its F features.
    for (int64_t t : touchedSet) EXPECT_TRUE(touchedSet.count(t ^ 1)) << t;
}

TEST(Encoding, InputEncodingGradientsMatchFiniteDifferencesWithGlobalParameterIndices) {
    const InputEncoding e = parse(R"([
        {"type": "frequency", "inputs": "view", "frequencies": 3},
        {"type": "hash_grid", "inputs": "position", "levels": 2, "log2_table_size": 10, "features_per_level": 2,
         "base_resolution": 4, "growth": 2},
        {"type": "one_blob", "inputs": "normal", "bins": 5},
        {"type": "hash_grid", "inputs": ["light"], "levels": 2, "log2_table_size": 10, "features_per_level": 1,
         "base_resolution": 3, "growth": 1.5}])",
                                  14);
    ASSERT_EQ(e.numParams(), 2 * 1024 * 2 + 2 * 1024 * 1);
    ASSERT_EQ(e.components[1].paramOffset, 0);
    ASSERT_EQ(e.components[3].paramOffset, 4096);
    ASSERT_EQ(e.outputs(), 3 * 7 + 4 + 3 * 5 + 2 + 2);
    const auto& posGrid = dynamic_cast<const HashGridEncoding&>(*e.components[1].encoding);
    const auto& lightGrid = dynamic_cast<const HashGridEncoding&>(*e.components[3].encoding);

    const std::vector<double> params = randomParams(e.numParams(), 50);
    const MatX<double> x = randomInputs(14, 30, 51);
    const MatX<double> w = randomInputs(e.outputs(), x.cols(), 52);
    MatX<double> dX;
    e.backwardInputs(params.data(), x, w, dX);
    ASSERT_EQ(dX.rows(), 14);
    const MatX<double> num = numericInputGradient(e, params.data(), x, w, 1e-7);
    std::vector<bool> skip(size_t(x.cols()));
    for (Eigen::Index n = 0; n < x.cols(); ++n)
        skip[size_t(n)] = nearKink(posGrid, x, n, 1e-5, 0) || nearKink(lightGrid, x, n, 1e-5, 6);
    EXPECT_GE(expectInputGradientsMatch(dX, num, skip, 1e-6, "InputEncoding"), 20);
    // Pass-through inputs (BRDF 12, 13) get their feature's gradient unchanged (the last two rows).
    EXPECT_EQ(dX.row(12), w.row(e.outputs() - 2));
    EXPECT_EQ(dX.row(13), w.row(e.outputs() - 1));

    const MatX<double> xs = x.leftCols(4), ws = w.leftCols(4);
    std::vector<double> grad(params.size(), 0.0);
    std::vector<int64_t> touched;
    e.backwardParams(params.data(), xs, ws, grad.data(), &touched);
    const std::vector<double> numP = numericParamGradient(e, params, xs, ws, 1e-3);
    const std::set<int64_t> touchedSet(touched.begin(), touched.end());
    int inSecond = 0;
    for (size_t i = 0; i < params.size(); ++i) {
        EXPECT_NEAR(grad[i], numP[i], 1e-9) << "param " << i;
        if (numP[i] != 0) {
            EXPECT_TRUE(touchedSet.count(int64_t(i))) << "param " << i;
        }
    }
    for (int64_t t : touchedSet) {
        EXPECT_GE(t, 0);
        EXPECT_LT(t, e.numParams());
        inSecond += t >= 4096;
    }
    EXPECT_EQ(touched.size(), size_t(4 * (2 * 8 * 2 + 2 * 8 * 1)));
    EXPECT_GT(inSecond, 0);
}

TEST(Encoding, FloatAndDoublePassesComputeTheSameFormula) {
    const InputEncoding e = parse(R"([
        {"type": "hash_grid", "inputs": "position", "levels": 6, "log2_table_size": 12, "base_resolution": 8},
        {"type": "frequency", "inputs": "view", "frequencies": 5},
        {"type": "one_blob", "inputs": "light", "bins": 12}])");
    const std::vector<double> pd = randomParams(e.numParams(), 60);
    const std::vector<float> pf(pd.begin(), pd.end());
    const MatX<double> xd = randomInputs(16, 50, 61, 1.05);
    const MatX<float> xf = xd.cast<float>();
    MatX<double> fd, dXd;
    MatX<float> ff, dXf;
    e.forward(pd.data(), xd, fd);
    e.forward(pf.data(), xf, ff);
    EXPECT_LT((ff.cast<double>() - fd).cwiseAbs().maxCoeff(), 1e-5);
    const MatX<double> wd = randomInputs(e.outputs(), xd.cols(), 62);
    const MatX<float> wf = wd.cast<float>();
    e.backwardInputs(pd.data(), xd, wd, dXd);
    e.backwardInputs(pf.data(), xf, wf, dXf);
    EXPECT_LT((dXf.cast<double>() - dXd).cwiseAbs().maxCoeff(), 1e-3 * (1 + dXd.cwiseAbs().maxCoeff()));
    std::vector<double> gd(pd.size(), 0.0);
    std::vector<float> gf(pf.size(), 0.f);
    e.backwardParams(pd.data(), xd, wd, gd.data(), nullptr);
    e.backwardParams(pf.data(), xf, wf, gf.data(), nullptr);
    for (size_t i = 0; i < gd.size(); ++i) ASSERT_NEAR(gf[i], gd[i], 1e-5 * (1 + std::abs(gd[i]))) << i;
}

TEST(Encoding, InitialParametersAreSmallUniformAndAPureFunctionOfSeedAndStream) {
    const InputEncoding e = parse(R"([{"type": "hash_grid", "inputs": "position", "levels": 2, "log2_table_size": 10},
                                      {"type": "hash_grid", "inputs": "light", "levels": 1, "log2_table_size": 10}])");
    const VecX<double> a = e.initialParams(7, 3);
    ASSERT_EQ(a.size(), 2 * 1024 * 2 + 1024 * 2);
    EXPECT_LE(a.cwiseAbs().maxCoeff(), 1e-4);
    EXPECT_GT(a.cwiseAbs().maxCoeff(), 0.9e-4);
    EXPECT_NEAR(a.mean(), 0.0, 5e-6);  // 6144 uniforms of sd 5.8e-5: the mean's sd is 7e-7
    EXPECT_EQ(a, e.initialParams(7, 3));
    EXPECT_NE(a, e.initialParams(7, 4));
    EXPECT_NE(a, e.initialParams(8, 3));
    // Component k is keyed by kEncodingStreamTag + stream·16 + k: the second grid equals a one-level
    // grid initialised alone.
    const HashGridEncoding alone(3, grid(1, 10, 2, 16, 1.5));
    std::vector<double> p(size_t(alone.numParams()));
    alone.initParams(p.data(), 7, kEncodingStreamTag + 3 * 16 + 1);
    for (size_t i = 0; i < p.size(); ++i) ASSERT_EQ(a[Eigen::Index(4096 + i)], p[i]) << i;
    // The identity has no parameters.
    EXPECT_EQ(parse("[]").initialParams(7, 3).size(), 0);
}

TEST(Encoding, InitialParametersDoNotReuseTheMlpsRandomNumbers) {
    // The MLP's initial weights of (seed, stream) draw from Rng(seed, stream·128 + layer, neuron)
    // (mlp.cpp). A hash grid level l keyed by the bare stream would start with the very number neuron
    // l of layer 0 draws; no level's first value may be (2u − 1)·1e-4 of any of those first draws.
    const InputEncoding e = parse(R"([{"type": "hash_grid", "inputs": "position", "levels": 8, "log2_table_size": 10,
                                       "features_per_level": 1}])");
    for (uint64_t stream = 0; stream < 4; ++stream) {
        const VecX<double> a = e.initialParams(7, stream);
        ASSERT_EQ(a.size(), 8 * 1024);
        for (uint64_t s = 0; s < 4 * 128; ++s)
            for (uint64_t neuron = 0; neuron < 8; ++neuron) {
                Rng mlp(7, s, neuron);
                const double mlpValue = (2.0 * mlp.uniformDouble() - 1.0) * 1e-4;
                for (Eigen::Index l = 0; l < 8; ++l)
                    ASSERT_NE(a[l * 1024], mlpValue) << "stream " << stream << " level " << l << " = MLP stream " << s;
            }
    }
}

TEST(Encoding, JsonErrorsNameFileAndPointer) {
    struct Case {
        const char* json;
        int inputs;
        const char* pointer;
        const char* mentions;
    };
    const Case cases[] = {
        {R"({"type": "frequency"})", 16, "/network/encoding", "array"},
        {R"([{"type": "fourier", "inputs": "view"}])", 16, "/network/encoding/0/type", "fourier"},
        {R"([{"type": "frequency", "inputs": "view", "freqs": 4}])", 16, "/network/encoding/0/freqs", "freqs"},
        {R"([{"type": "frequency"}])", 16, "/network/encoding/0", "inputs"},
        {R"([{"type": "frequency", "inputs": 3}])", 16, "/network/encoding/0/inputs", "group"},
        {R"([{"type": "frequency", "inputs": []}])", 16, "/network/encoding/0/inputs", "at least one"},
        {R"([{"type": "frequency", "inputs": ["view", "colour"]}])", 16, "/network/encoding/0/inputs/1", "colour"},
        {R"([{"type": "frequency", "inputs": ["view", "view"]}])", 16, "/network/encoding/0/inputs/1", "twice"},
        {R"([{"type": "frequency", "inputs": "view"}, {"type": "one_blob", "inputs": ["light", "view"]}])", 16,
         "/network/encoding/1/inputs/1", "component 0"},
        {R"([{"type": "one_blob", "inputs": "brdf"}])", 12, "/network/encoding/0/inputs", "empty"},
        {R"([{"type": "frequency", "inputs": "view", "frequencies": 17}])", 16, "/network/encoding/0/frequencies", "17"},
        {R"([{"type": "frequency", "inputs": "view", "include_input": 1}])", 16, "/network/encoding/0/include_input", "true or false"},
        {R"([{"type": "one_blob", "inputs": "view", "bins": 1}])", 16, "/network/encoding/0/bins", "1"},
        {R"([{"type": "hash_grid", "inputs": "position", "levels": 25}])", 16, "/network/encoding/0/levels", "25"},
        {R"([{"type": "hash_grid", "inputs": "position", "log2_table_size": 9}])", 16,
         "/network/encoding/0/log2_table_size", "9"},
        {R"([{"type": "hash_grid", "inputs": "position", "features_per_level": 3}])", 16,
         "/network/encoding/0/features_per_level", "1, 2, 4 or 8"},
        {R"([{"type": "hash_grid", "inputs": "position", "base_resolution": 1}])", 16,
         "/network/encoding/0/base_resolution", "1"},
        {R"([{"type": "hash_grid", "inputs": "position", "growth": 0.5}])", 16, "/network/encoding/0/growth", "0.5"},
        {R"([{"type": "hash_grid", "inputs": ["position", "view"]}])", 16, "/network/encoding/0/inputs", "at most 4"},
        {R"([{"type": "hash_grid", "inputs": "position", "levels": 24, "base_resolution": 1024, "growth": 4}])", 16,
         "/network/encoding/0", "2^24"},
        {R"([{"type": "hash_grid", "inputs": "position", "levels": 24, "log2_table_size": 22, "features_per_level": 8,
              "growth": 1}])", 16, "/network/encoding/0", "parameters"},
    };
    for (const Case& c : cases) {
        const InputError e = parseError(c.json, c.inputs);
        EXPECT_EQ(e.file(), "project.json") << c.json;
        EXPECT_EQ(e.where(), c.pointer) << c.json << ": " << e.what();
        EXPECT_NE(e.detail().find(c.mentions), std::string::npos) << c.json << ": " << e.what();
    }
}

TEST(Encoding, ToJsonWritesEveryKeyAndReadsBackEqual) {
    const InputEncoding e = parse(R"([{"type": "hash_grid", "inputs": "position"},
                                      {"type": "frequency", "inputs": ["view", "normal"]},
                                      {"type": "one_blob", "inputs": "light"}])");
    const nlohmann::json expected = nlohmann::json::parse(R"([
        {"type": "hash_grid", "inputs": "position", "levels": 16, "log2_table_size": 14, "features_per_level": 2,
         "base_resolution": 16, "growth": 1.5},
        {"type": "frequency", "inputs": ["view", "normal"], "frequencies": 6, "include_input": true},
        {"type": "one_blob", "inputs": "light", "bins": 16}])");
    EXPECT_EQ(toJson(e), expected);
    EXPECT_EQ(parse(toJson(e).dump()), e);
    EXPECT_NE(parse(R"([{"type": "one_blob", "inputs": "light", "bins": 8}])"), e);
    EXPECT_EQ(e.describe(), "hash_grid(position) + frequency(view,normal) + one_blob(light)");
    EXPECT_EQ(e.outputs(), 16 * 2 + 6 * 13 + 3 * 16 + 4);
    EXPECT_EQ(encodingGroupInputs("brdf", 16), (std::vector<int>{12, 13, 14, 15}));
    EXPECT_EQ(encodingGroupInputs("normal", 16), (std::vector<int>{9, 10, 11}));
    EXPECT_THROW(encodingGroupInputs("colour", 16), std::invalid_argument);
}

}  // namespace test_encodings
