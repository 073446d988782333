// Draft frames of the live prediction while the light is dragged (app/gui/prediction_draft.h):
// the draft camera keeps the view at half the resolution, the draft settings divide the direct
// light's samples, and pixel replication puts each output pixel's centre in the right draft pixel.
#include <gtest/gtest.h>

#include "app/gui/prediction_draft.h"

namespace rrf::test::test_prediction_draft {
/// Pixel (x, y) of a w × h test image: a colour that names the pixel.
Vec3 named(int x, int y) { return Vec3(float(x), float(y), float(10 * x + y)); }
}  // namespace rrf::test::test_prediction_draft

using rrf::test::test_prediction_draft::named;

TEST(PredictionDraft, CameraKeepsTheViewAtHalfTheResolution) {
    rrf::Camera full;
    full.eye = rrf::Vec3(1, 2, 3);
    full.target = rrf::Vec3(0, 1, 0);
    full.fovYDegrees = 37.f;
    full.width = 255;
    full.height = 101;
    const rrf::Camera d = rrf::draftCamera(full, 2);
    EXPECT_EQ(d.width, 128);
    EXPECT_EQ(d.height, 51);
    EXPECT_EQ(rrf::draftCamera(full, 4).width, 64);
    EXPECT_EQ(rrf::draftCamera(full, 4).height, 26);
    EXPECT_EQ(rrf::draftCamera(full, 1).width, 255);
    EXPECT_EQ(d.eye, full.eye);
    EXPECT_EQ(d.target, full.target);
    EXPECT_EQ(d.up, full.up);
    EXPECT_EQ(d.fovYDegrees, full.fovYDegrees);
    full.width = full.height = 1;
    EXPECT_EQ(rrf::draftCamera(full, 4).width, 1);
    EXPECT_EQ(rrf::draftCamera(full, 4).height, 1);
}

TEST(PredictionDraft, DivisorAdaptsToTheBudget) {
    const double budget = rrf::kDraftBudgetSeconds;
    EXPECT_EQ(rrf::nextDraftDivisor(2, 2 * budget), 3) << "too slow: coarser";
    EXPECT_EQ(rrf::nextDraftDivisor(rrf::kMaxDraftDivisor, 10 * budget), rrf::kMaxDraftDivisor);
    EXPECT_EQ(rrf::nextDraftDivisor(2, 0.2 * budget), 1) << "far below the budget: finer";
    EXPECT_EQ(rrf::nextDraftDivisor(1, 0.0), 1);
    EXPECT_EQ(rrf::nextDraftDivisor(3, 0.5 * budget), 3) << "within the budget: unchanged";
}

TEST(PredictionDraft, SettingsDivideTheDirectSamplesButKeepAtLeastOne) {
    rrf::PredictionSettings p;
    p.directSamples = 64;
    p.seed = 7;
    EXPECT_EQ(rrf::draftPrediction(p).directSamples, 4);
    EXPECT_EQ(rrf::draftPrediction(p).seed, 7u);
    EXPECT_EQ(rrf::draftPrediction(p).direct, p.direct);
    p.directSamples = 8;
    EXPECT_EQ(rrf::draftPrediction(p).directSamples, 1);
    p.directSamples = 1;
    EXPECT_EQ(rrf::draftPrediction(p).directSamples, 1);
}

TEST(PredictionDraft, ReplicationTakesThePixelUnderEachOutputCentre) {
    // 3 × 2 draft to 5 × 4: output centres (x + 0.5) / 5 = 0.1, 0.3, 0.5, 0.7, 0.9 lie in draft
    // columns floor(3 · c) = 0, 0, 1, 2, 2; rows (y + 0.5) / 4 = 0.125 … 0.875 in rows 0, 0, 1, 1.
    rrf::Image small(3, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) small.set(x, y, named(x, y));
    const rrf::Image out = rrf::replicatePixels(small, 5, 4);
    ASSERT_EQ(out.width, 5);
    ASSERT_EQ(out.height, 4);
    const int column[5] = {0, 0, 1, 2, 2}, row[4] = {0, 0, 1, 1};
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x) EXPECT_EQ(out.at(x, y), named(column[x], row[y])) << x << "," << y;
    // Exactly doubled sizes replicate each draft pixel into a 2 × 2 block.
    const rrf::Image doubled = rrf::replicatePixels(small, 6, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 6; ++x) EXPECT_EQ(doubled.at(x, y), named(x / 2, y / 2));
}
