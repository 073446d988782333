// The job runner: progress and status from workers, cancel, failures, and refusal of conflicts.
#include <chrono>
#include <stdexcept>
#include <thread>

#include <gtest/gtest.h>

#include "app/gui/job_runner.h"

namespace rrf::test {

namespace {
/// Runs until cancelled, reporting progress.
void spinUntilCancelled(JobContext& ctx) {
    ctx.setStatus("spinning");
    ctx.setProgress(0.5);
    while (!ctx.cancelled()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

std::vector<JobInfo> waitFinished(JobRunner& runner) {
    runner.waitAll();
    return {};
}
}  // namespace

TEST(JobRunner, ConflictingJobIsRefusedWithAReason) {
    JobRunner runner;
    std::string why;
    const int a = runner.start(JobKind::Train, "train A", spinUntilCancelled, &why);
    ASSERT_NE(a, 0);
    EXPECT_EQ(runner.start(JobKind::Train, "train B", spinUntilCancelled, &why), 0);
    EXPECT_NE(why.find("train A"), std::string::npos) << why;
    EXPECT_EQ(runner.start(JobKind::Generate, "generate", spinUntilCancelled, &why), 0);
    const int r = runner.start(JobKind::Render, "render", spinUntilCancelled, &why);
    EXPECT_NE(r, 0) << "rendering does not conflict with training: " << why;
    EXPECT_EQ(runner.jobs().size(), 2u);
    runner.cancelAll();
    runner.waitAll();
    EXPECT_TRUE(runner.idle());
}

TEST(JobRunner, ProgressStatusCancelAndFinish) {
    JobRunner runner;
    bool hookCalled = false;
    const int id = runner.start(JobKind::Render, "r", [&](JobContext& ctx) {
        ctx.onCancel([&] { hookCalled = true; });
        spinUntilCancelled(ctx);
        ctx.setStatus("stopped");
    });
    ASSERT_NE(id, 0);
    for (int i = 0; i < 2000 && runner.jobs().at(0).status != "spinning"; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    const JobInfo info = runner.jobs().at(0);
    EXPECT_EQ(info.status, "spinning");
    EXPECT_DOUBLE_EQ(info.progress, 0.5);
    EXPECT_TRUE(info.running);
    runner.cancel(id);
    for (int i = 0; i < 2000 && !runner.idle(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    const std::vector<JobInfo> done = runner.takeFinished();
    ASSERT_EQ(done.size(), 1u);
    EXPECT_TRUE(done[0].cancelled);
    EXPECT_FALSE(done[0].failed);
    EXPECT_EQ(done[0].status, "stopped");
    EXPECT_TRUE(hookCalled);
    EXPECT_TRUE(runner.takeFinished().empty()) << "each finished job is reported once";
    // The slot is free again.
    EXPECT_NE(runner.start(JobKind::Render, "again", [](JobContext&) {}), 0);
    waitFinished(runner);
}

TEST(JobRunner, ExceptionsMarkTheJobFailed) {
    JobRunner runner;
    runner.start(JobKind::Evaluate, "boom", [](JobContext&) { throw std::runtime_error("no models"); });
    for (int i = 0; i < 2000 && !runner.idle(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    const std::vector<JobInfo> done = runner.takeFinished();
    ASSERT_EQ(done.size(), 1u);
    EXPECT_TRUE(done[0].failed);
    EXPECT_EQ(done[0].error, "no models");
}

TEST(JobRunner, ConflictMatrixIsSymmetric) {
    const JobKind kinds[] = {JobKind::Render, JobKind::Generate, JobKind::Train,
                             JobKind::Evaluate, JobKind::Predict, JobKind::Sweep};
    for (JobKind a : kinds)
        for (JobKind b : kinds) EXPECT_EQ(jobsConflict(a, b), jobsConflict(b, a));
    EXPECT_FALSE(jobsConflict(JobKind::Render, JobKind::Generate));
    EXPECT_TRUE(jobsConflict(JobKind::Train, JobKind::Predict)) << "prediction reads the models training replaces";
    EXPECT_FALSE(jobsConflict(JobKind::Sweep, JobKind::Train)) << "a sweep writes no project files";
}

}  // namespace rrf::test
