// The reference's noise floor and the noise-corrected error (core/eval/error_metrics.h): the formulas
// on synthetic images with known variance, then on renders of a small Cornell-like scene — two
// independent renders agree once their noise is taken out, a converged image scores within a noisy
// reference's floor, and a known 5 % error is recovered from a noisy reference.
//
// Statistical bounds. Every corrected figure is sqrt(max(0, Q)) with Q = mean over the n = 3·pixels
// entries of (d² − v)·w (w = 1, or 1/(|ref| + 0.01)² for the relative figure). Pixels are independent
// (each has its own random streams), channels of one pixel are not, so Q is the mean of independent
// per-pixel terms q_i = Σ_c (d_c² − v_c)·w_c / 3 and its standard error is estimated from their sample
// spread: SE(Q) = sd(q_i) / sqrt(pixels). A Q that should be Q0 is asserted within Q0 ± 5·SE(Q).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "core/eval/error_metrics.h"
#include "core/eval/error_metrics_json.h"
#include "core/eval/evaluation.h"
#include "core/eval/reference_file.h"
#include "core/render/render_outputs.h"
#include "core/scene/accel.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "scene_builders.h"
#include "tests/image_builders.h"

namespace test_noise_floor {

using namespace rrf;
using namespace rrf::test;

namespace {

Image make(int w, int h, std::initializer_list<Vec3> pixels) { return test::imageOf(w, h, pixels); }

/// Q = mean((d² − v)·w) over `mask`, its standard error from the per-pixel terms (see the file
/// comment) and, for the relative figure, the bound of its second-order bias (below).
struct CorrectedSquare {
    double q = 0, se = 0, bias = 0;
};
/// `v` is the variance subtracted; `vRef` the part of it that is the reference's (whose noise also
/// sits in the relative weight); `a` the systematic error p − t where it is known (else empty).
///
/// Second-order bias of the relative figure. The weight 1/(|r| + 0.01)² uses the noisy reference
/// r = t + e. Expanding in e/D (D = t + 0.01, σ² = Var(e), a = p − t) the expectation of
/// (d² − v)/(r + 0.01)² is a²/D² + 4aσ²/D³ + 3a²σ²/D⁴ + 3(μ4 − σ⁴)/D⁴ + O(e⁵): the first-order
/// terms cancel (the sample variance's covariance with the mean is the mean's third moment, as in d²),
/// the rest is of order (σ/D)² relative to the figure. With μ4 ≈ 3σ⁴ (a mean of many samples is
/// near Gaussian) the bound is mean(4|a|σ²/D³ + 3a²σ²/D⁴ + 6σ⁴/D⁴), σ² estimated by vRef.
CorrectedSquare correctedSquare(const Image& p, const Image& r, const Image& v, const Image& vRef, const Image& a,
                                const std::vector<uint32_t>& mask, bool relative) {
    std::vector<double> terms;
    double bias = 0;
    for (uint32_t i : mask) {
        double t = 0;
        for (int c = 0; c < 3; ++c) {
            const size_t k = 3 * size_t(i) + size_t(c);
            const double ref = r.data[k], d = double(p.data[k]) - ref, D = std::fabs(ref) + kRelativeEpsilon;
            const double w = relative ? 1.0 / (D * D) : 1.0;
            t += (d * d - double(v.data[k])) * w / 3.0;
            const double s2 = vRef.data[k], sys = a.empty() ? 0.0 : std::fabs(double(a.data[k]));
            bias += relative ? (4 * sys * s2 / (D * D * D) + 3 * sys * sys * s2 / (D * D * D * D) + 6 * s2 * s2 / (D * D * D * D)) : 0.0;
        }
        terms.push_back(t);
    }
    double mean = 0, m2 = 0;
    for (double t : terms) mean += t / double(terms.size());
    for (double t : terms) m2 += (t - mean) * (t - mean);
    return {mean, std::sqrt(m2 / double(terms.size() - 1)) / std::sqrt(double(terms.size())), bias / (3.0 * double(terms.size()))};
}

/// Per-pixel sum of two variance images: the variance of the difference of two independent images.
Image sum(const Image& a, const Image& b) {
    Image out = a;
    for (size_t k = 0; k < out.data.size(); ++k) out.data[k] += b.data[k];
    return out;
}

/// mean over `mask` of v·w, w = 1 or 1/(|d| + 0.01)² with the denominator image `den`.
double meanWeighted(const Image& v, const Image& den, const std::vector<uint32_t>& mask, bool relative) {
    double s = 0;
    for (uint32_t i : mask)
        for (int c = 0; c < 3; ++c) {
            const size_t k = 3 * size_t(i) + size_t(c);
            const double w = relative ? 1.0 / std::pow(std::fabs(double(den.data[k])) + kRelativeEpsilon, 2) : 1.0;
            s += double(v.data[k]) * w;
        }
    return s / (3.0 * double(mask.size()));
}

/// The pixels away from the light: none of the 3×3 neighbourhood sees the emitter (radiance > 2 in
/// `image`; lit walls stay below 1). As the evaluation's mask does, this leaves out the light's edge,
/// where a pixel is 0 or the light's radiance per sample and its mean is far from Gaussian.
std::vector<uint32_t> awayFromLight(const Image& image) {
    std::vector<uint32_t> mask;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            bool light = false;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int nx = std::clamp(x + dx, 0, image.width - 1), ny = std::clamp(y + dy, 0, image.height - 1);
                    light = light || image.at(nx, ny).x > 2.f;
                }
            if (!light) mask.push_back(uint32_t(y * image.width + x));
        }
    return mask;
}

