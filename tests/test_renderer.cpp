// Renderer tests on a small Cornell-like scene: NEE and naive estimators converge to the same
// image, the stored split direct + indirect = global, NEE's direct light is far less noisy, and
// images are bit-identical for any thread count and any split into passes.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include <tbb/global_control.h>

#include "core/scene/accel.h"
#include "core/render/renderer.h"
#include "scene_builders.h"

namespace test_renderer {

using namespace rrf;
using namespace rrf::test;

namespace {

RenderOptions options(const Scene& scene, Estimator estimator, int spp, int samplesPerPass, uint64_t seed = 1) {
    RenderOptions o = renderOptions(scene, estimator, spp, samplesPerPass, seed);
    o.tileSize = 8;  // several tiles even on the small test images, so threads really interleave
    return o;
}

bool sameBits(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.data.size() == b.data.size() &&
           std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)) == 0;
}

bool sameBits(const RenderSnapshot& a, const RenderSnapshot& b) {
    return sameBits(a.direct, b.direct) && sameBits(a.indirect, b.indirect) && sameBits(a.global, b.global) &&
           sameBits(a.variance, b.variance) && sameBits(a.directVariance, b.directVariance) &&
           sameBits(a.indirectVariance, b.indirectVariance);
}

}  // namespace

TEST(Renderer, NeeAndNaiveConvergeToTheSameImageMean) {
    // Light 2× the default size (4× the area, same power): the naive estimator hits it 4× as often.
    const Scene scene = cornellLike(1.f, 32, 2.f);
    const Accel accel(scene);
    // 256 (NEE) and 1024 (naive) spp at 32×32 make the standard error of the difference of the
    // image means ≈ 0.4% of the mean; asserted below 1%, so a 5% bias cannot pass.
    const RenderSnapshot nee = render(scene, accel, options(scene, Estimator::NEE, 256, 64));
    const RenderSnapshot naive = render(scene, accel, options(scene, Estimator::Naive, 1024, 256));
    EXPECT_EQ(nee.nonFinite, 0u);
    EXPECT_EQ(naive.nonFinite, 0u);
    EXPECT_EQ(nee.samples, 32u * 32u * 256u);
    EXPECT_EQ(naive.samples, 32u * 32u * 1024u);
    for (int c = 0; c < 3; ++c) {
        const double a = nee.global.mean()[c], b = naive.global.mean()[c];
        const double sigma = std::hypot(imageMeanSigma(nee, c), imageMeanSigma(naive, c));
        EXPECT_LT(sigma, 0.01 * a) << "the comparison must be able to see a 5% bias";
        EXPECT_NEAR(a, b, 5 * sigma) << "channel " << c;
    }
    // The split agrees too. Paired samples: both estimators trace the same camera ray (pixel and
    // jitter from one key) with independent path randomness, so the emission seen directly cancels
    // in the difference; the pairs are i.i.d., so the standard error of the mean difference is exact.
    const PathTracer tNee(scene, accel, Estimator::NEE), tNaive(scene, accel, Estimator::Naive);
    const CameraRays cam(scene.camera, 32, 32);
    TraceCounters counters;
    RunningStat dDirect, dIndirect, direct, indirect;
    for (int i = 0; i < 400000; ++i) {
        Rng pick(20, uint64_t(i));
        const int px = int(pick.uniformInt(32)), py = int(pick.uniformInt(32));
        const Ray ray = cam.generate(px, py, pick.uniform(), pick.uniform());
        Rng ra(21, uint64_t(i)), rb(22, uint64_t(i));
        const Radiance a = tNee.trace(ray, ra, counters), b = tNaive.trace(ray, rb, counters);
        dDirect.add(double(a.direct.x) - double(b.direct.x));
        dIndirect.add(double(a.indirect.x) - double(b.indirect.x));
        direct.add(a.direct.x);
        indirect.add(a.indirect.x);
    }
    EXPECT_NEAR(dDirect.mean, 0.0, 5 * dDirect.sigma());
    EXPECT_NEAR(dIndirect.mean, 0.0, 5 * dIndirect.sigma());
    // Power: a 3% bias of direct or 8% of indirect would be seen.
    EXPECT_LT(5 * dDirect.sigma(), 0.03 * direct.mean);
    EXPECT_LT(5 * dIndirect.sigma(), 0.08 * indirect.mean);
    EXPECT_GT(indirect.mean, 0.1 * direct.mean) << "the scene must have real indirect light";
}

TEST(Renderer, DirectPlusIndirectIsGlobal) {
    // The renderer stores global as the float sum of the stored direct and indirect images, so the
    // identity holds exactly, bit for bit.
    const Scene scene = cornellLike(1.f, 32);
    const Accel accel(scene);
    for (const Estimator e : {Estimator::NEE, Estimator::Naive}) {
        const RenderSnapshot s = render(scene, accel, options(scene, e, 16, 4));
        for (size_t i = 0; i < s.global.data.size(); ++i) {
            const float g = s.global.data[i];
            ASSERT_EQ(s.direct.data[i] + s.indirect.data[i], g) << "value " << i;
            ASSERT_GE(s.direct.data[i], 0.f);
            ASSERT_GE(s.indirect.data[i], 0.f);
        }
    }
}

