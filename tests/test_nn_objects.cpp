// Per-object training: target modes, skipped and tiny objects, thread-count independence.
#include <gtest/gtest.h>

#include <cmath>
#include <mutex>

#include <tbb/global_control.h>

#include "core/nn/encoding_settings_json.h"
#include "core/nn/model.h"
#include "core/nn/object_training.h"
#include "core/nn/trainer_config_json.h"
#include "core/nn/training_samples.h"
#include "core/util/error.h"
#include "tests/synthetic_samples.h"
#include "tests/training_builders.h"

namespace test_nn_objects {

using namespace rrf;

namespace {

ObjectTrainingOptions lmOptions(int epochs) {
    ObjectTrainingOptions o = test::plainTraining();
    o.trainer = trainerConfigFromJson({{"type", "levenberg_marquardt"}, {"max_epochs", epochs}});
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

TEST(ObjectTraining, EachTargetModeLearnsItsOwnTarget) {
    // Records laid out as the generator writes them (14 inputs, direct RGB, indirect RGB), read by
    // the same bridge as dataset files. Direct (≈ 1 … 3) and indirect (≈ 0.04 … 0.3) differ by an
    // order of magnitude, so a network fitted to one is far (relative RMSE ≫ 1) from the other.
    const ObjectSamples synth = syntheticObject(3, 200);
    std::vector<float> records;
    for (size_t i = 0; i < synth.size(); ++i) {
        records.insert(records.end(), synth.inputs.begin() + long(14 * i), synth.inputs.begin() + long(14 * (i + 1)));
        records.insert(records.end(), synth.direct.begin() + long(3 * i), synth.direct.begin() + long(3 * (i + 1)));
        records.insert(records.end(), synth.indirect.begin() + long(3 * i), synth.indirect.begin() + long(3 * (i + 1)));
    }
    uint64_t dropped = 0;
    const ObjectSamples s = objectSamples(3, "object3", records.data(), synth.size(), 14, false, dropped);
    EXPECT_EQ(dropped, 0u);
    ASSERT_EQ(s.direct, synth.direct);
    ASSERT_EQ(s.indirect, synth.indirect);

    const MatX<float> x = s.inputMatrix();
    const MatX<float> direct = s.directMatrix(), indirect = s.indirectMatrix();
    ObjectTrainingOptions o = lmOptions(60);
    o.hidden = {6};
    o.targets = TargetMode::Separate;
    const std::vector<ObjectModel> sep = trainObjects({s}, o);
    ASSERT_EQ(sep.size(), 2u);
    const MatX<float> pd = sep[0].model.predict(x), pi = sep[1].model.predict(x);
    EXPECT_LT(relativeRmse(pd, direct), 0.1) << "the direct network reproduces the direct targets";
    EXPECT_GT(relativeRmse(pd, indirect), 1.0) << "… not the indirect ones";
    EXPECT_LT(relativeRmse(pi, indirect), 0.2) << "the indirect network reproduces the indirect targets";
    EXPECT_GT(relativeRmse(pi, direct), 0.5);
    o.targets = TargetMode::Joint;
    const std::vector<ObjectModel> joint = trainObjects({s}, o);
    ASSERT_EQ(joint.size(), 1u);
    const MatX<float> pj = joint[0].model.predict(x);
    EXPECT_LT(relativeRmse(pj.topRows(3), direct), 0.1) << "joint rows 0–2 are direct";
    EXPECT_LT(relativeRmse(pj.bottomRows(3), indirect), 0.2) << "joint rows 3–5 are indirect";
    o.targets = TargetMode::Global;
    const std::vector<ObjectModel> global = trainObjects({s}, o);
    ASSERT_EQ(global.size(), 1u);
    const MatX<float> sum = direct + indirect;
    EXPECT_LT(relativeRmse(global[0].model.predict(x), sum), 0.1) << "global is direct + indirect";
}

TEST(ObjectTraining, BitIdenticalForAnyThreadCountAndSelection) {
    const std::vector<ObjectSamples> objs = {syntheticObject(0, 400), syntheticObject(1, 250), syntheticObject(2, 300)};
    ObjectTrainingOptions o = lmOptions(4);
    o.trainer = trainerConfigFromJson({{"type", "adam"}, {"max_epochs", 3}});
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

}  // namespace test_nn_objects

namespace {

TEST(ObjectTraining, PerObjectEntriesChangeTheirObjectsNetworksOnly) {
    const std::vector<rrf::ObjectSamples> objs = {rrf::syntheticObject(0, 200), rrf::syntheticObject(1, 200)};
    rrf::ObjectTrainingOptions o = rrf::test::plainTraining();
    o.hidden = {4};
    o.targets = rrf::TargetMode::Indirect;
    o.trainer = rrf::TrainerConfig().withType(rrf::TrainerType::Adam);
    o.trainer.adam.maxEpochs = 3;
    const std::vector<rrf::ObjectModel> plain = rrf::trainObjects(objs, o);
    rrf::ObjectNetworkOverride entry;
    entry.hidden = std::vector<int>{6, 3};
    entry.inputs = rrf::DerivedInputs{true};
    entry.encoding = rrf::encodingSettingsFromJson(nlohmann::json::parse(R"([{"type": "one_blob", "inputs": "reflected", "bins": 4}])"));
    o.perObject["object1"] = entry;
    o.perObject["not-in-the-data"] = entry;  // names no trained object: changes nothing
    const std::vector<rrf::ObjectModel> r = rrf::trainObjects(objs, o);
    ASSERT_EQ(r.size(), 2u);
    EXPECT_EQ(r[0].model.arch().hidden, std::vector<int>{4});
    EXPECT_FALSE(r[0].model.encoding().derived.any());
    EXPECT_EQ(r[0].model.leaves[0].params, plain[0].model.leaves[0].params) << "object 0 trains as without entries";
    EXPECT_EQ(r[1].model.arch().hidden, (std::vector<int>{6, 3}));
    EXPECT_TRUE(r[1].model.encoding().derived.reflected);
    EXPECT_EQ(r[1].model.arch().inputs, 3 * 4 + 14);  // one-blob of the 3 reflected rows, then the 14 record inputs
    EXPECT_EQ(r[1].model.rawInputs(), 14);
    // An entry whose encoding names the reflected rows without deriving them is refused by name.
    entry.inputs = rrf::DerivedInputs{false};
    o.perObject["object1"] = entry;
    EXPECT_THROW(rrf::trainObjects(objs, o), rrf::SettingError);
}

}  // namespace
