// How `mpirun -n N rrf sweep|pipeline` splits what is not split by cells or objects (docs/cluster.md),
// tested without MPI: a render's interleaved rows, rendered apart, sent as bytes and joined, against
// the whole render bit for bit; a sweep's tasks run in two parts, sent as bytes and joined in either
// order, against the single-process sweep (every error, count and break-even; only times differ).

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/pipeline/sweep.h"
#include "core/pipeline/sweep_parts.h"
#include "core/predict/footprint_mask.h"
#include "core/predict/gbuffer.h"
#include "core/render/render_rows.h"
#include "core/scene/accel.h"
#include "scene_builders.h"
#include "tests/training_builders.h"

namespace test_cluster_sweep {

using namespace rrf;

/// Bit equality of doubles (NaN equals NaN of the same bits).
bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

RenderState renderState(const Scene& scene, const Accel& accel, RenderOptions o) {
    Renderer renderer(scene, accel, o);
    renderer.run();
    return renderer.exportState();
}

/// The figures of an error that do not depend on time, compared bit for bit.
void expectSameStats(const ErrorStats& a, const ErrorStats& b, const std::string& where) {
    EXPECT_EQ(a.pixels, b.pixels) << where;
    EXPECT_TRUE(sameBits(a.rmse, b.rmse)) << where;
    EXPECT_TRUE(sameBits(a.relativeRmse, b.relativeRmse)) << where;
    EXPECT_TRUE(sameBits(a.relativeRmseCorrected, b.relativeRmseCorrected)) << where;
    EXPECT_TRUE(sameBits(a.maxError, b.maxError)) << where;
}

TEST(ClusterRender, InterleavedRowsJoinIntoTheWholeRenderBitForBit) {
    const Scene scene = test::cornellLike(1.f, 16);
    const Accel accel(scene);
    RenderOptions o;
    o.width = 16;
    o.height = 11;  // not a multiple of the 3 parts: the last part has one row fewer
    o.spp = 4;
    o.samplesPerPass = 2;
    const RenderState whole = renderState(scene, accel, o);
    std::vector<std::string> parts, names;
    for (int r = 0; r < 3; ++r) {
        RenderOptions part = o;
        part.rowOffset = r;
        part.rowStride = 3;
        const RenderState state = renderState(scene, accel, part);
        // A part samples its own rows only: rows 0, 3, 6, 9 for part 0.
        for (int y = 0; y < o.height; ++y)
            EXPECT_EQ(state.pixels[size_t(y) * 16].accepted > 0, y % 3 == r) << "part " << r << " row " << y;
        parts.push_back(encodeRenderRows(state, r, 3));
        names.push_back("rank " + std::to_string(r));
    }
    const RenderState joined = joinRenderRows(parts, names);
    ASSERT_EQ(joined.pixels.size(), whole.pixels.size());
    EXPECT_EQ(std::memcmp(joined.pixels.data(), whole.pixels.data(), whole.pixels.size() * sizeof(PixelSums)), 0)
        << "the joined rows differ from the whole render";
    EXPECT_EQ(joined.samples, whole.samples);
    EXPECT_EQ(joined.rays, whole.rays);
    EXPECT_EQ(joined.sppDone, 4);
    EXPECT_EQ(joined.passes, 2);
    // Parts in another order are refused by the rows they hold.
    std::swap(parts[0], parts[1]);
    try {
        joinRenderRows(parts, names);
        ADD_FAILURE() << "parts out of order were accepted";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("rank 0: rows 1 mod 3, expected 0 mod 3"), std::string::npos) << e.what();
    }
}

TEST(ClusterRender, PartsOfAnotherPassCountOrRowsOutOfRangeAreRefused) {
    const Scene scene = test::cornellLike(1.f, 16);
    const Accel accel(scene);
    RenderOptions o;
    o.width = 8;
    o.height = 6;
    o.spp = 4;
    o.samplesPerPass = 2;
    std::vector<std::string> parts;
    for (int r = 0; r < 2; ++r) {
        RenderOptions part = o;
        part.rowOffset = r;
        part.rowStride = 2;
        // Part 1 reaches the same 4 spp in 4 passes of 1 sample: not the same render.
        if (r == 1) part.samplesPerPass = 1;
        parts.push_back(encodeRenderRows(renderState(scene, accel, part), r, 2));
    }
    try {
        joinRenderRows(parts, {"rank 0", "rank 1"});
        ADD_FAILURE() << "parts of 2 and 4 passes were joined";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("rank 1: a render of 8x6 at 4 spp in 4 passes, the first part's is 8x6 at 4 spp in 2 passes"),
                  std::string::npos)
            << e.what();
    }
    // Rows that select nothing (offset outside [0, stride)) or no stride at all are refused.
    for (const auto& [offset, stride] : std::vector<std::pair<int, int>>{{2, 2}, {-1, 2}, {0, 0}}) {
        RenderOptions bad = o;
        bad.rowOffset = offset;
        bad.rowStride = stride;
        EXPECT_THROW((Renderer(scene, accel, bad)), std::invalid_argument) << offset << " mod " << stride;
    }
}

