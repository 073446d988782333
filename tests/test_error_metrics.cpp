// Error metrics on hand-made images with known answers, object masks, NaN handling.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "core/eval/error_metrics.h"
#include "core/eval/error_metrics_json.h"
#include "core/util/image.h"
#include "tests/image_builders.h"

namespace test_error_metrics {

using namespace rrf;

namespace {
Image make(int w, int h, std::initializer_list<Vec3> pixels) { return test::imageOf(w, h, pixels); }
}  // namespace

TEST(ErrorMetrics, KnownAnswersOverAllPixels) {
    // d = +1 in every channel of pixel 0 (ref 0) and -2 in every channel of pixel 1 (ref 3).
    const Image ref = make(2, 1, {Vec3(0.f), Vec3(3.f)});
    const Image pred = make(2, 1, {Vec3(1.f), Vec3(1.f)});
    const ErrorStats s = errorStats(pred, ref);
    EXPECT_EQ(s.pixels, 2u);
    EXPECT_EQ(s.nonFinite, 0u);
    EXPECT_DOUBLE_EQ(s.rmse, std::sqrt((1.0 + 4.0) / 2.0));
    EXPECT_DOUBLE_EQ(s.mae, 1.5);
    EXPECT_DOUBLE_EQ(s.maxError, 2.0);
    EXPECT_DOUBLE_EQ(s.meanReference, 1.5);
    const double r0 = 1.0 / 0.01, r1 = 2.0 / 3.01;
    EXPECT_NEAR(s.relativeRmse, std::sqrt((r0 * r0 + r1 * r1) / 2.0), 1e-9);
}

TEST(ErrorMetrics, ChannelsAreAveragedNotLuminance) {
    // Only the blue channel is wrong: luminance weighs it 0.0722, the per-channel average 1/3.
    const Image ref = make(1, 1, {Vec3(1.f, 1.f, 1.f)});
    const Image pred = make(1, 1, {Vec3(1.f, 1.f, 4.f)});
    const ErrorStats s = errorStats(pred, ref);
    EXPECT_DOUBLE_EQ(s.mae, 1.0);
    EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(3.0));
    EXPECT_DOUBLE_EQ(s.maxError, 3.0);
}

TEST(ErrorMetrics, MapsHoldPerPixelValues) {
    const Image ref = make(2, 1, {Vec3(0.f), Vec3(0.99f)});
    const Image pred = make(2, 1, {Vec3(0.5f), Vec3(0.99f + 0.5f)});
    const Image a = errorMap(pred, ref, ErrorMapKind::Absolute);
    const Image r = errorMap(pred, ref, ErrorMapKind::Relative);
    const Image q = errorMap(pred, ref, ErrorMapKind::Squared);
    EXPECT_FLOAT_EQ(a.at(0, 0).x, 0.5f);
    EXPECT_FLOAT_EQ(a.at(0, 0).z, 0.5f);
    EXPECT_NEAR(r.at(0, 0).x, 50.f, 1e-4);  // 0.5 / (0 + 0.01)
    EXPECT_NEAR(r.at(1, 0).y, 0.5f, 1e-6);   // 0.5 / (0.99 + 0.01)
    EXPECT_FLOAT_EQ(q.at(1, 0).x, 0.25f);
}

TEST(ErrorMetrics, ObjectMasksSelectPixelsById) {
    // 3x2 object-id buffer: background, object 0, object 1 (ids ≥ count are ignored).
    const std::vector<int32_t> ids = {-1, 0, 1, 0, 1, 7};
    const auto masks = objectMasks(ids, 2);
    ASSERT_EQ(masks.size(), 2u);
    EXPECT_EQ(masks[0], (std::vector<uint32_t>{1, 3}));
    EXPECT_EQ(masks[1], (std::vector<uint32_t>{2, 4}));
    // Object 0 exact, object 1 off by 1 everywhere, background off by 100 (outside both masks).
    const Image ref(3, 2, Vec3(1.f));
    Image pred = ref;
    pred.set(0, 0, Vec3(101.f));
    pred.set(2, 0, Vec3(2.f));
    pred.set(1, 1, Vec3(2.f));
    const ErrorStats s0 = errorStats(pred, ref, masks[0]);
    const ErrorStats s1 = errorStats(pred, ref, masks[1]);
    EXPECT_EQ(s0.pixels, 2u);
    EXPECT_DOUBLE_EQ(s0.rmse, 0.0);
    EXPECT_EQ(s1.pixels, 2u);
    EXPECT_DOUBLE_EQ(s1.rmse, 1.0);
    EXPECT_NEAR(s1.relativeRmse, 1.0 / 1.01, 1e-7);
    EXPECT_EQ(errorStats(pred, ref, {}).pixels, 0u);
}