const Scene& scene() {
    static const Scene s = cornellLike(1.f, 32);
    return s;
}

/// A render of the test scene: `spp` samples per pixel with `seed`, in 4 passes.
RenderSnapshot renderScene(int spp, uint64_t seed) {
    static const Accel accel(scene());
    return render(scene(), accel, renderOptions(scene(), Estimator::NEE, spp, spp / 4, seed));
}

}  // namespace

TEST(NoiseFloor, FormulasOnKnownImages) {
    // Pixel 0: ref 1, pred 1.5, variance 0.04 → d² = 0.25, relative weight 1/1.01².
    // Pixel 1: ref 0, pred 0.1, variance 0.02 → d² = 0.01, relative weight 1/0.01² = 1e4.
    const Image ref = make(2, 1, {Vec3(1.f), Vec3(0.f)});
    const Image pred = make(2, 1, {Vec3(1.5f), Vec3(0.1f)});
    const Image var = make(2, 1, {Vec3(0.04f), Vec3(0.02f)});
    const ErrorStats s = errorStatsWithNoise(pred, ref, var);
    ASSERT_TRUE(s.noiseKnown);
    const double d0 = 0.5, d1 = double(0.1f), v0 = double(0.04f), v1 = double(0.02f);
    const double w0 = 1.0 / (1.01 * 1.01), w1 = 1.0 / (0.01 * 0.01);
    EXPECT_NEAR(s.rmse, std::sqrt((d0 * d0 + d1 * d1) / 2), 1e-9);
    EXPECT_NEAR(s.rmseNoiseFloor, std::sqrt((v0 + v1) / 2), 1e-9);
    EXPECT_NEAR(s.rmseCorrected, std::sqrt((d0 * d0 + d1 * d1 - v0 - v1) / 2), 1e-9);
    EXPECT_NEAR(s.relativeRmseNoiseFloor, std::sqrt((v0 * w0 + v1 * w1) / 2), 1e-6);
    // Relative: pixel 1's variance (200 in relative units) exceeds its squared error (100): the sum is
    // negative and the corrected figure clamps at 0.
    EXPECT_LT(d0 * d0 * w0 + d1 * d1 * w1 - v0 * w0 - v1 * w1, 0.0);
    EXPECT_EQ(s.relativeRmseCorrected, 0.0);
    // The raw figures are the ones errorStats gives without the variance; MAE and max stay raw.
    const ErrorStats raw = errorStats(pred, ref);
    EXPECT_EQ(raw.rmse, s.rmse);
    EXPECT_EQ(raw.relativeRmse, s.relativeRmse);
    EXPECT_EQ(raw.mae, s.mae);
    EXPECT_EQ(raw.maxError, s.maxError);
    // relMSE (tev's d² / (ref² + 0.01), no root): floor and corrected by the same rule.
    const double q0 = 1.0 / 1.01, q1 = 1.0 / 0.01;
    EXPECT_NEAR(s.relMse, (d0 * d0 * q0 + d1 * d1 * q1) / 2, 1e-6);
    EXPECT_NEAR(s.relMseNoiseFloor, (v0 * q0 + v1 * q1) / 2, 1e-6);
    // Pixel 1's variance outweighs its error here too: the sum is negative and clamps at 0.
    EXPECT_LT(d0 * d0 * q0 + d1 * d1 * q1 - v0 * q0 - v1 * q1, 0.0);
    EXPECT_EQ(s.relMseCorrected, 0.0);
    EXPECT_NEAR(errorStatsWithNoise(pred, ref, var, {0u}).relMseCorrected, (d0 * d0 - v0) * q0, 1e-6);
    // Over a mask: only pixel 0.
    const ErrorStats one = errorStatsWithNoise(pred, ref, var, {0u});
    EXPECT_NEAR(one.relativeRmseCorrected, std::sqrt((d0 * d0 - v0) * w0), 1e-6);
    EXPECT_NEAR(one.relativeRmseNoiseFloor, std::sqrt(v0 * w0), 1e-6);
}

