// Per-object training: target modes, skipped and tiny objects, thread-count independence.
#include <gtest/gtest.h>

#include <cmath>
#include <mutex>

#include <tbb/global_control.h>

#include "core/nn/object_training.h"
#include "tests/synthetic_samples.h"

using namespace rrf;

namespace {

ObjectTrainingOptions lmOptions(int epochs) {
    ObjectTrainingOptions o;
    o.trainer = TrainerConfig::fromJson({{"type", "levenberg_marquardt"}, {"max_epochs", epochs}});
    return o;
}

}  // namespace

TEST(ObjectTraining, SamplesMapWithoutCopy) {
    const ObjectSamples s = syntheticObject(1, 5);
    EXPECT_EQ(s.size(), 5u);
    EXPECT_EQ(s.inputMatrix()(3, 2), s.inputs[2 * 14 + 3]);
    EXPECT_EQ(s.indirectMatrix()(1, 4), s.indirect[4 * 3 + 1]);
    EXPECT_EQ(s.inputMatrix().data(), s.inputs.data());
    ObjectSamples bad = s;
    bad.direct.pop_back();
    EXPECT_THROW(bad.validate(), std::invalid_argument);
}

TEST(ObjectTraining, SkipsEmptyAndUnknownObjectsAndTrainsSingleSample) {
    std::vector<ObjectSamples> objs = {syntheticObject(0, 300), syntheticObject(1, 0), syntheticObject(2, 1)};
    ObjectTrainingOptions o = lmOptions(5);
    o.objects = {0, 1, 2, 9};
    std::mutex mu;
    std::vector<std::string> messages;
    int epochs = 0;
    ObjectTrainingObserver obs;
    obs.onMessage = [&](const std::string& m) {
        std::lock_guard<std::mutex> lock(mu);
        messages.push_back(m);
    };
    obs.onEpoch = [&](int, const std::string& target, const EpochRecord&) {
        std::lock_guard<std::mutex> lock(mu);
        EXPECT_EQ(target, "global");
        ++epochs;
    };
    const std::vector<ObjectModel> r = trainObjects(objs, o, obs);
    ASSERT_EQ(r.size(), 4u);
    EXPECT_FALSE(r[0].skipped);
    EXPECT_TRUE(r[1].skipped);
    EXPECT_NE(r[1].message.find("no samples"), std::string::npos);
    EXPECT_FALSE(r[2].skipped);
    EXPECT_TRUE(r[3].skipped);
    EXPECT_NE(r[3].message.find("not in the training data"), std::string::npos);
    EXPECT_GT(epochs, 2);
    bool sawEmpty = false;
    for (const auto& m : messages) sawEmpty |= m.find("no samples") != std::string::npos;
    EXPECT_TRUE(sawEmpty);

    // The single-sample object: trained, finite, reproduces its one target.
    const NetworkModel& one = r[2].model.leaves[0];
    EXPECT_EQ(one.training.trainSamples, 1);
    EXPECT_TRUE(one.params.allFinite());
    const MatX<float> p = one.predict(objs[2].inputMatrix());
    const MatX<float> t = objs[2].directMatrix() + objs[2].indirectMatrix();
    EXPECT_LT((p - t).cwiseAbs().maxCoeff(), 1e-4f);
    EXPECT_EQ(r[0].model.objectId(), 0);
    EXPECT_EQ(r[0].model.arch().inputs, 14);
    EXPECT_TRUE(r[0].model.predict(objs[0].inputMatrix()).allFinite());
}

TEST(ObjectTraining, TargetModes) {
    const std::vector<ObjectSamples> objs = {syntheticObject(3, 200)};
    ObjectTrainingOptions o = lmOptions(3);
    o.hidden = {6};
    o.targets = TargetMode::Separate;
    std::vector<ObjectModel> r = trainObjects(objs, o);
    ASSERT_EQ(r.size(), 2u);
    EXPECT_EQ(r[0].target, "direct");
    EXPECT_EQ(r[1].target, "indirect");
    EXPECT_EQ(r[1].model.arch().outputs, 3);
    o.targets = TargetMode::Joint;
    r = trainObjects(objs, o);
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r[0].model.arch().outputs, 6);
    EXPECT_EQ(r[0].model.target(), "joint");
    EXPECT_EQ(parseTargetMode("indirect"), TargetMode::Indirect);
    EXPECT_THROW(parseTargetMode("both"), std::invalid_argument);
    EXPECT_EQ(modelFileName(3, "joint"), "object_3_joint.rrfm");
}

TEST(ObjectTraining, BitIdenticalForAnyThreadCountAndSelection) {
    const std::vector<ObjectSamples> objs = {syntheticObject(0, 400), syntheticObject(1, 250), syntheticObject(2, 300)};
    ObjectTrainingOptions o = lmOptions(4);
    o.trainer = TrainerConfig::fromJson({{"type", "adam"}, {"max_epochs", 3}});
    auto run = [&](int threads, std::vector<int> which) {
        tbb::global_control gc(tbb::global_control::max_allowed_parallelism, size_t(threads));
        ObjectTrainingOptions oo = o;
        oo.objects = std::move(which);
        return trainObjects(objs, oo);
    };
    const auto a = run(1, {}), b = run(2, {}), c = run(2, {2});
    ASSERT_EQ(a.size(), 3u);
    for (size_t i = 0; i < 3; ++i) EXPECT_EQ(a[i].model.leaves[0].params, b[i].model.leaves[0].params);
    EXPECT_EQ(c[0].model.leaves[0].params, a[2].model.leaves[0].params);
    EXPECT_NE(a[0].model.leaves[0].params.head(5), a[1].model.leaves[0].params.head(5));
}

TEST(ObjectTraining, CancelledBeforeStartIsSkipped) {
    const std::vector<ObjectSamples> objs = {syntheticObject(0, 50)};
    std::atomic<bool> cancel{true};
    ObjectTrainingObserver obs;
    obs.cancel = &cancel;
    const auto r = trainObjects(objs, lmOptions(5), obs);
    ASSERT_EQ(r.size(), 1u);
    EXPECT_TRUE(r[0].skipped);
    EXPECT_NE(r[0].message.find("cancelled"), std::string::npos);
}