TEST(ErrorMetrics, NonFinitePixelsAreCountedAndLeftOut) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const Image ref = make(3, 1, {Vec3(1.f), Vec3(1.f), Vec3(1.f, INFINITY, 1.f)});
    const Image pred = make(3, 1, {Vec3(2.f), Vec3(nan, 1.f, 1.f), Vec3(1.f)});
    const ErrorStats s = errorStats(pred, ref);
    EXPECT_EQ(s.pixels, 1u);
    EXPECT_EQ(s.nonFinite, 2u);
    EXPECT_DOUBLE_EQ(s.rmse, 1.0);
    const Image map = errorMap(pred, ref, ErrorMapKind::Absolute);
    EXPECT_TRUE(std::isnan(map.at(1, 0).x));
    EXPECT_TRUE(std::isnan(map.at(2, 0).x));
    uint64_t replaced = 0;
    const Image clean = finiteMap(map, replaced);
    EXPECT_EQ(replaced, 2u);
    EXPECT_EQ(clean.nonFiniteCount(), 0u);
    // False colour shows the NaN as magenta instead of a plausible error value.
    const Image fc = falseColor(map, 0.f, 1.f);
    EXPECT_EQ(fc.at(1, 0), Vec3(1.f, 0.f, 1.f));
}

TEST(ErrorMetrics, PercentileIsNearestRankOverFiniteValues) {
    Image im(101, 1);
    for (int i = 0; i <= 100; ++i) im.set(i, 0, Vec3(float(i)));
    EXPECT_FLOAT_EQ(percentile(im, 0.99), 99.f);
    EXPECT_FLOAT_EQ(percentile(im, 1.0), 100.f);
    EXPECT_FLOAT_EQ(percentile(im, 0.0), 0.f);
    im.set(50, 0, Vec3(std::numeric_limits<float>::quiet_NaN()));
    EXPECT_FLOAT_EQ(percentile(im, 1.0), 100.f);
    EXPECT_FLOAT_EQ(percentile(Image(2, 2, Vec3(NAN)), 0.5), 0.f);
}

TEST(ErrorMetrics, RejectsMismatchedSizesAndBadMasks) {
    EXPECT_THROW(errorStats(Image(2, 2), Image(2, 3)), std::invalid_argument);
    EXPECT_THROW(errorMap(Image(2, 2), Image(3, 2), ErrorMapKind::Absolute), std::invalid_argument);
    EXPECT_THROW(errorStats(Image(2, 2), Image(2, 2), std::vector<uint32_t>{4}), std::invalid_argument);
}

TEST(ErrorMetrics, PixelErrorIsTheMapAtThatPixel) {
    // A coloured pixel with a NaN neighbour: the read-out of one pixel and the map agree bit for bit.
    const Image ref = make(2, 1, {Vec3(0.8f, 0.2f, 0.05f), Vec3(1.f)});
    const Image pred = make(2, 1, {Vec3(0.5f, 0.4f, 0.05f), Vec3(NAN, 1.f, 1.f)});
    for (ErrorMapKind k : kErrorMapKinds) {
        const Image map = errorMap(pred, ref, k);
        EXPECT_EQ(pixelError(pred.at(0, 0), ref.at(0, 0), k), map.at(0, 0).x) << errorMapName(k);
        EXPECT_TRUE(std::isnan(pixelError(pred.at(1, 0), ref.at(1, 0), k))) << errorMapName(k);
    }
    EXPECT_NEAR(pixelError(pred.at(0, 0), ref.at(0, 0), ErrorMapKind::Absolute), (0.3 + 0.2 + 0.0) / 3.0, 1e-6);
    EXPECT_NEAR(pixelError(pred.at(0, 0), ref.at(0, 0), ErrorMapKind::Relative), (0.3 / 0.81 + 0.2 / 0.21) / 3.0, 1e-6);
    EXPECT_NEAR(pixelError(pred.at(0, 0), ref.at(0, 0), ErrorMapKind::Squared), (0.09 + 0.04) / 3.0, 1e-6);
}