TEST(NoiseFloor, UnknownWithoutVarianceNeverZero) {
    const Image ref = make(1, 1, {Vec3(1.f)});
    const Image pred = make(1, 1, {Vec3(2.f)});
    for (const ErrorStats& s : {errorStats(pred, ref), errorStatsWithNoise(pred, ref, Image())}) {
        EXPECT_FALSE(s.noiseKnown);
        EXPECT_TRUE(std::isnan(s.rmseNoiseFloor));
        EXPECT_TRUE(std::isnan(s.relativeRmseCorrected));
        EXPECT_TRUE(toJson(s)["relative_rmse_noise_floor"].is_null());
        EXPECT_TRUE(toJson(s)["rmse_corrected"].is_null());
        EXPECT_EQ(noiseFigureText(s.relativeRmseNoiseFloor), "unknown");
    }
    EXPECT_EQ(noiseFigureText(0.0), "0");
    // A variance of the wrong size is an error, a negative or NaN one leaves the pixel out (counted).
    EXPECT_THROW(errorStatsWithNoise(pred, ref, Image(2, 1)), std::invalid_argument);
    const ErrorStats bad = errorStatsWithNoise(pred, ref, make(1, 1, {Vec3(-1.f)}));
    EXPECT_EQ(bad.pixels, 0u);
    EXPECT_EQ(bad.nonFinite, 1u);
}

/// 64×64 pixels of truth t ∈ [0.2, 2]; the reference is t plus Gaussian noise of relative sd
/// `relativeSd` with its variance known, the prediction t·1.03 (a 3 % error).
struct NoisyReference {
    Image truth, ref, var, pred;
};
NoisyReference noisyReference(double relativeSd, uint64_t seed) {
    const int w = 64, h = 64;
    NoisyReference n{Image(w, h), Image(w, h), Image(w, h), Image(w, h)};
    Rng rng(seed, 0);
    for (size_t k = 0; k < n.truth.data.size(); ++k) {
        const double t = 0.2 + 1.8 * rng.uniform();
        const double sd = relativeSd * t;
        // Box–Muller.
        const double u1 = std::max(1e-12, double(rng.uniform())), u2 = rng.uniform();
        const double z = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
        n.truth.data[k] = float(t);
        n.ref.data[k] = float(t + sd * z);
        n.var.data[k] = float(sd * sd);
        n.pred.data[k] = float(1.03 * t);
    }
    return n;
}

