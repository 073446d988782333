#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/eval/evaluation.h"
#include "core/eval/evaluation_json.h"
#include "core/eval/flip_evaluation.h"
#include "core/util/image.h"
#include "tests/test_dirs.h"

namespace test_flip_evaluation {

using namespace rrf;

namespace {

/// A smooth HDR image (a bright corner falling off to a dim one), like a lit wall.
Image wall(int w, int h, float scale) {
    Image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float v = scale / (1.f + 0.05f * float(x * x + y * y));
            img.set(x, y, Vec3(v, 0.8f * v, 0.6f * v));
        }
    return img;
}

/// An evaluation whose global prediction is `prediction`, comparing every pixel, the left half as
/// object 0 and the right half as object 1 (what evaluatePrediction fills from a G-buffer).
Evaluation evaluationOf(const Image& prediction) {
    Evaluation e;
    e.prediction.images[int(Term::Global)] = prediction;
    e.footprint.keptByObject.resize(2);
    for (int y = 0; y < prediction.height; ++y)
        for (int x = 0; x < prediction.width; ++x) {
            const uint32_t i = uint32_t(y * prediction.width + x);
            e.footprint.kept.push_back(i);
            e.footprint.keptByObject[x < prediction.width / 2 ? 0 : 1].push_back(i);
        }
    return e;
}

Reference referenceOf(const Image& global, const Image& variance = {}) {
    Reference r;
    r.images[int(Term::Global)] = global;
    r.variances[int(Term::Global)] = variance;
    return r;
}

}  // namespace

TEST(FlipEvaluation, DrawnNoiseIsStandardNormal) {
    // The sample mean and variance of 200 000 draws: standard errors 0.0022 and 0.0032; 5σ bounds.
    double sum = 0, sum2 = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        const double z = flipNoiseNormal(7, uint64_t(i / 3), i % 3);
        ASSERT_TRUE(std::isfinite(z));
        sum += z;
        sum2 += z * z;
    }
    EXPECT_NEAR(sum / n, 0.0, 0.012);
    EXPECT_NEAR(sum2 / n, 1.0, 0.016);
    EXPECT_EQ(flipNoiseNormal(7, 12, 1), flipNoiseNormal(7, 12, 1)) << "a pure function of its key";
    EXPECT_NE(flipNoiseNormal(7, 12, 1), flipNoiseNormal(8, 12, 1));
}

TEST(FlipEvaluation, DrawnNoiseHasThePixelsVariance) {
    // Per-pixel variance 0.04 on the left half, 0 on the right: the right half is unchanged and the
    // left half's squared deviations average 0.04 (n = 3 · 64 · 128; standard error 0.0006).
    const int w = 256, h = 128;
    const Image img = wall(w, h, 5.f);
    Image var(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w / 2; ++x) var.set(x, y, Vec3(0.04f));
    var.set(w - 1, 0, Vec3(-1.f));  // negative: adds nothing
    const Image noisy = withDrawnNoise(img, var, 3);
    double sq = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const Vec3 d = noisy.at(x, y) - img.at(x, y);
            if (x >= w / 2) ASSERT_EQ(d.x * d.x + d.y * d.y + d.z * d.z, 0.f);
            else sq += double(d.x * d.x + d.y * d.y + d.z * d.z);
        }
    EXPECT_NEAR(sq / (3.0 * (w / 2) * h), 0.04, 0.003);
    EXPECT_THROW(withDrawnNoise(img, Image(2, 2), 3), std::invalid_argument);
}

TEST(FlipEvaluation, PerfectPredictionScoresZeroAndTheNoiseFloorIsPositive) {
    const Image ref = wall(64, 48, 20.f);
    Image var(64, 48, Vec3(0.01f));
    const Evaluation e = evaluationOf(ref);
    const FlipEvaluation f = flipEvaluation(e, referenceOf(ref, var));
    ASSERT_TRUE(f.available);
    EXPECT_EQ(f.hdr.mean, 0.0);
    EXPECT_EQ(f.ldr.mean, 0.0);
    EXPECT_EQ(f.hdr.pixels, 64u * 48u);
    ASSERT_EQ(f.hdrPerObject.size(), 2u);
    EXPECT_EQ(f.hdrPerObject[0].pixels + f.hdrPerObject[1].pixels, 64u * 48u);
    EXPECT_GT(f.hdrNoiseFloor, 0.0) << "the reference's own noise is visible to FLIP";
    EXPECT_LT(f.hdrNoiseFloor, 1.0);

    // Without the variance, the floor is unknown (NaN), never 0.
    EXPECT_TRUE(std::isnan(flipEvaluation(e, referenceOf(ref)).hdrNoiseFloor));
    // Without a global prediction there is nothing to judge.
    Evaluation none = evaluationOf(ref);
    none.prediction.available[int(Term::Global)] = false;
    EXPECT_FALSE(flipEvaluation(none, referenceOf(ref)).available);
}