TEST(ErrorMetrics, SignedRelMseAndSmapeKnownAnswers) {
    // Pixel 0: ref 1, pred 0.98 (2 % low); pixel 1: ref 0.5, pred 0.6 (above). Per channel, equal.
    const Image ref = make(2, 1, {Vec3(1.f), Vec3(0.5f)});
    const Image pred = make(2, 1, {Vec3(0.98f), Vec3(0.6f)});
    const ErrorStats s = errorStats(pred, ref);
    const double d0 = double(0.98f) - 1.0, d1 = double(0.6f) - double(0.5f);
    EXPECT_NEAR(s.signedRelativeMean, (d0 / 1.01 + d1 / 0.51) / 2, 1e-9);
    EXPECT_NEAR(s.relMse, (d0 * d0 / 1.01 + d1 * d1 / 0.26) / 2, 1e-9);
    EXPECT_NEAR(s.smape, (-d0 / (0.98 + 1.0 + 0.01) + d1 / (0.6 + 0.5 + 0.01)) / 2, 1e-6);
    // A uniform 2 % low bias: the signed mean says −0.02 (to the 0.01 offset), the RMSE only its size.
    const Image low = make(2, 1, {Vec3(0.98f), Vec3(0.49f)});
    const ErrorStats b = errorStats(low, ref);
    EXPECT_NEAR(b.signedRelativeMean, (-0.02 / 1.01 - 0.01 / 0.51) / 2, 1e-6);
    EXPECT_LT(b.signedRelativeMean, 0.0);
    EXPECT_NEAR(b.relativeRmse, std::fabs(b.signedRelativeMean), 1e-3);
    // Swapping prediction and reference leaves SMAPE unchanged (symmetric) and flips the sign of d.
    EXPECT_NEAR(errorStats(ref, pred).smape, s.smape, 1e-9);
    const Image signedMap = errorMap(pred, ref, ErrorMapKind::Signed);
    EXPECT_NEAR(signedMap.at(0, 0).x, d0 / 1.01, 1e-6);
    EXPECT_NEAR(errorMap(ref, pred, ErrorMapKind::Signed).at(1, 0).x, -d1 / double(0.61f), 1e-6);
    EXPECT_NEAR(errorMap(pred, ref, ErrorMapKind::RelativeSquared).at(1, 0).x, d1 * d1 / 0.26, 1e-6);
    EXPECT_NEAR(errorMap(pred, ref, ErrorMapKind::Smape).at(1, 0).x, d1 / 1.11, 1e-6);
    const nlohmann::json j = toJson(s);
    EXPECT_DOUBLE_EQ(j["signed_relative_mean"].get<double>(), s.signedRelativeMean);
    EXPECT_DOUBLE_EQ(j["relmse"].get<double>(), s.relMse);
    EXPECT_DOUBLE_EQ(j["smape"].get<double>(), s.smape);
    EXPECT_TRUE(j["relmse_corrected"].is_null());  // no variance given
}

TEST(ErrorMetrics, SignedMapsAreScaledByMagnitudeAndCentredOnZero) {
    // A signed map's scale is the p99 of |value|: −3 counts as much as +3.
    const Image map = make(4, 1, {Vec3(-3.f), Vec3(1.f), Vec3(0.f), Vec3(2.f)});
    EXPECT_FLOAT_EQ(errorMapScale(map, ErrorMapKind::Signed), 3.f);
    EXPECT_FLOAT_EQ(errorMapScale(map, ErrorMapKind::Absolute), 2.f);
    EXPECT_TRUE(errorMapIsSigned(ErrorMapKind::Signed));
    EXPECT_FALSE(errorMapIsSigned(ErrorMapKind::Relative));
    const Image c = errorMapColour(map, ErrorMapKind::Signed, 3.f);
    // Zero is the map's neutral centre (equal channels), below is blue, above is red.
    EXPECT_FLOAT_EQ(c.at(2, 0).x, c.at(2, 0).y);
    EXPECT_FLOAT_EQ(c.at(2, 0).y, c.at(2, 0).z);
    EXPECT_GT(c.at(0, 0).z, c.at(0, 0).x);
    EXPECT_GT(c.at(3, 0).x, c.at(3, 0).z);
    // The ends are Moreland's cool-warm ends, values beyond the scale clamp to them.
    EXPECT_NEAR(linearToSrgb(coolWarm(-1.f).z), 192 / 255.f, 1e-5);
    EXPECT_NEAR(linearToSrgb(coolWarm(5.f).x), 180 / 255.f, 1e-5);
    EXPECT_EQ(coolWarm(-7.f).z, coolWarm(-1.f).z);
    // Non-finite stays visible (magenta), a zero or bad scale is refused by the image function.
    const Image nanMap = make(1, 1, {Vec3(NAN)});
    EXPECT_EQ(errorMapColour(nanMap, ErrorMapKind::Signed, 1.f).at(0, 0).y, 0.f);
    EXPECT_THROW(signedFalseColor(map, 0.f), std::invalid_argument);
}

TEST(ErrorMetrics, MapKindNamesRoundTrip) {
    for (ErrorMapKind k : kErrorMapKinds) {
        ASSERT_TRUE(parseErrorMapKind(errorMapName(k)).has_value()) << errorMapName(k);
        EXPECT_EQ(*parseErrorMapKind(errorMapName(k)), k);
        EXPECT_STRNE(errorMapFormula(k), "?");
    }
    EXPECT_FALSE(parseErrorMapKind("luminance").has_value());
    EXPECT_FALSE(parseErrorMapKind("Relative").has_value());
}

}  // namespace test_error_metrics