TEST(NoiseFloor, CorrectedRecoversTheErrorOfSyntheticNoise) {
    // Relative sd 0.2, as a 64-spp render: the corrected RMSE must find the 3 % error that the raw
    // RMSE buries under the noise.
    const NoisyReference n = noisyReference(0.2, 7);
    const Image &truth = n.truth, &ref = n.ref, &var = n.var, &pred = n.pred;
    const ErrorStats s = errorStatsWithNoise(pred, ref, var);
    const ErrorStats exact = errorStats(pred, truth);
    std::vector<uint32_t> all(truth.pixelCount());
    for (size_t i = 0; i < all.size(); ++i) all[i] = uint32_t(i);
    EXPECT_GT(s.rmse, 5 * exact.rmse) << "the noise dominates the raw figure";
    const CorrectedSquare q = correctedSquare(pred, ref, var, var, Image(), all, false);
    EXPECT_NEAR(s.rmseCorrected * s.rmseCorrected, std::max(0.0, q.q), 1e-9) << "the test's Q is the metric's";
    EXPECT_NEAR(q.q, exact.rmse * exact.rmse, 5 * q.se);
    EXPECT_NEAR(s.rmseNoiseFloor, std::sqrt(meanWeighted(var, ref, all, false)), 1e-6);
}

TEST(NoiseFloor, CorrectedRelMseRecoversTheErrorOfSyntheticNoise) {
    // The reference's relative sd σ = 0.02 (a converged reference) and a 3 % error e:
    // the noise adds about half the squared error to the raw figure; the corrected one finds the
    // truth's. Its weight 1 / (r² + ε) uses the noisy reference r = t(1 + σz), which correlates with
    // d = t(e − σz): to second order (ε ≪ t²) E[(d² − v) w] ≈ e² + 4eσ², a bias of 4σ²/e ≈ 5 % here,
    // which is why it needs a reference whose relative noise is well under the error.
    const NoisyReference n = noisyReference(0.02, 11);
    const Image &truth = n.truth, &ref = n.ref, &var = n.var, &pred = n.pred;
    const ErrorStats s = errorStatsWithNoise(pred, ref, var);
    const ErrorStats exact = errorStats(pred, truth);
    EXPECT_GT(s.relMse, 1.3 * exact.relMse) << "the noise shows in the raw figure";
    EXPECT_NEAR(s.relMseCorrected, exact.relMse * (1 + 4 * 0.02 * 0.02 / 0.03), 0.02 * exact.relMse);
    EXPECT_NEAR(s.relMseNoiseFloor, s.relMse - s.relMseCorrected, 1e-12);
    // The bias (signed relative mean) has the same second-order term: E[1/r] = (1 + σ²)/t, so it
    // reads (1 + e)(1 + σ²) − 1 ≈ e + σ², here 0.0304 for the truth's 0.03.
    EXPECT_NEAR(exact.signedRelativeMean, 0.03, 0.002);
    EXPECT_NEAR(s.signedRelativeMean, (1.0 + exact.signedRelativeMean) * (1 + 0.02 * 0.02) - 1, 0.001);
}

TEST(NoiseFloor, RendererKeepsTheVarianceOfEveryTerm) {
    const RenderSnapshot s = renderScene(64, 1);
    for (Term t : kTerms) {
        const Image& v = s.varianceOf(t);
        ASSERT_EQ(v.width, 32);
        EXPECT_EQ(v.nonFiniteCount(), 0u) << termName(t);
        EXPECT_GT(v.mean().x, 0.f) << termName(t);
    }
    // Direct and indirect radiance of one path are correlated, so neither variance is the global one.
    EXPECT_NE(s.varianceOf(Term::Global).mean().x, s.varianceOf(Term::Direct).mean().x);
    EXPECT_NE(s.varianceOf(Term::Global).mean().x, s.varianceOf(Term::Indirect).mean().x);
}