TEST(FlipEvaluation, ExposuresComeFromTheReferenceAloneAndErrorGrowsWithTheDifference) {
    const Image ref = wall(64, 48, 20.f);
    Image slightly = ref, very = ref;
    for (float& v : slightly.data) v *= 1.05f;
    for (float& v : very.data) v *= 1.6f;
    const FlipEvaluation a = flipEvaluation(evaluationOf(slightly), referenceOf(ref));
    const FlipEvaluation b = flipEvaluation(evaluationOf(very), referenceOf(ref));
    const FlipExposureRange r = flipExposureRange(ref);
    for (const FlipEvaluation* f : {&a, &b}) {
        EXPECT_EQ(f->range.start, r.start);
        EXPECT_EQ(f->range.stop, r.stop);
        EXPECT_EQ(f->range.count, r.count);
    }
    EXPECT_GT(a.hdr.mean, 0.0);
    EXPECT_GT(b.hdr.mean, a.hdr.mean) << "a 60 % brighter image looks more different than a 5 % brighter one";
    // The overall mean is the pixel-weighted mean of the two objects' means.
    const double pooled = (a.hdrPerObject[0].mean * double(a.hdrPerObject[0].pixels) +
                           a.hdrPerObject[1].mean * double(a.hdrPerObject[1].pixels)) /
                          double(a.hdr.pixels);
    EXPECT_NEAR(a.hdr.mean, pooled, 1e-9);
}

TEST(FlipEvaluation, ReportTableAndMapsCarryTheFlipFigures) {
    const Image ref = wall(32, 24, 20.f);
    Image pred = ref;
    for (float& v : pred.data) v *= 1.2f;
    Evaluation e = evaluationOf(pred);
    const Reference reference = referenceOf(ref, Image(32, 24, Vec3(0.01f)));
    for (int t = 0; t < kTermCount; ++t)
        if (t != int(Term::Global)) e.prediction.available[t] = false, e.terms[t].available = false;
    e.flip = flipEvaluation(e, reference);
    Scene scene;
    const nlohmann::json j = evaluationJson(scene, e);
    ASSERT_TRUE(j.contains("flip"));
    EXPECT_DOUBLE_EQ(j["flip"]["hdr"]["mean"].get<double>(), e.flip.hdr.mean);
    EXPECT_DOUBLE_EQ(j["flip"]["hdr_noise_floor"].get<double>(), e.flip.hdrNoiseFloor);
    EXPECT_EQ(j["flip"]["exposures"]["count"].get<int>(), e.flip.range.count);
    EXPECT_EQ(j["flip"]["objects"].size(), 2u);
    EXPECT_NE(evaluationTable(scene, e).find("HDR-FLIP"), std::string::npos);

    const std::string dir = rrf::test::freshTestDir("flip_evaluation_maps").string();
    const nlohmann::json images = toJson(writeEvaluationImages(dir, e, reference));
    for (const char* f : {"flip_hdr_global.exr", "flip_hdr_global.png", "flip_ldr_global.exr", "flip_ldr_global.png"})
        EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(dir) / f)) << f;
    EXPECT_EQ(images["false_colour_ranges"]["flip_hdr_global"], nlohmann::json({0.0, 1.0}));

    // Without FLIP figures neither the report nor the directory mention FLIP.
    e.flip = {};
    EXPECT_FALSE(evaluationJson(scene, e).contains("flip"));
    EXPECT_EQ(evaluationTable(scene, e).find("HDR-FLIP"), std::string::npos);
}

}  // namespace test_flip_evaluation
