// End to end on a small diffuse scene built in code: generate → train → predict at held-out light
// positions → relative RMSE against path-traced references. The bound is checked against two broken
// pipelines (targets shuffled across records, light-position input decorrelated from the targets),
// which must fail it. Also: held-out light positions are inside the region and not training's.
#include <algorithm>
#include <cstdio>

#include <gtest/gtest.h>

#include "core/pipeline/experiment.h"
#include "core/eval/held_out.h"
#include "core/project/project.h"
#include "core/project/project_file.h"
#include "core/util/rng.h"
#include "core/util/stopwatch.h"
#include "core/pipeline/sweep.h"
#include "tests/training_builders.h"

namespace test_end_to_end {

using namespace rrf;

namespace {

/// Floor (white), back wall (white) and left wall (red) of a 2×2×2 corner, lit by a small one-sided
/// rect light facing down that moves in a box covering most of the room's upper half, so moving it
/// changes the shading of every surface by a large factor.
Scene cornerScene() {
    Scene s;
    Material white, red;
    white.name = "white";
    white.kd = Vec3(0.8f, 0.8f, 0.8f);
    red.name = "red";
    red.kd = Vec3(0.7f, 0.15f, 0.1f);
    s.materials = {white, red};
    auto quad = [&](const char* name, int mat, Vec3 c, Vec3 e1, Vec3 e2) {
        Object o;
        o.kind = Object::Kind::Quads;
        o.name = name;
        o.id = int(s.objects.size());
        o.material = mat;
        o.positions = {c, c + e1, c + e1 + e2, c + e2};
        o.indices = {0, 1, 2, 3};
        s.objects.push_back(o);
    };
    quad("floor", 0, {-1, 0, -1}, {0, 0, 2}, {2, 0, 0});
    quad("back-wall", 0, {-1, 0, -1}, {2, 0, 0}, {0, 2, 0});
    quad("left-wall", 1, {-1, 0, -1}, {0, 2, 0}, {0, 0, 2});
    Light l;
    l.name = "light";
    l.corner = Vec3(-0.15f, 1.5f, -0.15f);
    l.edge1 = Vec3(0.3f, 0, 0);
    l.edge2 = Vec3(0, 0, 0.3f);  // e1 × e2 = (0, -0.09, 0): facing down
    l.radiance = Vec3(60.f);
    s.lights = {l};
    s.movableLight = 0;
    s.lightRegion.expand(Vec3(-0.5f, 1.0f, -0.4f));
    s.lightRegion.expand(Vec3(0.5f, 1.6f, 0.4f));
    s.camera.eye = Vec3(0.6f, 1.2f, 3.0f);
    s.camera.target = Vec3(-0.2f, 0.4f, -0.4f);
    s.camera.fovYDegrees = 45.f;
    s.camera.width = s.camera.height = 40;
    return s;
}

SamplingSettings sampling() {
    SamplingSettings ss;
    ss.nx = ss.ny = ss.nz = 4;
    ss.directions = 60;
    ss.spp = 16;
    ss.maxSpp = 16;  // fixed paths per record: the bound below was measured with 16-path targets
    return ss;
}

enum class Breakage { None, ShuffledTargets, WrongLightInput };

struct RunResult {
    double meanRelativeRmse = 0;  ///< global term, all object pixels, mean over the held-out lights
    double seconds = 0;
};

RunResult run(const Scene& scene, const GeneratedData& data, const std::vector<Reference>& refs, Breakage breakage) {
    Stopwatch clock;
    const RecordLayout layout = RecordLayout::forScene(scene);
    std::vector<ObjectSamples> samples = samplesFromGenerated(data, scene, layout);
    for (ObjectSamples& s : samples) {
        const size_t n = s.size(), in = size_t(s.numInputs);
        if (breakage == Breakage::ShuffledTargets) {
            // Fisher–Yates over records: each record keeps its inputs but gets another record's targets.
            for (size_t i = n; i > 1; --i) {
                const size_t j = Rng(7, uint64_t(s.objectId), i).uniformInt(uint32_t(i));
                for (int c = 0; c < 3; ++c) {
                    std::swap(s.direct[3 * (i - 1) + c], s.direct[3 * j + c]);
                    std::swap(s.indirect[3 * (i - 1) + c], s.indirect[3 * j + c]);
                }
            }
        } else if (breakage == Breakage::WrongLightInput) {
            // The light columns get positions unrelated to the light that produced the targets.
            const Bounds3& r = scene.lightRegion;
            for (size_t i = 0; i < n; ++i) {
                Rng rng(11, uint64_t(s.objectId), i);
                for (int c = 0; c < 3; ++c) s.inputs[i * in + 6 + size_t(c)] = r.lo[c] + r.extent()[c] * rng.uniform();
            }
        }
    }
    ObjectTrainingOptions o = test::plainTraining();
    o.hidden = {20, 10};
    o.targets = TargetMode::Separate;
    o.trainer.lm.maxEpochs = 60;
    const ModelSet models = modelSetFromTrained(trainObjects(samples, o), scene, layout);
    PredictionSettings learned;  // both terms learned: the bounds below were measured so
    learned.direct = PredictionSettings::Direct::Network;
    const Predictor predictor(scene, models, learned);
    RunResult r;
    for (const Reference& ref : refs) r.meanRelativeRmse += evaluate(predictor, ref).term(Term::Global).overall.relativeRmse;
    r.meanRelativeRmse /= double(refs.size());
    r.seconds = clock.seconds();
    return r;
}

}  // namespace

TEST(EndToEnd, HeldOutLightsAreInsideTheRegionAndNotTrainingPositions) {
    const Scene scene = cornerScene();
    const std::vector<Vec3> held = heldOutLightPositions(scene.lightRegion, 16, 1);
    ASSERT_EQ(held.size(), 16u);
    EXPECT_EQ(held, heldOutLightPositions(scene.lightRegion, 16, 1));  // deterministic
    SamplingSettings ss = sampling();
    ss.nx = ss.ny = ss.nz = 2;
    ss.directions = 50;
    ss.spp = 1;
    const GeneratedData data = DataGenerator(scene, ss).run();
    const int fpr = RecordLayout::forScene(scene).floatsPerRecord();
    size_t records = 0;
    for (const Vec3& h : held) {
        EXPECT_TRUE(scene.lightRegion.contains(h));
        for (const auto& recs : data.perObject)
            for (size_t i = 0; i + size_t(fpr) <= recs.size(); i += size_t(fpr)) {
                ASSERT_NE(Vec3(recs[i + 6], recs[i + 7], recs[i + 8]), h);
                ++records;
            }
    }
    EXPECT_GT(records, 1000u);
    // Distinct positions, spread over the region (not a degenerate stream).
    Bounds3 spread;
    for (const Vec3& h : held) spread.expand(h);
    for (int c = 0; c < 3; ++c) EXPECT_GT(spread.extent()[c], 0.5f * scene.lightRegion.extent()[c]);
}

TEST(EndToEnd, SmallRunLearnsAndBrokenPipelinesFail) {
    Stopwatch total;
    const Scene scene = cornerScene();
    const GeneratedData data = DataGenerator(scene, sampling()).run();
    std::vector<Reference> refs;
    RenderOptions ro;
    ro.width = ro.height = 40;
    ro.spp = 256;
    ro.seed = 99;
    for (const Vec3& lp : heldOutLightPositions(scene.lightRegion, 3, 5)) refs.push_back(renderReference(scene, lp, ro));
    const RunResult good = run(scene, data, refs, Breakage::None);
    const RunResult shuffled = run(scene, data, refs, Breakage::ShuffledTargets);
    const RunResult wrongLight = run(scene, data, refs, Breakage::WrongLightInput);
    std::printf("relative RMSE of global (mean over 3 held-out lights): good %.4f (%.1f s), shuffled %.4f (%.1f s), "
                "wrong light %.4f (%.1f s); total %.1f s\n",
                good.meanRelativeRmse, good.seconds, shuffled.meanRelativeRmse, shuffled.seconds,
                wrongLight.meanRelativeRmse, wrongLight.seconds, total.seconds());
    // The bound. Measured (this machine, deterministic): good ≈ 0.26, light input decorrelated ≈ 1.1,
    // targets shuffled ≈ 1.7. What sets the good value: 4³ viewpoints × 60 directions (≈ 3.8k records),
    // 16-path targets and 60 LM epochs of a 20-10 net leave a smooth fit whose largest relative errors
    // sit on dark pixels (the +0.01 in |d|/(ref+0.01) matters there) and on edge pixels where the
    // box-filtered reference mixes two surfaces; the 256-spp references add ≈ 0.05 of their own noise.
    // A network that ignores the light can only predict the light-averaged image: the light moves over
    // 1 × 0.6 × 0.8 at 0.5–1.5 above the surfaces, which changes the shading by a factor ≈ 3, so its
    // error is of the order of 1. 0.45 leaves the good run 1.7× headroom against changes in
    // floating-point order and sits 2.4× below the best broken pipeline. (120 directions gave good
    // ≈ 0.23 at twice the training time; 3³ viewpoints gave ≈ 0.36, too close to the bound.)
    const double bound = 0.45;
    EXPECT_LT(good.meanRelativeRmse, bound);
    EXPECT_GT(shuffled.meanRelativeRmse, bound);
    EXPECT_GT(wrongLight.meanRelativeRmse, bound);
}

TEST(EndToEnd, SppSweepShowsTheMonteCarloSlope) {
    EXPECT_NEAR(logLogSlope({1, 4, 16}, {1.0, 0.5, 0.25}), -0.5, 1e-12);
    SweepOptions o;
    o.training = test::plainTraining();
    o.what = "spp";
    o.values = {"1", "2", "4", "8", "16"};
    o.width = o.height = 48;
    o.referenceSpp = 1024;
    const Project cornell = loadProjectOrScene(std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/project.json");
    const SweepResult r = runSweep(cornell.scene, o);
    ASSERT_EQ(r.rows.size(), 5u);
    // RMSE ∝ N^-1/2 for an unbiased estimator; the 1024-spp reference's own noise flattens the curve by
    // less than 1 % at 16 spp. The RMSE is dominated by the pixels on the light's edge (the box filter
    // samples 0 or 18), a few dozen of 2304, so the fitted slope scatters by several hundredths.
    EXPECT_NEAR(r.extra.loglogSlopeRmse.value(), -0.5, 0.1);
    for (size_t i = 1; i < r.rows.size(); ++i) EXPECT_LT(r.rows[i].overall.rmse, r.rows[i - 1].overall.rmse);
    EXPECT_NE(sweepCsv(cornell.scene, r).find("spp,16,"), std::string::npos);
}

}  // namespace test_end_to_end