TEST(NoiseFloor, TwoIndependentRendersAgreeOnceTheirNoiseIsTakenOut) {
    // Both images are 64-spp Monte Carlo estimates of one truth, independent (different seeds): the
    // noise of their difference has the variance Var(A) + Var(B), which is what is subtracted.
    const RenderSnapshot a = renderScene(64, 1), b = renderScene(64, 2);
    const std::vector<uint32_t> mask = awayFromLight(b.global);
    for (Term t : kTerms) {
        const Image noise = sum(a.varianceOf(t), b.varianceOf(t));
        const ErrorStats s = errorStatsWithNoise(a.image(t), b.image(t), noise, mask);
        EXPECT_GT(s.relativeRmse, 0.05) << termName(t) << ": two 64-spp renders differ clearly";
        for (bool relative : {false, true}) {
            const CorrectedSquare q = correctedSquare(a.image(t), b.image(t), noise, b.varianceOf(t), Image(), mask, relative);
            const double raw = relative ? s.relativeRmse : s.rmse, corrected = relative ? s.relativeRmseCorrected : s.rmseCorrected;
            EXPECT_NEAR(corrected * corrected, std::max(0.0, q.q), 1e-9 * (1 + std::fabs(q.q))) << "the test's Q is the metric's";
            // Unbiased up to the relative figure's second-order bias: Q is 0 within 5 SE (+ the bias bound).
            EXPECT_GT(q.q, -5 * q.se) << termName(t) << (relative ? " relative" : " absolute");
            EXPECT_LT(q.q, 5 * q.se + q.bias) << termName(t) << (relative ? " relative" : " absolute");
            EXPECT_LT(corrected, std::sqrt(5 * q.se + q.bias)) << termName(t);
            EXPECT_LT(corrected, 0.6 * raw) << termName(t);
            std::printf("%s %s raw %.4f floor %.4f corrected %.4f  Q %.3g se %.3g bias %.3g\n", termName(t), relative ? "rel" : "abs",
                        raw, relative ? s.relativeRmseNoiseFloor : s.rmseNoiseFloor, corrected, q.q, q.se, q.bias);
        }
    }
}

TEST(NoiseFloor, ConvergedPredictionScoresWithinTheReferenceFloor) {
    // A 2048-spp render as the prediction, a 64-spp render of another seed as the reference. The
    // prediction's own error (its variance, 1/32 of the reference's) stays in the expected Q.
    const RenderSnapshot high = renderScene(2048, 11), ref = renderScene(64, 12);
    const std::vector<uint32_t> mask = awayFromLight(high.global);
    for (Term t : kTerms) {
        const ErrorStats s = errorStatsWithNoise(high.image(t), ref.image(t), ref.varianceOf(t), mask);
        for (bool relative : {false, true}) {
            const CorrectedSquare q =
                correctedSquare(high.image(t), ref.image(t), ref.varianceOf(t), ref.varianceOf(t), Image(), mask, relative);
            const double own = meanWeighted(high.varianceOf(t), high.image(t), mask, relative);
            const double raw = relative ? s.relativeRmse : s.rmse, floor = relative ? s.relativeRmseNoiseFloor : s.rmseNoiseFloor;
            const double corrected = relative ? s.relativeRmseCorrected : s.rmseCorrected;
            std::printf("%s %s raw %.4f floor %.4f corrected %.4f  Q %.3g se %.3g own %.3g bias %.3g\n", termName(t),
                        relative ? "rel" : "abs", raw, floor, corrected, q.q, q.se, own, q.bias);
            EXPECT_GT(q.q, own - 5 * q.se) << termName(t);
            EXPECT_LT(q.q, own + 5 * q.se + q.bias) << termName(t);
            EXPECT_LT(raw * raw, floor * floor + own + 5 * q.se + q.bias) << termName(t) << ": raw error within the noise floor";
            EXPECT_LT(corrected, std::sqrt(own + 5 * q.se + q.bias)) << termName(t);
        }
    }
}

