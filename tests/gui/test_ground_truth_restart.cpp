// The ground truth's restart after scene edits: a structural edit (an opened project) restarts the
// render at once; edits of materials or the light, which come one per frame of a drag, restart it
// once they rest, so a drag does not start and stop a render (with its BVH build) every frame.
#include <chrono>
#include <functional>
#include <thread>

#include <gtest/gtest.h>

#include "app/gui/ground_truth_controller.h"
#include "app/gui/job_runner.h"
#include "panels/project_io.h"

namespace rrf::test::test_ground_truth_restart {

namespace {
using Clock = std::chrono::steady_clock;

/// Polls `gt` every millisecond until `done()` holds, for at most a minute. Returns done().
bool pollUntil(GroundTruthController& gt, const std::function<bool()>& done) {
    const auto deadline = Clock::now() + std::chrono::seconds(60);
    while (!done() && Clock::now() < deadline) {
        gt.poll();
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return done();
}
}  // namespace

TEST(GroundTruthRestart, LightEditsRestartTheRenderOnceTheyRest) {
    panels::WorkbenchState state;
    std::string error;
    ASSERT_TRUE(panels::loadProjectIntoState(state, RRF_SOURCE_DIR "/projects/cornell-box/project.json", error)) << error;
    state.project.render.spp = 1 << 20;  // runs until stopped
    state.project.render.width = state.project.render.height = 16;
    JobRunner jobs;
    ControllerContext ctx{state, jobs};
    ctx.untitled = true;  // nothing stored next to the bundled project
    GroundTruthController gt(ctx);
    ASSERT_TRUE(gt.start());
    const RenderSession* first = gt.session().get();

    // A drag: one light edit per frame, each followed by the frame's poll.
    Clock::time_point lastEdit;
    for (int frame = 0; frame < 20; ++frame) {
        gt.restart(/*afterRest=*/true);
        lastEdit = Clock::now();
        gt.poll();
        EXPECT_EQ(gt.session().get(), first) << "no render starts while the edits come, frame " << frame;
        EXPECT_TRUE(gt.restartPending());
        EXPECT_FALSE(gt.shown()) << "the old light's image is not the ground truth of the edited scene";
        EXPECT_FALSE(gt.converged());
    }
    ASSERT_TRUE(pollUntil(gt, [&] { return gt.session().get() != first; })) << "the render restarts once the edits rest";
    const double rested = std::chrono::duration<double>(Clock::now() - lastEdit).count();
    EXPECT_GE(rested, kRestartRestSeconds);
    EXPECT_TRUE(gt.running());
    EXPECT_FALSE(gt.restartPending());

    // An edit that is not part of a drag (a project opened) restarts at once.
    gt.cancel();
    ASSERT_TRUE(pollUntil(gt, [&] { return !gt.running(); }));
    const RenderSession* second = gt.session().get();
    gt.restart();
    EXPECT_NE(gt.session().get(), second) << "started in the call, no rest awaited";
    EXPECT_FALSE(gt.restartPending());
    gt.cancel();
    jobs.waitAll();
}

}  // namespace rrf::test::test_ground_truth_restart