TEST(Renderer, NeeDirectLightIsLessNoisyThanNaive) {
    // Seed figure 2: at equal sample counts the naive estimator's direct light is far noisier (it
    // only sees the light when a BRDF ray happens to hit it). Mean per-pixel sample variance of
    // direct over 64 pixels × 256 samples; NEE must be at least 4× quieter (typically ≫ 10×).
    const Scene scene = cornellLike(1.f, 32);
    const Accel accel(scene);
    const CameraRays cam(scene.camera, 32, 32);
    double var[2] = {0, 0};
    for (const Estimator e : {Estimator::NEE, Estimator::Naive}) {
        const PathTracer tracer(scene, accel, e);
        TraceCounters counters;
        for (int py = 2; py < 32; py += 4)
            for (int px = 2; px < 32; px += 4) {
                RunningStat st;
                for (int s = 0; s < 256; ++s) {
                    Rng rng(5, uint64_t(py * 32 + px), uint64_t(s));
                    const float jx = rng.uniform(), jy = rng.uniform();
                    st.add(tracer.trace(cam.generate(px, py, jx, jy), rng, counters).direct.x);
                }
                var[e == Estimator::NEE ? 0 : 1] += st.variance();
            }
    }
    EXPECT_LT(var[0] * 4, var[1]) << "NEE " << var[0] / 64 << " vs naive " << var[1] / 64;
}

TEST(Renderer, BitIdenticalForAnyThreadCount) {
    const Scene scene = cornellLike(1.f, 32);
    const Accel accel(scene);
    for (const Estimator e : {Estimator::NEE, Estimator::Naive}) {
        const RenderOptions o = options(scene, e, 4, 2);
        RenderSnapshot one, two, four;
        {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
            one = render(scene, accel, o);
        }
        {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
            two = render(scene, accel, o);
        }
        {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 4);
            four = render(scene, accel, o);
        }
        EXPECT_TRUE(sameBits(one, two));
        EXPECT_TRUE(sameBits(one, four));
        EXPECT_GT(one.global.mean().x, 0.f);
    }
}

TEST(Renderer, BitIdenticalForAnyPassSplit) {
    // 4 spp in one pass, in four passes of 1, and in passes of 3 + 1: sample k of pixel i always
    // uses Rng(seed, i, k) and sums run in sample order.
    const Scene scene = cornellLike(1.f, 32);
    const Accel accel(scene);
    const RenderSnapshot once = render(scene, accel, options(scene, Estimator::NEE, 4, 4));
    const RenderSnapshot fourPasses = render(scene, accel, options(scene, Estimator::NEE, 4, 1));
    const RenderSnapshot uneven = render(scene, accel, options(scene, Estimator::NEE, 4, 3));
    EXPECT_TRUE(sameBits(once, fourPasses));
    EXPECT_TRUE(sameBits(once, uneven));
    EXPECT_EQ(once.passes, 1);
    EXPECT_EQ(fourPasses.passes, 4);
    EXPECT_EQ(uneven.passes, 2);
    EXPECT_EQ(fourPasses.sppCompleted, 4);
    // A different seed gives a different image.
    const RenderSnapshot other = render(scene, accel, options(scene, Estimator::NEE, 4, 4, 2));
    EXPECT_FALSE(sameBits(once.global, other.global));
}

TEST(Renderer, CancelStopsBeforeTheNextPass) {
    const Scene scene = cornellLike(1.f, 16);
    const Accel accel(scene);
    Renderer r(scene, accel, options(scene, Estimator::NEE, 8, 1));
    int passes = 0;
    r.run([&](int sppDone) {
        ++passes;
        EXPECT_EQ(sppDone, passes);
        if (sppDone == 3) r.cancel();
    });
    const RenderSnapshot s = r.snapshot();
    EXPECT_EQ(s.sppCompleted, 3);
    EXPECT_EQ(s.samples, 16u * 16u * 3u);
    EXPECT_NEAR(r.progress(), 3.0 / 8.0, 1e-12);
    EXPECT_EQ(r.stats().nonFinite, 0u);
    EXPECT_GT(r.stats().rays, 0u);
}

TEST(Renderer, NeeAndNaiveAgreeAtEveryMaxDepth) {
    // max_depth bounds the number of reflections for both estimators: NEE at depth d accounts for
    // paths of d+1 reflections, so the naive estimator must bounce at depth d to see them too.
    // Before the fix, naive at max_depth 1 had no direct light and at 2 no indirect light.
    const Scene scene = cornellLike(1.f, 16);
    const Accel accel(scene);
    for (const int depth : {1, 2, 3}) {
        RenderOptions nee = options(scene, Estimator::NEE, 256, 256);
        RenderOptions naive = options(scene, Estimator::Naive, 2048, 2048);
        nee.maxDepth = naive.maxDepth = depth;
        const RenderSnapshot a = render(scene, accel, nee);
        const RenderSnapshot b = render(scene, accel, naive);
        const double sa = imageMeanSigma(a, 0), sb = imageMeanSigma(b, 0);
        const double tol = 5.0 * std::sqrt(sa * sa + sb * sb);
        EXPECT_NEAR(a.global.mean().x, b.global.mean().x, tol) << "max_depth " << depth;
        EXPECT_GT(b.direct.mean().x, 0.5 * a.direct.mean().x) << "naive direct light missing at max_depth " << depth;
        if (depth >= 2) EXPECT_GT(b.indirect.mean().x, 0.f) << "naive indirect light missing at max_depth " << depth;
        else EXPECT_EQ(b.indirect.mean().x, 0.f);
    }
}

}  // namespace test_renderer