TEST(NoiseFloor, CorrectedRecoversAKnownPerturbationFromANoisyReference) {
    // Prediction: a 2048-spp render H × 1.05; reference: a 64-spp render of another seed. Against the
    // truth t the prediction's error is a = 0.05 t + 1.05 e_H, so Q should be mean(w (0.05 H)²) +
    // 1.05² mean(w Var(H)), with the weight w at H (≈ t) — about 0.05² for the relative figure.
    const RenderSnapshot high = renderScene(2048, 21), ref = renderScene(64, 22);
    const std::vector<uint32_t> mask = awayFromLight(high.global);
    for (Term t : kTerms) {
        Image pred = high.image(t), a = high.image(t), a2 = high.image(t);
        for (float& x : pred.data) x *= 1.05f;
        for (float& x : a.data) x *= 0.05f;
        for (float& x : a2.data) x = 0.05f * x * 0.05f * x;
        const ErrorStats s = errorStatsWithNoise(pred, ref.image(t), ref.varianceOf(t), mask);
        for (bool relative : {false, true}) {
            const CorrectedSquare q = correctedSquare(pred, ref.image(t), ref.varianceOf(t), ref.varianceOf(t), a, mask, relative);
            const double expected = meanWeighted(a2, high.image(t), mask, relative) +
                                    1.05 * 1.05 * meanWeighted(high.varianceOf(t), high.image(t), mask, relative);
            const double raw = relative ? s.relativeRmse : s.rmse, corrected = relative ? s.relativeRmseCorrected : s.rmseCorrected;
            std::printf("%s %s raw %.4f corrected %.4f expected %.4f  Q %.3g se %.3g bias %.3g\n", termName(t),
                        relative ? "rel" : "abs", raw, corrected, std::sqrt(expected), q.q, q.se, q.bias);
            EXPECT_GT(q.q, expected - 5 * q.se) << termName(t);
            EXPECT_LT(q.q, expected + 5 * q.se + q.bias) << termName(t);
            if (relative && t != Term::Direct) {
                // The relative error is 0.05·t/(t + 0.01): 0.05 where t ≫ 0.01, less on dark pixels.
                EXPECT_GT(std::sqrt(expected), 0.04) << termName(t);
                EXPECT_LT(std::sqrt(expected), 0.0501) << termName(t);
                EXPECT_GT(raw, 1.5 * corrected) << termName(t) << ": the raw figure is mostly the reference's noise";
            }
            if (!relative) {
                EXPECT_NEAR(corrected, std::sqrt(expected), 0.2 * std::sqrt(expected)) << termName(t);
            }
        }
    }
}

TEST(NoiseFloor, ReferencesCarryAndSaveTheirVariance) {
    RenderOptions o = renderOptions(scene(), Estimator::NEE, 16, 4, 3);
    const Reference r = renderReference(scene(), scene().lightPosition(), o);
    for (Term t : kTerms) ASSERT_FALSE(r.variance(t).empty()) << termName(t);
    o.spp = 1;
    o.samplesPerPass = 1;
    const Reference one = renderReference(scene(), scene().lightPosition(), o);
    for (Term t : kTerms) EXPECT_TRUE(one.variance(t).empty()) << "1 spp: the variance is unknown, not 0";
}

TEST(NoiseFloor, RenderOutputsSaveTheVarianceAndLoadReferenceReadsIt) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("rrf_noise_floor_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    static const Accel accel(scene());
    Renderer renderer(scene(), accel, renderOptions(scene(), Estimator::NEE, 8, 4, 5));
    renderer.run();
    const RenderSnapshot snap = renderer.snapshot();
    const RenderOutputs out = writeRenderOutputs(dir.string(), scene(), renderer, snap, ImageFormat::EXR, 0.f);
    ASSERT_EQ(out.variances.size(), 3u);
    const Reference r = loadReference(dir.string());
    for (Term t : kTerms) {
        const Image& v = r.variance(t);
        ASSERT_EQ(v.data.size(), snap.varianceOf(t).data.size()) << termName(t);
        EXPECT_EQ(std::memcmp(v.data.data(), snap.varianceOf(t).data.data(), v.data.size() * sizeof(float)), 0)
            << termName(t) << ": EXR keeps the 32-bit floats";
    }
    // A render.json without "variance_images" (an older render): accepted, noise unknown.
    nlohmann::json meta = nlohmann::json::parse(readFile(out.metadata));
    meta.erase("variance_images");
    writeFileAtomically(out.metadata, meta.dump(2));
    const Reference old = loadReference(dir.string());
    for (Term t : kTerms) EXPECT_TRUE(old.variance(t).empty()) << termName(t);
    // A listed but missing file names itself.
    meta["variance_images"] = {{"direct", "variance_direct.exr"}, {"indirect", "nowhere.exr"}, {"global", "variance_global.exr"}};
    writeFileAtomically(out.metadata, meta.dump(2));
    try {
        loadReference(dir.string());
        ADD_FAILURE() << "a missing variance file must be an error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("nowhere.exr"), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}

}  // namespace test_noise_floor
