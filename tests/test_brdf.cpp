// Tests of the Lambert + modified Phong mixture in core/render/brdf.h: sampling against the mixture pdf
// (chi-square), normalisation of the pdf, the sample weight, and energy conservation.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "core/render/brdf.h"
#include "core/scene/scene_json.h"
#include "core/util/rng.h"
#include "scene_builders.h"

namespace test_brdf {

using namespace rrf;
using namespace rrf::test;

namespace {

constexpr double kPiD = 3.14159265358979323846;

Vec3 direction(double cosTheta, double phi) {
    const double s = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
    return {float(s * std::cos(phi)), float(s * std::sin(phi)), float(cosTheta)};
}

Vec3 viewAt(double thetaDegrees) { return direction(std::cos(thetaDegrees * kPiD / 180.0), 0.0); }

/// ∫ g over the upper hemisphere in (cos θ, φ): composite Gauss–Legendre, 64 × 128 panels of
/// 8 × 8 nodes. Resolves a Phong lobe of exponent ≤ 100 (angular width ≈ 0.1 rad) to < 1e-4.
double integrateHemisphere(const std::function<double(const Vec3&)>& g) {
    const GaussLegendre gl(8);
    return gl.integrate(
        [&](double c) {
            return gl.integrate([&](double phi) { return g(direction(c, phi)); }, 0.0, 2 * kPiD, 128);
        },
        0.0, 1.0, 64);
}

/// Directional albedo ∫ f cos θ dω at normal incidence, where f depends on cos θ only: 1-D
/// quadrature in s = 1 − cos θ on geometrically graded panels (resolves lobes up to n = 1e4).
double albedoAtNormalIncidence(const Brdf& b) {
    const GaussLegendre gl(20);
    const Vec3 wo(0, 0, 1);
    auto f = [&](double s) {
        const double c = 1.0 - s;
        return 2 * kPiD * double(b.eval(wo, direction(c, 0.0)).x) * c;
    };
    double sum = gl.integrate(f, 0.0, 1e-9);
    for (double lo = 1e-9; lo < 1.0; lo *= 2) sum += gl.integrate(f, lo, std::min(1.0, lo * 2));
    return sum;
}

/// The part of [φ0, φ1] ⊂ [0, 2π] where the direction (cos α = c, φ) about the lobe axis lies above
/// the surface, as (length, ∫ z dφ). The lobe axis r = (−sin θr, 0, cos θr) with tangents
/// t1 = (cos θr, 0, sin θr), t2 = (0, 1, 0), so z(φ) = c cos θr + sin α sin θr cos φ > 0 on
/// φ ∈ [0, φ*) ∪ (2π − φ*, 2π], φ* = acos(−c cos θr / (sin α sin θr)) (all or nothing when |…| ≥ 1).
std::pair<double, double> aboveHorizon(double c, double thetaR, double phi0, double phi1) {
    const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
    const double a = c * std::cos(thetaR), b = s * std::sin(thetaR);
    double phiStar;
    if (b <= 0.0) phiStar = a > 0.0 ? kPiD : 0.0;
    else phiStar = std::acos(std::clamp(-a / b, -1.0, 1.0));
    double length = 0, zIntegral = 0;
    auto add = [&](double lo, double hi) {
        lo = std::max(lo, phi0);
        hi = std::min(hi, phi1);
        if (hi <= lo) return;
        length += hi - lo;
        zIntegral += a * (hi - lo) + b * (std::sin(hi) - std::sin(lo));
    };
    add(0.0, phiStar);
    add(2 * kPiD - phiStar, 2 * kPiD);
    return {length, zIntegral};
}

}  // namespace

TEST(Brdf, MixtureSampleChiSquare) {
    // kd 0.3, ks 0.5, n 20 at three view angles; at 80° part of the Phong lobe lies below the
    // horizon, and sample() must fail exactly as often as the pdf's missing mass says (extra bin).
    const Brdf b = phong(0.3f, 0.5f, 20.f);
    const int K = 20, M = 16, samples = 300000;
    uint64_t seed = 200;
    for (const double thetaO : {0.0, 45.0, 80.0}) {
        const Vec3 wo = viewAt(thetaO);
        std::vector<double> observed(size_t(K * M) + 1, 0.0);
        for (int i = 0; i < samples; ++i) {
            Rng rng(seed, uint64_t(i));
            const float ul = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
            Vec3 wi, weight;
            if (!b.sample(wo, ul, u1, u2, wi, weight)) {
                observed.back() += 1;
                continue;
            }
            ASSERT_GT(wi.z, 0.f);
            // Bins in t = cos²θ (equiprobable for the diffuse part) × φ.
            const double t = double(wi.z) * wi.z;
            double phi = std::atan2(double(wi.y), double(wi.x));
            if (phi < 0) phi += 2 * kPiD;
            const int it = std::min(K - 1, int(t * K));
            const int ip = std::min(M - 1, int(phi / (2 * kPiD) * M));
            observed[size_t(it * M + ip)] += 1;
        }
        ++seed;
        // Expected: ∫∫ pdf dc dφ over each bin (c = cos θ ∈ [√t0, √t1]), 16 × 16 nodes per bin.
        const GaussLegendre gl(8);
        std::vector<double> expected(observed.size(), 0.0);
        double total = 0;
        for (int it = 0; it < K; ++it) {
            const double c0 = std::sqrt(double(it) / K), c1 = std::sqrt(double(it + 1) / K);
            for (int ip = 0; ip < M; ++ip) {
                const double p0 = 2 * kPiD * ip / M, p1 = 2 * kPiD * (ip + 1) / M;
                const double p = gl.integrate(
                    [&](double c) {
                        return gl.integrate([&](double phi) { return double(b.pdf(wo, direction(c, phi))); }, p0, p1, 2);
                    },
                    c0, c1, 2);
                expected[size_t(it * M + ip)] = p * samples;
                total += p;
            }
        }
        expected.back() = std::max(0.0, 1.0 - total) * samples;
        int dof = 0;
        const double p = chiSquarePValue(observed, expected, &dof);
        EXPECT_GT(dof, K * M / 2);
        EXPECT_GT(p, sidakAlpha(kChiSquareTests)) << "view angle " << thetaO << "°";
    }
}

TEST(Brdf, MixturePdfIntegratesToOneWhenTheLobeIsAboveTheHorizon) {
    // Quadrature error < 1e-4 (see integrateHemisphere); 1e-3 bounds it with margin.
    const Brdf b = phong(0.3f, 0.5f, 20.f);
    const Vec3 normal = viewAt(0.0);
    EXPECT_NEAR(integrateHemisphere([&](const Vec3& wi) { return b.pdf(normal, wi); }), 1.0, 1e-3);
    // At 80° a visible part of the lobe (around the mirror direction, 10° above the horizon) falls
    // below the surface: the pdf integrates to less than 1 but never to less than the diffuse share.
    const Vec3 grazing = viewAt(80.0);
    const double total = integrateHemisphere([&](const Vec3& wi) { return b.pdf(grazing, wi); });
    EXPECT_LT(total, 1.0 - 1e-2);
    EXPECT_GT(total, b.pDiffuse);
    // Pure Lambert: exactly the cosine pdf.
    const Brdf lambert = phong(0.6f, 0.f, 1.f);
    EXPECT_NEAR(integrateHemisphere([&](const Vec3& wi) { return lambert.pdf(grazing, wi); }), 1.0, 1e-4);
    // Below the surface the pdf is 0.
    EXPECT_EQ(b.pdf(normal, Vec3(0.f, 0.6f, -0.8f)), 0.f);
    EXPECT_EQ(b.pdf(Vec3(0.f, 0.6f, -0.8f), normal), 0.f);
}

TEST(Brdf, SampleWeightIsEvalCosOverPdf) {
    // Mixtures use eval·cosθ/pdf directly; the pure lobes use closed forms (kd; ks (n+2)/(n+1) cosθ)
    // that must agree with it wherever cos^n α has not underflowed. Float rounding of the two paths
    // differs by a few ulps: relative 1e-4.
    struct Case {
        float kd, ks, n;
    };
    for (const Case c : {Case{0.3f, 0.5f, 20.f}, Case{0.5f, 0.4f, 1.f}, Case{0.1f, 0.8f, 300.f}, Case{0.7f, 0.f, 1.f},
                         Case{0.f, 0.9f, 5.f}, Case{0.f, 0.6f, 200.f}}) {
        const Brdf b = phong(c.kd, c.ks, c.n);
        int accepted = 0;
        for (int i = 0; i < 2000; ++i) {
            Rng rng(300, uint64_t(i));
            const Vec3 wo = sampleCosineHemisphere(rng.uniform(), rng.uniform());
            Vec3 wi, weight;
            if (!b.sample(wo, rng.uniform(), rng.uniform(), rng.uniform(), wi, weight)) continue;
            const float pdf = b.pdf(wo, wi);
            if (!(pdf > 1e-20f)) continue;
            ++accepted;
            const Vec3 expected = b.eval(wo, wi) * (wi.z / pdf);
            ASSERT_TRUE(weight.isFinite());
            ASSERT_NEAR(weight.x, expected.x, 1e-4f * expected.x + 1e-30f)
                << "kd " << c.kd << " ks " << c.ks << " n " << c.n << " wo " << wo << " wi " << wi;
        }
        EXPECT_GT(accepted, 1000);
    }
}

TEST(Brdf, AlbedoAtNormalIncidenceIsKdPlusKs) {
    // For the modified Phong lobe at normal incidence cos α = cos θ, so
    // ∫ ks (n+2)/(2π) cos^n θ cos θ dω = ks (n+2) ∫_0^1 c^{n+1} dc = ks exactly: the albedo is kd + ks,
    // never more. Quadrature error 1e-3 (float quantisation of cos θ at n = 1e4, see test_sampling).
    for (const float n : {1.f, 20.f, 1000.f, 1e4f}) {
        const Brdf b = phong(0.3f, 0.5f, n);
        const double a = albedoAtNormalIncidence(b);
        EXPECT_NEAR(a, 0.8, 0.8e-3) << "n = " << n;
    }
    EXPECT_NEAR(albedoAtNormalIncidence(phong(0.6f, 0.f, 1.f)), 0.6, 1e-6);
}

TEST(Brdf, AlbedoNeverExceedsKdPlusKs) {
    // Away from normal incidence the lobe is clipped by the horizon and cos θ < cos α near the
    // lobe: the albedo drops below kd + ks (modified Phong loses energy at grazing angles).
    for (const float n : {1.f, 20.f, 100.f}) {
        const Brdf b = phong(0.3f, 0.5f, n);
        double previous = 1.0;
        for (const double thetaO : {0.0, 30.0, 60.0, 85.0}) {
            const Vec3 wo = viewAt(thetaO);
            const double a = integrateHemisphere([&](const Vec3& wi) { return double(b.eval(wo, wi).x) * wi.z; });
            EXPECT_LE(a, 0.8 * (1 + 1e-4)) << "n = " << n << " θo = " << thetaO;
            EXPECT_GT(a, 0.3 * 0.99) << "the diffuse part alone reflects kd";
            EXPECT_LE(a, previous * (1 + 1e-4)) << "albedo grows towards grazing: n = " << n << " θo = " << thetaO;
            previous = a;
        }
    }
}

TEST(Brdf, EvalIsReciprocalAndZeroBelowTheSurface) {
    const Brdf b = phong(0.3f, 0.5f, 20.f);
    for (int i = 0; i < 1000; ++i) {
        Rng rng(400, uint64_t(i));
        const Vec3 a = sampleCosineHemisphere(rng.uniform(), rng.uniform());
        const Vec3 c = sampleCosineHemisphere(rng.uniform(), rng.uniform());
        const Vec3 fac = b.eval(a, c), fca = b.eval(c, a);
        ASSERT_NEAR(fac.x, fca.x, 1e-5f * fac.x + 1e-7f);
        EXPECT_TRUE(b.eval(a, Vec3(c.x, c.y, -c.z)).isZero());
    }
}

TEST(Brdf, GlossyProjectMaterialsPassChiSquareInTheLobeFrame) {
    // The bundled glossy project's Phong materials (exponents 10, 100, 1000) at normal and 45°
    // incidence. A lobe of exponent 1000 is ~0.03 rad wide, far narrower than the bins above, so the
    // bins follow the lobe: K bins equiprobable for the lobe, u = cos^(n+1) α ∈ [k/K, (k+1)/K], times
    // M bins of the azimuth φ about the mirror direction r, plus one bin for cos α < 0 (diffuse
    // samples only) and one for failed samples. Expected counts integrate the mixture pdf over each
    // bin: the lobe part is uniform in (u, φ) (density (1 − pd)/(2π)), the diffuse part is
    // pd·z/π in (cos α, φ); the azimuth integrals are closed forms over the part above the horizon
    // (aboveHorizon), the polar ones Gauss–Legendre.
    const Scene scene = loadScene(std::string(RRF_SOURCE_DIR) + "/projects/cornell-glossy/scene.json");
    const int K = 20, M = 16, samples = 200000;
    const GaussLegendre gl(8);
    int tested = 0;
    uint64_t seed = 900;
    for (const Material& m : scene.materials) {
        if (m.type != Material::Type::Phong || m.ks.isZero()) continue;
        ++tested;
        const Brdf b(m);
        const double n = b.n, pd = b.pDiffuse;
        for (const double thetaO : {0.0, 45.0}) {
            const double thetaR = thetaO * kPiD / 180.0;
            const Vec3 wo = viewAt(thetaO);
            const double rx = -std::sin(thetaR), rz = std::cos(thetaR);
            std::vector<double> observed(size_t(K * M) + 2, 0.0);
            for (int i = 0; i < samples; ++i) {
                Rng rng(seed, uint64_t(i));
                const float ul = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
                Vec3 wi, weight;
                if (!b.sample(wo, ul, u1, u2, wi, weight)) {
                    observed.back() += 1;
                    continue;
                }
                ASSERT_GT(wi.z, 0.f);
                const double c = rx * wi.x + rz * wi.z;  // cos α
                if (c < 0) {
                    observed[size_t(K * M)] += 1;
                    continue;
                }
                const double t1 = rz * wi.x - rx * wi.z;  // (cos θr, 0, sin θr) · wi
                double phi = std::atan2(double(wi.y), t1);
                if (phi < 0) phi += 2 * kPiD;
                const int k = std::min(K - 1, int(std::pow(c, n + 1) * K));
                const int j = std::min(M - 1, int(phi / (2 * kPiD) * M));
                observed[size_t(k * M + j)] += 1;
            }
            ++seed;
            std::vector<double> expected(observed.size(), 0.0);
            double total = 0;
            for (int k = 0; k <= K; ++k) {  // k == K: the bin cos α < 0
                for (int j = 0; j < (k < K ? M : 1); ++j) {
                    const double p0 = k < K ? 2 * kPiD * j / M : 0.0, p1 = k < K ? 2 * kPiD * (j + 1) / M : 2 * kPiD;
                    const double cLo = k < K ? std::pow(double(k) / K, 1 / (n + 1)) : -1.0;
                    const double cHi = k < K ? std::pow(double(k + 1) / K, 1 / (n + 1)) : 0.0;
                    const double diffuse =
                        gl.integrate([&](double c) { return aboveHorizon(c, thetaR, p0, p1).second; }, cLo, cHi, 32) /
                        kPiD;
                    const double lobe =
                        k < K ? gl.integrate(
                                    [&](double u) {
                                        return aboveHorizon(std::pow(u, 1 / (n + 1)), thetaR, p0, p1).first;
                                    },
                                    double(k) / K, double(k + 1) / K, 8) /
                                    (2 * kPiD)
                              : 0.0;
                    const double p = pd * diffuse + (1 - pd) * lobe;
                    expected[size_t(k * M + j)] = p * samples;
                    total += p;
                }
            }
            expected.back() = std::max(0.0, 1.0 - total) * samples;
            int dof = 0;
            const double p = chiSquarePValue(observed, expected, &dof);
            EXPECT_GT(dof, K * M / 2) << m.name;
            EXPECT_GT(p, sidakAlpha(kChiSquareTests)) << m.name << " (exponent " << n << ") at " << thetaO << "°";
        }
    }
    EXPECT_EQ(tested, 3) << "the glossy project's three Phong materials";
}
}  // namespace test_brdf
