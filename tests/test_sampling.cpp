// Chi-square and normalisation tests of the direction samplers in core/util/warp.h.
//
// The chi-square tests bin sampled directions in (t, φ), where t = cos^m α is a monotone map of the
// angle to the lobe axis chosen so that bins are roughly equiprobable (m = 2 for the cosine lobe,
// m = n+1 for Phong). Expected counts come from integrating the implementation's pdf over each bin
// numerically, so a sampler that disagrees with its pdf fails, whatever the binning variable.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "core/util/rng.h"
#include "core/util/warp.h"
#include "scene_builders.h"

namespace test_sampling {

using namespace rrf;
using namespace rrf::test;

namespace {

constexpr double kPiD = 3.14159265358979323846;

/// Chi-square test of a sampler of directions around +z whose pdf depends on cos α only.
/// t = cos^m α (K bins) × φ (M bins). For each t-bin the probability is
/// 2π ∫ pdf(c) dc over c ∈ [t0^{1/m}, t1^{1/m}], computed in the variable t (where the integrand
/// pdf(c(t))·c'(t) is smooth, constant for the correct pdf) with Gauss–Legendre panels.
double lobeChiSquare(const std::function<Vec3(float, float)>& sample, const std::function<float(float)>& pdf,
                     double m, int samples, uint64_t seed, int K = 20, int M = 8) {
    std::vector<double> observed(size_t(K * M) + 1, 0.0);  // last bin: below the horizon / invalid
    for (int i = 0; i < samples; ++i) {
        Rng rng(seed, uint64_t(i));
        const float u = rng.uniform(), v = rng.uniform();
        const Vec3 w = sample(u, v);
        if (!(w.z > 0.f)) {
            observed.back() += 1;
            continue;
        }
        // t = cos^m α in double; near the axis use sin²α = x² + y², which keeps its relative
        // precision when cos α rounds to 1 (n = 1e4: 1 − cos α ≈ 1e-4).
        const double s2 = double(w.x) * w.x + double(w.y) * w.y;
        const double lnC = w.z > 0.7f ? 0.5 * std::log1p(-s2) : std::log(double(w.z));
        const double t = std::exp(m * lnC);
        double phi = std::atan2(double(w.y), double(w.x));
        if (phi < 0) phi += 2 * kPiD;
        const int it = std::min(K - 1, int(t * K));
        const int ip = std::min(M - 1, int(phi / (2 * kPiD) * M));
        observed[size_t(it * M + ip)] += 1;
    }
    const GaussLegendre gl(16);
    std::vector<double> expected(observed.size(), 0.0);
    double total = 0;
    for (int it = 0; it < K; ++it) {
        const double t0 = double(it) / K, t1 = double(it + 1) / K;
        auto integrand = [&](double t) {
            const double c = std::pow(t, 1.0 / m);
            const double dcdt = c / (m * t);
            return 2 * kPiD * double(pdf(float(c))) * dcdt;
        };
        // The first bin reaches t = 0, where c'(t) is singular on its own: grade the panels.
        double p = 0;
        if (it == 0) {
            p += gl.integrate(integrand, 0.0, t1 * 1e-12);
            for (double lo = t1 * 1e-12; lo < t1; lo *= 10) p += gl.integrate(integrand, lo, std::min(t1, lo * 10));
        } else {
            p = gl.integrate(integrand, t0, t1, 2);
        }
        for (int ip = 0; ip < M; ++ip) expected[size_t(it * M + ip)] = p / M * samples;
        total += p;
    }
    expected.back() = std::max(0.0, 1.0 - total) * samples;
    int dof = 0;
    const double pValue = chiSquarePValue(observed, expected, &dof);
    EXPECT_GT(dof, K * M / 2);  // the test keeps most of its bins
    return pValue;
}

/// ∫ pdf over the sphere for a pdf of cos α only: 2π ∫_{-1}^{1} pdf(c) dc, with panels graded
/// geometrically in 1 − c so that a lobe of width 1/n around c = 1 is resolved, and a panel edge at
/// the horizon c = 0 where the pdfs have a kink or a jump.
double integrateLobe(const std::function<float(float)>& pdf) {
    const GaussLegendre gl(20);
    auto f = [&](double s) { return double(pdf(float(1.0 - s))); };  // s = 1 − c ∈ [0, 2]
    double sum = gl.integrate(f, 0.0, 1e-9);
    for (double lo = 1e-9; lo < 1.0; lo *= 2) sum += gl.integrate(f, lo, std::min(1.0, lo * 2));
    sum += gl.integrate(f, 1.0, 2.0);
    return 2 * kPiD * sum;
}

}  // namespace

TEST(Sampling, CosineHemisphereChiSquare) {
    const double p = lobeChiSquare(sampleCosineHemisphere, cosineHemispherePdf, 2.0, 400000, 11);
    EXPECT_GT(p, sidakAlpha(kChiSquareTests)) << "cosine hemisphere sampling disagrees with cosθ/π";
}

TEST(Sampling, PhongLobeChiSquare) {
    // Exponents from broad to the narrow lobes of the hard cases (docs/design.md §7).
    uint64_t seed = 100;
    for (const float n : {1.f, 10.f, 100.f, 1e4f}) {
        const double p = lobeChiSquare([n](float u, float v) { return samplePhongLobe(u, v, n); },
                                       [n](float c) { return phongLobePdf(c, n); }, double(n) + 1.0, 400000,
                                       seed++);
        EXPECT_GT(p, sidakAlpha(kChiSquareTests)) << "Phong lobe sampling disagrees with its pdf at n = " << n;
    }
}

TEST(Sampling, ChiSquareDetectsAWrongPdf) {
    // Power check of the harness: the Phong sampler tested against the pdf of a neighbouring exponent
    // (n = 10 vs 11, a 10% change of width) must be rejected.
    const double p = lobeChiSquare([](float u, float v) { return samplePhongLobe(u, v, 10.f); },
                                   [](float c) { return phongLobePdf(c, 11.f); }, 11.0, 400000, 7);
    EXPECT_LT(p, 1e-6);
}

TEST(Sampling, CosinePdfIntegratesToOne) {
    // Smooth integrand, 20-point Gauss–Legendre on graded panels: error far below 1e-6.
    EXPECT_NEAR(integrateLobe(cosineHemispherePdf), 1.0, 1e-6);
    EXPECT_EQ(cosineHemispherePdf(0.f), 0.f);
    EXPECT_EQ(cosineHemispherePdf(-0.5f), 0.f);
}

TEST(Sampling, PhongPdfIntegratesToOne) {
    // phongLobePdf takes a float cos α: near 1 it is quantised in steps of 6e-8, which moves each
    // node by ≤ 3e-8 and the pdf by ≤ n·3e-8 relative (3e-4 at n = 1e4); 1e-3 covers that.
    for (const float n : {0.f, 1.f, 10.f, 100.f, 1e4f}) {
        EXPECT_NEAR(integrateLobe([n](float c) { return phongLobePdf(c, n); }), 1.0, 1e-3) << "n = " << n;
    }
}

TEST(Sampling, PhongLobeStaysFiniteAndUnitAtHugeExponents) {
    // n up to 1e6 (and beyond): directions are unit vectors in the upper hemisphere around +z, and
    // E[1 − cos α] = 1/(n+2) for cos α = u^{1/(n+1)}; sin α must not collapse to 0 (the lobe would
    // become a delta). 20000 samples: relative standard error of the mean of 1 − cos α ≈ 1/√N = 0.7%.
    for (const float n : {1e3f, 1e6f, 1e7f}) {
        RunningStat oneMinusCos;
        for (int i = 0; i < 20000; ++i) {
            Rng rng(5, uint64_t(i));
            const float u = rng.uniform(), v = rng.uniform();
            const Vec3 w = samplePhongLobe(u, v, n);
            ASSERT_TRUE(w.isFinite());
            ASSERT_GT(w.z, 0.f);
            ASSERT_NEAR(length(w), 1.f, 1e-6f);
            const double s2 = double(w.x) * w.x + double(w.y) * w.y;
            oneMinusCos.add(s2 / (1.0 + std::sqrt(1.0 - s2)));  // 1 − cos α from sin²α, no cancellation
            ASSERT_TRUE(std::isfinite(phongLobePdf(w.z, n)));
        }
        const double expected = 1.0 / (double(n) + 2.0);
        EXPECT_NEAR(oneMinusCos.mean, expected, 6 * oneMinusCos.sigma() + 1e-3 * expected) << "n = " << n;
    }
    // Extreme inputs: u = 0 (log guarded) and u just below 1.
    for (const float n : {1.f, 1e6f}) {
        EXPECT_TRUE(samplePhongLobe(0.f, 0.3f, n).isFinite());
        EXPECT_TRUE(samplePhongLobe(0x1.fffffep-1f, 0.3f, n).isFinite());
    }
    EXPECT_EQ(powCos(0.f, 1e6f), 0.f);
    EXPECT_EQ(powCos(-1.f, 3.f), 0.f);
    EXPECT_EQ(powCos(0.5f, 0.f), 1.f);
    EXPECT_EQ(powCos(0.999f, 1e6f), 0.f);  // underflows to 0, not NaN
}

}  // namespace test_sampling
