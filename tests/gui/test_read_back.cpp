// Reads the UI would wait for, done on workers (issue 29: no UI-thread stall over 100 ms at open):
// the ReadBack session hands a result over only in a later poll() and only the latest request's, and
// the picking map (BVH + one ray per pixel) is built on a worker and published when it arrives, the
// views keeping the previous map (or none, for a new project) meanwhile.
#include <atomic>
#include <chrono>
#include <functional>
#include <thread>

#include <gtest/gtest.h>

#include "app/gui/job_runner.h"
#include "app/gui/picking_controller.h"
#include "app/gui/read_back.h"
#include "app/gui/render_session.h"
#include "panels/project_io.h"

namespace rrf::test::test_read_back {

namespace {
using Clock = std::chrono::steady_clock;

/// Calls `poll` every millisecond until `done()` holds, for at most a minute. Returns done().
bool pollUntil(const std::function<void()>& poll, const std::function<bool()>& done) {
    const auto deadline = Clock::now() + std::chrono::seconds(60);
    while (!done() && Clock::now() < deadline) {
        poll();
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return done();
}

void loadCornellBox(panels::WorkbenchState& state) {
    std::string error;
    ASSERT_TRUE(panels::loadProjectIntoState(state, RRF_SOURCE_DIR "/projects/cornell-box/project.json", error)) << error;
    state.project.render.width = 48;
    state.project.render.height = 32;
}
}  // namespace

TEST(ReadBack, ResultArrivesInALaterPollAndOnlyTheLatestRequests) {
    panels::WorkbenchState state;
    JobRunner jobs;
    ReadBack<int> read(jobs, state.log);
    std::atomic<bool> release{false};
    int arrived = 0, calls = 0;
    ASSERT_TRUE(read.start("first", [&](JobContext& ctx) -> std::optional<int> {
        while (!release && !ctx.cancelled()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        return 1;
    }, [&](int& v) { arrived = v, ++calls; }));
    EXPECT_TRUE(read.pending());
    read.poll();
    EXPECT_EQ(calls, 0) << "nothing arrives while the worker runs";
    // A newer request replaces the one in flight: the first one's result never lands.
    ASSERT_TRUE(read.start("second", [](JobContext&) -> std::optional<int> { return 2; }, [&](int& v) { arrived = v, ++calls; }));
    release = true;
    ASSERT_TRUE(pollUntil([&] { read.poll(); }, [&] { return !read.pending(); }));
    EXPECT_EQ(arrived, 2);
    EXPECT_EQ(calls, 1);
    // A dropped read (another project opened) never arrives.
    ASSERT_TRUE(read.start("third", [](JobContext&) -> std::optional<int> { return 3; }, [&](int& v) { arrived = v, ++calls; }));
    read.drop();
    EXPECT_FALSE(read.pending());
    jobs.waitAll();
    read.poll();
    EXPECT_EQ(calls, 1);
    // A read that delivers nothing (it failed, or was cancelled) ends without a call.
    ASSERT_TRUE(read.start("nothing", [](JobContext&) -> std::optional<int> { return std::nullopt; }, [&](int&) { ++calls; }));
    ASSERT_TRUE(pollUntil([&] { read.poll(); }, [&] { return !read.pending(); }));
    EXPECT_EQ(calls, 1);
}

TEST(ReadBack, OnArrivedMayStartTheNextRead) {
    panels::WorkbenchState state;
    JobRunner jobs;
    ReadBack<int> read(jobs, state.log);
    std::vector<int> seen;
    std::function<void(int&)> chain = [&](int& v) {
        seen.push_back(v);
        if (v < 3) read.start("next", [n = v + 1](JobContext&) -> std::optional<int> { return n; }, chain);
    };
    ASSERT_TRUE(read.start("first", [](JobContext&) -> std::optional<int> { return 1; }, chain));
    ASSERT_TRUE(pollUntil([&] { read.poll(); }, [&] { return seen.size() == 3 && !read.pending(); }));
    EXPECT_EQ(seen, (std::vector<int>{1, 2, 3}));
}

TEST(PickingController, TheMapIsBuiltOnAWorkerAndPublishedWhenItArrives) {
    panels::WorkbenchState state;
    loadCornellBox(state);
    JobRunner jobs;
    ControllerContext ctx{state, jobs};
    PickingController picking(ctx);
    int published = 0;
    picking.onPublished = [&] { ++published; };

    // Opening the project: the call returns without having traced anything (the old workbench
    // built the BVH and traced every pixel here, on the UI thread).
    picking.sceneChanged(/*geometryChanged=*/true);
    EXPECT_TRUE(picking.pending());
    EXPECT_FALSE(state.pickAccel) << "no map before its build has arrived";
    EXPECT_TRUE(state.objectIds.empty());
    ASSERT_TRUE(pollUntil([&] { picking.poll(); }, [&] { return !picking.pending(); }));
    ASSERT_TRUE(state.pickAccel);
    EXPECT_EQ(published, 1);
    const Camera camera = groundTruthCamera(state.project.scene, state.project.render);
    ASSERT_EQ(state.idWidth, camera.width);
    ASSERT_EQ(state.idHeight, camera.height);
    ASSERT_EQ(state.objectIds.size(), size_t(camera.width) * size_t(camera.height));
    // The same ids as the single-threaded build of the same scene and size.
    const std::optional<PickingMap> direct = buildPickingMap(std::make_shared<const Scene>(state.project.scene), camera.width, camera.height);
    ASSERT_TRUE(direct);
    EXPECT_EQ(state.objectIds, direct->objectIds);
    int objects = 0;
    for (int id : state.objectIds) objects += id >= 0;
    EXPECT_GT(objects, int(state.objectIds.size()) / 2) << "the box fills most of the view";

    // The light moves (a drag): nothing is rebuilt.
    picking.sceneChanged(/*geometryChanged=*/false);
    EXPECT_FALSE(picking.pending());

    // The geometry changes: the old map stays on screen until the new one arrives.
    const std::shared_ptr<const Accel> old = state.pickAccel;
    const uint64_t revision = state.idsRevision;
    picking.sceneChanged(/*geometryChanged=*/true);
    EXPECT_TRUE(picking.pending());
    EXPECT_EQ(state.pickAccel, old);
    ASSERT_TRUE(pollUntil([&] { picking.poll(); }, [&] { return !picking.pending(); }));
    EXPECT_NE(state.pickAccel, old);
    EXPECT_GT(state.idsRevision, revision) << "the views redraw the highlight with the new map";

    // The view size changes: a map of the new size.
    state.project.render.width = 24;
    state.project.render.height = 16;
    picking.sceneChanged(/*geometryChanged=*/false);
    ASSERT_TRUE(pollUntil([&] { picking.poll(); }, [&] { return !picking.pending(); }));
    EXPECT_EQ(state.idWidth, 24);
    EXPECT_EQ(state.objectIds.size(), size_t(24 * 16));

    // Another project: the old map goes at once, and a build in flight never lands.
    picking.sceneChanged(/*geometryChanged=*/true);
    picking.drop();
    EXPECT_FALSE(state.pickAccel);
    EXPECT_TRUE(state.objectIds.empty());
    jobs.waitAll();
    picking.poll();
    EXPECT_FALSE(state.pickAccel);
}

TEST(PickingController, ACancelledBuildStopsEarly) {
    panels::WorkbenchState state;
    loadCornellBox(state);
    std::atomic<bool> cancel{true};
    EXPECT_FALSE(buildPickingMap(std::make_shared<const Scene>(state.project.scene), 64, 64, &cancel));
}

}  // namespace rrf::test::test_read_back
