// The GL worker (app/gl/gl_worker.h) and the live prediction on it (app/gui/live_prediction.h),
// issue 29: the prediction's shaders are compiled, and its frames rendered, by a context of the
// worker's own thread, so the UI thread never waits for llvmpipe's compiles. What the worker
// renders must be what a predictor on the calling thread renders.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>
#include <vector>

#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include "app/gl/gl_worker.h"
#include "app/gl/glsl_predictor.h"
#include "app/gui/live_prediction.h"
#include "tests/gl/gl_test_env.h"
#include "tests/gl/glsl_comparison.h"
#include "tests/gl/test_models.h"

namespace rrf::test_gl_worker {
namespace {

double sum(const Image& im) {
    double s = 0.0;
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) s += im.at(x, y).x;
    return s;
}

/// Waits (up to a minute) until `ready` says so; false on time-out.
template <class F> bool waitFor(F ready) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!ready()) {
        if (std::chrono::steady_clock::now() > end) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return true;
}

}  // namespace

TEST(GlWorker, RunsTasksInOrderOnAThreadWithAContextOfItsOwn) {
    RRF_REQUIRE_GL();
    GLFWwindow* mine = glfwGetCurrentContext();
    GlWorker worker;
    EXPECT_EQ(glfwGetCurrentContext(), mine) << "making the worker leaves the caller's context current";
    const std::thread::id caller = std::this_thread::get_id();
    const auto where = worker.run([] {
        const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
        return std::make_pair(std::this_thread::get_id(), std::make_pair(glfwGetCurrentContext(), version != nullptr));
    });
    EXPECT_NE(where.first, caller);
    EXPECT_NE(where.second.first, nullptr);
    EXPECT_NE(where.second.first, mine) << "the worker draws with a context of its own";
    EXPECT_TRUE(where.second.second) << "GL answers on the worker";

    // Posted tasks run one at a time, in order, without the caller waiting for them.
    std::vector<int> order;
    std::atomic<bool> release{false};
    std::future<void> first = worker.post([&] {
        while (!release.load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        order.push_back(1);
    });
    std::future<void> second = worker.post([&] { order.push_back(2); });
    EXPECT_EQ(first.wait_for(std::chrono::milliseconds(20)), std::future_status::timeout);
    EXPECT_EQ(worker.pending(), 2);
    release = true;
    second.get();
    EXPECT_EQ(order, (std::vector<int>{1, 2}));

    // A task's exception reaches the caller; the worker goes on.
    EXPECT_THROW(worker.run([]() -> int { throw std::runtime_error("task failed"); }), std::runtime_error);
    EXPECT_EQ(worker.run([] { return 7; }), 7);
}

TEST(GlWorker, APredictorOnTheWorkerRendersWhatOneOnTheCallingThreadRenders) {
    RRF_REQUIRE_GL();
    const Scene scene = test::cornellBox();
    const ModelSet set = test::mixedModelSet(scene);
    Camera camera = scene.camera;
    camera.width = 64;
    camera.height = 48;
    const Vec3 light = scene.lightRegion.lo * 0.3f + scene.lightRegion.hi * 0.7f;
    auto render = [&] {
        GlslPredictor gp(scene, set);
        gp.setCamera(camera);
        gp.setPrediction(test::liveSettings());
        gp.setLightPosition(light);
        gp.render();
        std::vector<Image> out;
        for (Term t : kTerms) out.push_back(gp.read(t));
        return out;
    };
    const std::vector<Image> here = render();
    ASSERT_GT(sum(here[int(Term::Global)]), 0.0) << "the frame shows something to compare";
    GlWorker worker;
    const std::vector<Image> there = worker.run(render);
    for (Term t : kTerms) EXPECT_LE(test::maxRelativeDifference(there[int(t)], here[int(t)]), 1e-6) << termName(t);
}

TEST(LivePrediction, BuildsOnTheWorkerAndItsBandsMakeTheFrameItRendersWhole) {
    RRF_REQUIRE_GL();
    const Scene scene = test::cornellBox();
    auto set = std::make_shared<const ModelSet>(test::mixedModelSet(scene));
    LivePrediction live;
    live.load(scene, "test models", true, test::liveSettings(), set);
    EXPECT_TRUE(live.building());
    EXPECT_FALSE(live.loaded()) << "the models drive the prediction once the build is handed over";
    std::optional<LivePrediction::Build> build;
    ASSERT_TRUE(waitFor([&] { return (build = live.takeBuild()).has_value(); }));
    EXPECT_EQ(build->glslError, "");
    EXPECT_TRUE(live.loaded());
    EXPECT_TRUE(live.usesGlsl());
    EXPECT_FALSE(live.building());

    Camera camera = scene.camera;
    camera.width = 64;
    camera.height = 48;
    const Vec3 light = scene.lightRegion.lo * 0.3f + scene.lightRegion.hi * 0.7f;
    Image whole[kTermCount];
    const double seconds = live.renderGlsl(camera, light, test::liveSettings(), whole);
    EXPECT_GT(seconds, 0.0);
    ASSERT_GT(sum(whole[int(Term::Global)]), 0.0);

    // A draft of another size and light in between, then the frame in bands, bottom up.
    Camera draft = camera;
    draft.width = 16;
    draft.height = 12;
    Image scratch[kTermCount];
    live.renderGlsl(draft, scene.lightRegion.lo, test::liveSettings(), scratch);
    const int bands[] = {5, 20, 23};
    int done = 0;
    std::optional<LivePrediction::Rows> rows;
    for (int h : bands) {
        const int end = camera.height - done;
        live.startRows(camera, light, test::liveSettings(), end - h, end, done + h == camera.height);
        EXPECT_TRUE(live.rowsRunning());
        ASSERT_TRUE(waitFor([&] { return (rows = live.takeRows()).has_value(); }));
        EXPECT_FALSE(live.rowsRunning());
        EXPECT_GE(rows->wallSeconds, 0.0);
        done += h;
    }
    ASSERT_EQ(rows->images.size(), size_t(kTermCount)) << "the last band reads the frame back";
    for (Term t : kTerms) EXPECT_LE(test::maxRelativeDifference(rows->images[int(t)], whole[int(t)]), 1e-5) << termName(t);

    // Loading a new set keeps the one loaded until the new one is built.
    const std::shared_ptr<const ModelSet> first = live.models();
    auto second = std::make_shared<const ModelSet>(test::mixedModelSet(scene, Activation::Relu));
    live.load(scene, "second models", true, test::liveSettings(), second);
    EXPECT_TRUE(live.building());
    EXPECT_EQ(live.models(), first);
    EXPECT_TRUE(live.usesGlsl());
    ASSERT_TRUE(waitFor([&] { return (build = live.takeBuild()).has_value(); }));
    EXPECT_EQ(build->glslError, "");
    EXPECT_EQ(live.models(), second);
    EXPECT_EQ(live.dir(), "second models");

    // A dropped band is never handed over; reset releases the predictor on the worker.
    live.startRows(camera, light, test::liveSettings(), 0, camera.height, true);
    live.dropRows();
    EXPECT_FALSE(live.rowsRunning());
    EXPECT_FALSE(live.takeRows().has_value());
    live.reset();
    EXPECT_FALSE(live.loaded());
    EXPECT_FALSE(live.usesGlsl());
}

TEST(LivePrediction, AShaderThatCannotBeBuiltFallsBackToTheCpuPathWithTheReason) {
    RRF_REQUIRE_GL();
    const Scene scene = test::cornellBox();
    // Models whose networks do not fit the scene (an object id the scene does not have) make
    // packNetworkTexture refuse them on the worker: the load ends on the CPU path, saying why.
    ModelSet set = test::mixedModelSet(scene);
    set.objects.push_back(set.objects.front());
    set.objects.back().objectId = 999;
    LivePrediction live;
    live.load(scene, "test models", true, test::liveSettings(), std::make_shared<const ModelSet>(set));
    std::optional<LivePrediction::Build> build;
    ASSERT_TRUE(waitFor([&] { return (build = live.takeBuild()).has_value(); }));
    EXPECT_NE(build->glslError, "");
    EXPECT_TRUE(live.loaded());
    EXPECT_FALSE(live.usesGlsl());
}

}  // namespace rrf::test_gl_worker
