#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "core/eval/flip.h"
#include "core/util/image.h"
#include "tests/flip_by_hand.h"

namespace test_flip {

using namespace rrf;
using namespace flip_by_hand;

namespace {

Image randomImage(int w, int h, float lo, float hi, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(lo, hi);
    Image img(w, h);
    for (float& v : img.data) v = u(rng);
    return img;
}

}  // namespace

TEST(Flip, IdenticalImagesGiveExactlyZero) {
    const Image a = randomImage(37, 29, 0.f, 1.f, 1);
    for (const Image& m : {ldrFlip(a, a), flipColourDifference(a, a), flipFeatureDifference(a, a)})
        for (float v : m.data) ASSERT_EQ(v, 0.f);
    const Image hdr = randomImage(37, 29, 0.f, 50.f, 2);
    for (float v : hdrFlip(hdr, hdr, flipExposureRange(hdr)).data) ASSERT_EQ(v, 0.f);
}

TEST(Flip, OutputStaysInUnitRange) {
    // Out-of-range inputs too: LDR-FLIP clamps to [0, 1], HDR-FLIP clamps negatives to 0.
    const Image a = randomImage(40, 32, -0.5f, 1.5f, 3), b = randomImage(40, 32, -0.5f, 1.5f, 4);
    const Image h1 = randomImage(40, 32, 0.f, 20.f, 5), h2 = randomImage(40, 32, 0.f, 20.f, 6);
    for (const Image& m : {ldrFlip(a, b), flipColourDifference(a, b), flipFeatureDifference(a, b),
                           hdrFlip(h1, h2, flipExposureRange(h1))})
        for (float v : m.data) {
            ASSERT_GE(v, 0.f);
            ASSERT_LE(v, 1.f);
        }
}

TEST(Flip, SymmetricInReferenceAndTest) {
    // HyAB and the feature difference |‖·‖ − ‖·‖| are symmetric, so LDR-FLIP is; HDR-FLIP is for a
    // fixed exposure range (the automatic range depends on the reference alone).
    const Image a = randomImage(33, 21, 0.f, 1.f, 7), b = randomImage(33, 21, 0.f, 1.f, 8);
    EXPECT_EQ(ldrFlip(a, b).data, ldrFlip(b, a).data);
    const Image h1 = randomImage(33, 21, 0.f, 8.f, 9), h2 = randomImage(33, 21, 0.f, 8.f, 10);
    const FlipExposureRange range = flipExposureRange(h1);
    EXPECT_EQ(hdrFlip(h1, h2, range).data, hdrFlip(h2, h1, range).data);
}

TEST(Flip, FlatFieldColourErrorMatchesClosedForm) {
    // Clamp-to-edge keeps a uniform image uniform under every filter, borders included, so each
    // pixel's error is the closed-form colour error; the feature term is 0 (up to rounding).
    struct Case {
        Vec3 ref, test;
    };
    const Case cases[] = {
        {Vec3(0.f), Vec3(1.f)},                                // above pc · cmax: the (pt, 1] branch
        {Vec3(0.5f), Vec3(0.55f, 0.5f, 0.5f)},                 // below: the [0, pt] branch
        {Vec3(1.f, 0.f, 0.f), Vec3(0.f, 0.f, 1.f)},
        {Vec3(0.2f, 0.7f, 0.1f), Vec3(0.25f, 0.6f, 0.3f)},
    };
    for (const Case& c : cases) {
        const Image r(48, 40, c.ref), t(48, 40, c.test);
        const double expected = handColourError(c.ref, c.test);
        const Image colour = flipColourDifference(r, t), feature = flipFeatureDifference(r, t), flip = ldrFlip(r, t);
        for (size_t i = 0; i < flip.data.size(); i += 3) {
            ASSERT_NEAR(colour.data[i], expected, 2e-5) << c.ref << " vs " << c.test;
            ASSERT_NEAR(feature.data[i], 0.0, 1e-3);
            ASSERT_NEAR(flip.data[i], expected, 1e-4);
        }
    }
    // Black against white: |ΔL| = 100, no chroma, 100^0.7 = 25.1189 > 0.4 cmax.
    EXPECT_NEAR(handColourError(Vec3(0.f), Vec3(1.f)), 0.967378, 1e-5);
}

TEST(Flip, StepEdgeFeatureErrorMatchesClosedForm) {
    // Reference: black left half, white right half; test: uniform grey (no features). Next to the
    // step, the edge filter's positive (or negative) weights all fall on white: response −1, so
    // ΔEf = ((1/√2) · 1)^0.5 = 2^−1/4 (the point response there is |k(0)| / 2 < 1). Farther than
    // the filter radius (⌈3 · 0.5 · 0.082 · 67⌉ = 9 pixels) from the step it is 0.
    const int w = 64, h = 16;
    Image ref(w, h), test(w, h, Vec3(0.5f));
    for (int y = 0; y < h; ++y)
        for (int x = w / 2; x < w; ++x) ref.set(x, y, Vec3(1.f));
    const Image feature = flipFeatureDifference(ref, test), colour = flipColourDifference(ref, test);
    const Image flip = ldrFlip(ref, test);
    for (int y = 0; y < h; ++y) {
        for (int x : {w / 2 - 1, w / 2}) {
            EXPECT_NEAR(feature.at(x, y).x, std::pow(2.0, -0.25), 1e-5);
            EXPECT_NEAR(flip.at(x, y).x, std::pow(colour.at(x, y).x, 1.0 - std::pow(2.0, -0.25)), 1e-5);
        }
        for (int x : {0, 5, w / 2 - 12, w / 2 + 11, w - 1}) EXPECT_NEAR(feature.at(x, y).x, 0.0, 1e-3);
    }
}

TEST(Flip, MatchesADirect2DImplementationOfThePaper) {
    // The separable filters, their normalisation and the clamp-to-edge border against the paper's
    // 2D kernels applied directly, at the default and at a lower pixels-per-degree.
    const Image a = randomImage(26, 19, -0.1f, 1.1f, 14);
    Image b = a;
    const Image noise = randomImage(26, 19, -0.3f, 0.3f, 15);
    for (size_t i = 0; i < b.data.size(); ++i) b.data[i] += (i / 3) % 4 == 0 ? noise.data[i] : 0.f;
    for (double ppd : {kFlipDefaultPixelsPerDegree, 30.0}) {
        const Image fast = ldrFlip(a, b, FlipSettings{ppd}), direct = bruteLdrFlip(a, b, ppd);
        double worst = 0;
        for (size_t i = 0; i < fast.data.size(); i += 3) worst = std::max(worst, std::fabs(double(fast.data[i]) - direct.data[i]));
        EXPECT_LT(worst, 2e-4) << "ppd " << ppd;
    }
}

TEST(Flip, HdrFlipIsTheMaxOverExposures) {
    const Image ref = randomImage(24, 20, 0.f, 6.f, 11), test = randomImage(24, 20, 0.f, 6.f, 12);
    // count 3 from −1.5 to 1.5: exposures −1.5, 0, 1.5.
    const FlipExposureRange range{-1.5, 1.5, 3};
    std::vector<int> which;
    const Image hdr = hdrFlip(ref, test, range, {}, &which);
    std::vector<Image> ldr;
    for (double c : {-1.5, 0.0, 1.5}) ldr.push_back(ldrFlip(flipToneMap(ref, c), flipToneMap(test, c)));
    for (size_t p = 0; p < hdr.pixelCount(); ++p) {
        const float e = hdr.data[3 * p];
        ASSERT_GE(e, ldr[1].data[3 * p]);  // HDR-FLIP ≥ LDR-FLIP at exposure 0
        ASSERT_EQ(e, std::max({ldr[0].data[3 * p], ldr[1].data[3 * p], ldr[2].data[3 * p]}));
        ASSERT_GE(which[p], 0);
        ASSERT_EQ(e, ldr[size_t(which[p])].data[3 * p]);
    }
    // A difference only in the dark: nearly invisible at exposure 0, clear at the exposures the
    // reference's range picks (its median brought up to 0.85).
    const Image dark(32, 32, Vec3(0.001f)), darker(32, 32, Vec3(0.002f));
    const double atZero = ldrFlip(flipToneMap(dark, 0), flipToneMap(darker, 0)).data[0];
    const double hdrValue = hdrFlip(dark, darker, flipExposureRange(dark)).data[0];
    EXPECT_GT(hdrValue, atZero + 0.1);
}

TEST(Flip, ExposureRangeMatchesClosedForm) {
    const double x85 = handX85();
    EXPECT_NEAR(x85, 2.11887, 1e-4);
    // Uniform luminance L: max = median = L, so start = stop = log2(x85 / L) and count = 2.
    const FlipExposureRange uniform = flipExposureRange(Image(8, 8, Vec3(0.25f)));
    EXPECT_NEAR(uniform.start, std::log2(x85 / 0.25), 1e-9);
    EXPECT_NEAR(uniform.stop, std::log2(x85 / 0.25), 1e-9);
    EXPECT_EQ(uniform.count, 2);
    // Grey pixels 0.01, 0.02, 0.03, 4, 5 (odd count: median 0.03): count ⌈log2(5 / 0.03)⌉ = 8.
    Image five(5, 1);
    const float ys[5] = {4.f, 0.02f, 5.f, 0.01f, 0.03f};
    for (int x = 0; x < 5; ++x) five.set(x, 0, Vec3(ys[x]));
    const FlipExposureRange r5 = flipExposureRange(five);
    EXPECT_NEAR(r5.start, std::log2(x85 / 5.0), 1e-6);
    EXPECT_NEAR(r5.stop, std::log2(x85 / 0.03), 1e-6);
    EXPECT_EQ(r5.count, 8);
    // The brightest pixel tone maps to 0.85 at the start exposure.
    EXPECT_NEAR(flipToneMap(five, r5.start).at(2, 0).x, 0.85, 1e-6);
    EXPECT_NEAR(flipExposure(r5, 0), r5.start, 1e-12);
    EXPECT_NEAR(flipExposure(r5, 7), r5.stop, 1e-12);
    // Even count: the median interpolates the middle two, (0.01 + 1) / 2.
    Image four(4, 1);
    const float ys4[4] = {1.f, 0.01f, 1.f, 0.01f};
    for (int x = 0; x < 4; ++x) four.set(x, 0, Vec3(ys4[x]));
    EXPECT_NEAR(flipExposureRange(four).stop, std::log2(x85 / 0.505), 1e-6);
    // Mostly black: the median of the lit pixels; all black: 0, 0.
    Image mostlyBlack(4, 1);
    mostlyBlack.set(3, 0, Vec3(0.5f));
    EXPECT_NEAR(flipExposureRange(mostlyBlack).stop, std::log2(x85 / 0.5), 1e-6);
    const FlipExposureRange black = flipExposureRange(Image(4, 4));
    EXPECT_EQ(black.start, 0.0);
    EXPECT_EQ(black.stop, 0.0);
}

TEST(Flip, MagmaEndsMatchThePublishedMap) {
    // matplotlib's magma, first and last sRGB entries.
    const Vec3 lo = magma(0.f), hi = magma(1.f);
    EXPECT_FLOAT_EQ(lo.x, srgbToLinear(0.001462f));
    EXPECT_FLOAT_EQ(lo.y, srgbToLinear(0.000466f));
    EXPECT_FLOAT_EQ(lo.z, srgbToLinear(0.013866f));
    EXPECT_FLOAT_EQ(hi.x, srgbToLinear(0.987053f));
    EXPECT_FLOAT_EQ(hi.y, srgbToLinear(0.991438f));
    EXPECT_FLOAT_EQ(hi.z, srgbToLinear(0.749504f));
    // Entry 128 of 256 (0.716387, 0.214982, 0.475290) sits at t = 128 / 255.
    const Vec3 mid = magma(128.f / 255.f);
    EXPECT_NEAR(linearToSrgb(mid.x), 0.716387, 3.0 / 255);
    EXPECT_NEAR(linearToSrgb(mid.y), 0.214982, 3.0 / 255);
    EXPECT_NEAR(linearToSrgb(mid.z), 0.475290, 3.0 / 255);
    EXPECT_EQ(magma(-1.f), lo);
    EXPECT_EQ(magma(2.f), hi);
    Image map(2, 1);
    map.set(0, 0, Vec3(std::numeric_limits<float>::quiet_NaN()));
    map.set(1, 0, Vec3(1.f));
    const Image c = flipColour(map);
    EXPECT_EQ(c.at(0, 0), Vec3(1.f, 0.f, 1.f));
    EXPECT_EQ(c.at(1, 0), hi);
}

TEST(Flip, WeightedPercentilesMatchHandComputation) {
    // Errors 0.1, 0.4, 0.2, 0.3 and a NaN. Sorted 0.1 0.2 0.3 0.4, cumulative 0.1 0.3 0.6 1.0.
    // p = 0.5: first cumulative ≥ 0.5 is index 2 → (0.3 + 0.4) / 2; p = 0.25: index 1 →
    // (0.2 + 0.3) / 2; p = 0.75: index 3, the last → 0.4.
    Image map(5, 1);
    const float v[5] = {0.1f, 0.4f, 0.2f, std::numeric_limits<float>::quiet_NaN(), 0.3f};
    for (int x = 0; x < 5; ++x) map.set(x, 0, Vec3(v[x]));
    const FlipStats s = flipStats(map);
    EXPECT_EQ(s.pixels, 4u);
    EXPECT_EQ(s.nonFinite, 1u);
    EXPECT_NEAR(s.mean, 0.25, 1e-7);
    EXPECT_NEAR(s.weightedMedian, 0.35, 1e-7);
    EXPECT_NEAR(s.weightedFirstQuartile, 0.25, 1e-7);
    EXPECT_NEAR(s.weightedThirdQuartile, 0.4, 1e-7);
    EXPECT_NEAR(s.min, 0.1, 1e-7);
    EXPECT_NEAR(s.max, 0.4, 1e-7);
    // Mask {1, 4, 4}: 0.4, 0.3, 0.3 → sorted 0.3 0.3 0.4, cumulative 0.3 0.6 1.0.
    const FlipStats m = flipStats(map, {1, 4, 4});
    EXPECT_EQ(m.pixels, 3u);
    EXPECT_NEAR(m.mean, 1.0 / 3.0, 1e-7);
    EXPECT_NEAR(m.weightedMedian, 0.35, 1e-7);         // index 1
    EXPECT_NEAR(m.weightedFirstQuartile, 0.3, 1e-7);   // index 0
    EXPECT_NEAR(m.weightedThirdQuartile, 0.4, 1e-7);   // index 2
    EXPECT_THROW(flipStats(map, {5}), std::out_of_range);
    const FlipStats zero = flipStats(Image(3, 3));
    EXPECT_EQ(zero.weightedMedian, 0.0);
    EXPECT_EQ(zero.pixels, 9u);
    EXPECT_EQ(flipStats(map, {3}).pixels, 0u);
}

TEST(Flip, NonFinitePixelsAreNaNAndLeftOutOfStats) {
    const Image a = randomImage(20, 20, 0.f, 1.f, 13);
    Image b = a;
    b.set(4, 5, Vec3(std::numeric_limits<float>::infinity(), 0.f, 0.f));
    const Image e = ldrFlip(a, b);
    EXPECT_TRUE(std::isnan(e.at(4, 5).x));
    EXPECT_EQ(e.nonFiniteCount(), 1u);
    EXPECT_EQ(flipStats(e).nonFinite, 1u);
    std::vector<int> which;
    const Image h = hdrFlip(a, b, flipExposureRange(a), {}, &which);
    EXPECT_TRUE(std::isnan(h.at(4, 5).x));
    EXPECT_EQ(h.nonFiniteCount(), 1u);
    EXPECT_EQ(which[5 * 20 + 4], -1);
}

TEST(Flip, RejectsInvalidInputs) {
    const Image a(8, 8), b(8, 9);
    EXPECT_THROW(ldrFlip(a, b), std::invalid_argument);
    EXPECT_THROW(ldrFlip(a, a, FlipSettings{0.0}), std::invalid_argument);
    EXPECT_THROW(ldrFlip(a, a, FlipSettings{std::nan("")}), std::invalid_argument);
    EXPECT_THROW(hdrFlip(a, a, FlipExposureRange{0, 1, 0}), std::invalid_argument);
    EXPECT_THROW(hdrFlip(a, a, FlipExposureRange{0, INFINITY, 2}), std::invalid_argument);
    EXPECT_TRUE(ldrFlip(Image(), Image()).empty());
    EXPECT_NEAR(kFlipDefaultPixelsPerDegree, 67.02, 0.01);
}

}  // namespace test_flip