TEST(ClusterSweep, TasksRunApartJoinIntoTheSingleProcessSweep) {
    const Scene scene = test::cornellLike(1.f, 16);
    SweepOptions o;
    o.training = test::plainTraining();
    o.what = "hidden";
    o.values = {"3", "2,2"};
    o.width = o.height = 16;
    o.referenceSpp = 8;
    o.pathTracerSpp = {1, 2, 4};
    o.sampling.nx = o.sampling.ny = o.sampling.nz = 2;
    o.sampling.directions = 20;
    o.sampling.spp = 2;
    o.training.trainer.lm.maxEpochs = 2;
    const SweepResult single = runSweep(scene, o);

    const SweepOptions checked = checkedSweepOptions(scene, o);
    const std::vector<SweepTask> tasks = sweepTasks(checked);
    ASSERT_EQ(tasks.size(), 3u) << "the path tracer's series and one task per value";
    EXPECT_TRUE(tasks[0].series);
    EXPECT_EQ(tasks[0].maxSpp, 4);
    EXPECT_EQ(tasks[2].training.hidden, (std::vector<int>{2, 2}));
    EXPECT_TRUE(sweepSharesData(checked));
    // The reference crosses a process boundary as bytes, as rank 0 sends it.
    const Reference obtained = obtainSweepReference(scene, checked);
    const Reference reference = decodeReference(encodeReference(obtained), "rank 0");
    EXPECT_EQ(reference.spp, 8);
    EXPECT_TRUE(reference.image(Term::Global).data == obtained.image(Term::Global).data);
    EXPECT_TRUE(reference.variance(Term::Global).data == obtained.variance(Term::Global).data);
    auto data = std::make_shared<const GeneratedData>(DataGenerator(scene, checked.sampling).run(0, 1));
    const SweepInputs inputs = sweepInputs(scene, checked, reference, data);
    // Point 1 on one rank, the series and point 2 on another; rank 0 receives them in any order.
    std::vector<SweepPart> parts;
    for (const std::vector<int>& share : {std::vector<int>{1}, std::vector<int>{0, 2}})
        parts.push_back(decodeSweepPart(encodeSweepPart(runSweepTasks(scene, checked, inputs, share)), "a rank"));
    const SweepResult joined = joinSweepParts(scene, checked, inputs, parts);

    ASSERT_EQ(joined.rows.size(), 2u);
    ASSERT_TRUE(single.rows[0].breakEven.known) << "the series must give the first point a break-even to compare";
    ASSERT_EQ(joined.pathTracer.size(), single.pathTracer.size());
    for (size_t i = 0; i < 2; ++i) {
        const SweepRow &a = single.rows[i], &b = joined.rows[i];
        EXPECT_EQ(a.setting, b.setting);
        expectSameStats(a.overall, b.overall, "row " + a.setting);
        ASSERT_EQ(a.perObject.size(), b.perObject.size());
        for (size_t k = 0; k < a.perObject.size(); ++k) expectSameStats(a.perObject[k], b.perObject[k], "object " + std::to_string(k));
        EXPECT_EQ(a.extra.parameters, b.extra.parameters);
        EXPECT_EQ(a.extra.leafEpochs, b.extra.leafEpochs);
        // The break-even comes from the joined series, which another part rendered.
        EXPECT_EQ(a.breakEven.known, b.breakEven.known) << a.setting;
        EXPECT_TRUE(sameBits(a.breakEven.spp, b.breakEven.spp)) << a.setting;
    }
    EXPECT_EQ(joined.rows[0].setting, "3") << "rows in the order of the values";
    for (size_t i = 0; i < single.pathTracer.size(); ++i)
        expectSameStats(single.pathTracer[i].overall, joined.pathTracer[i].overall, "spp " + single.pathTracer[i].setting);
    EXPECT_TRUE(sameBits(single.relativeNoiseFloor, joined.relativeNoiseFloor));
    EXPECT_TRUE(joined.extra.generateSeconds.has_value());
    // runSweep is these very functions in one process, so beside it the joined sweep is checked
    // against what is built apart: the series' spp and the pixels of the footprint mask made
    // independently from the G-buffer at the sweep's light (every error is over those pixels).
    ASSERT_EQ(joined.pathTracer.size(), 3u);
    for (size_t i = 0; i < 3; ++i) EXPECT_EQ(joined.pathTracer[i].spp, 1 << i);
    const Accel accel(scene);
    const PathTracer tracer(scene, accel, Estimator::NEE, 1);
    const FootprintMask mask =
        footprintMask(buildGBuffer(tracer, RecordLayout::forScene(scene), joined.lightPosition, o.width, o.height));
    ASSERT_GT(mask.kept.size(), 0u);
    for (const SweepRow& row : joined.rows) EXPECT_EQ(row.overall.pixels, mask.kept.size()) << row.setting;
    for (const SweepRow& row : joined.pathTracer) EXPECT_EQ(row.overall.pixels, mask.kept.size()) << row.setting;

    // A task left out, or run twice, is refused by name.
    try {
        joinSweepParts(scene, checked, inputs, {parts[1]});
        ADD_FAILURE() << "a missing task was accepted";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("task 1 (3) is missing"), std::string::npos) << e.what();
    }
    EXPECT_THROW(joinSweepParts(scene, checked, inputs, {parts[0], parts[1], parts[0]}), std::runtime_error);
}

}  // namespace test_cluster_sweep
