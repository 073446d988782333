// The type registries of issue 27 item 6 (core/nn/encodings/registry.h, core/nn/trainers/registry.h)
// checked against what the implementations themselves read and write: a registry row that names a
// key, a name or a GLSL id the implementation does not use fails here.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "core/nn/encoding.h"
#include "core/nn/encoding_json.h"
#include "core/nn/encodings/encodings_json.h"
#include "core/nn/encodings/registry.h"
#include "core/nn/trainer_config.h"
#include "core/nn/trainer_config_json.h"
#include "core/nn/trainers/registry.h"
#include "core/util/error.h"

namespace test_registries {

using namespace rrf;

using nlohmann::json;

/// The keys of a JSON object, as a set.
std::set<std::string> keysOf(const json& j) {
    std::set<std::string> k;
    for (auto it = j.begin(); it != j.end(); ++it) k.insert(it.key());
    return k;
}

/// A one-component "encoding" array of type `name` over position, read for 15 record inputs.
InputEncoding readOne(const std::string& name) {
    const json a = json::array({{{"type", name}, {"inputs", "position"}}});
    return inputEncodingFromJson(JsonReader(a, "test.json", "/encoding"), 15);
}

}  // namespace test_registries

TEST(EncodingRegistry, EveryTypeReadsItsNameAndWritesExactlyItsKeys) {
    using namespace test_registries;
    ASSERT_EQ(encodingTypes().size(), 3u);
    for (const EncodingType* t : encodingTypes()) {
        SCOPED_TRACE(t->name);
        EXPECT_EQ(findEncodingType(t->name), t);
        const InputEncoding e = readOne(t->name);
        ASSERT_EQ(e.components.size(), 1u);
        EXPECT_EQ(std::string(e.components[0].encoding->typeName()), t->name);
        EXPECT_EQ(&encodingTypeOf(*e.components[0].encoding), t);
        // A typed setting's alternative is its type's row (encodings/encoding_params.h).
        const json empty = json::object();
        EXPECT_EQ(&encodingTypeOf(encodingParamsFromJson(*t, JsonReader(empty, "test.json"))), t);
        EXPECT_EQ(keysOf(toJson(encodingParamsFromJson(*t, JsonReader(empty, "test.json")))),
                  std::set<std::string>(t->keys.begin(), t->keys.end()));
        // The keys the reader allows are the keys the implementation writes.
        EXPECT_EQ(keysOf(toJson(e.components[0].encoding->params())), std::set<std::string>(t->keys.begin(), t->keys.end()));
    }
    EXPECT_EQ(findEncodingType("sh"), nullptr);
}

TEST(EncodingRegistry, UnknownTypesAndKeysAreNamedWithTheRegisteredOnes) {
    using namespace test_registries;
    try {
        readOne("spherical_harmonics");
        FAIL() << "an unknown type was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("/encoding/0/type"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("(expected \"frequency\", \"one_blob\" or \"hash_grid\")"), std::string::npos)
            << e.what();
    }
    const json a = json::array({{{"type", "one_blob"}, {"inputs", "position"}, {"levels", 4}}});
    try {
        inputEncodingFromJson(JsonReader(a, "test.json", "/encoding"), 15);
        FAIL() << "a hash grid key was accepted by one_blob";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("/encoding/0/levels"), std::string::npos) << e.what();
    }
    // The hash grid's input bound comes from its row: brdf (3) + position (3) is 6 > 4 inputs.
    const json wide = json::array({{{"type", "hash_grid"}, {"inputs", json::array({"position", "brdf"})}}});
    try {
        inputEncodingFromJson(JsonReader(wide, "test.json", "/encoding"), 15);
        FAIL() << "a six-input hash grid was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("a hash_grid reads at most 4 inputs, these groups have 6"), std::string::npos)
            << e.what();
    }
}

TEST(TrainerRegistry, EveryTypeWritesExactlyItsKeysAndReadsBackByEachName) {
    using namespace test_registries;
    for (const TrainerTypeInfo& t : trainerTypes()) {
        SCOPED_TRACE(t.name);
        const TrainerConfig c = TrainerConfig().withType(t.type);
        const json written = toJson(c);
        EXPECT_EQ(keysOf(written), std::set<std::string>(t.keys.begin(), t.keys.end()));
        EXPECT_EQ(written.at("type"), t.name);
        EXPECT_EQ(trainerConfigFromJson(json{{"type", t.name}}).type, t.type);
        if (t.shortName) {
            EXPECT_EQ(trainerConfigFromJson(json{{"type", t.shortName}}).type, t.type);
        }
        EXPECT_EQ(TrainerConfig().withType(std::string(t.name)).type, t.type);
    }
    EXPECT_EQ(trainerConfigFromJson(json::object()).type, TrainerType::LevenbergMarquardt);
    EXPECT_EQ(trainerShortNames(), (std::vector<std::string>{"lm", "adam"}));
    try {
        TrainerConfig().withType(std::string("sgd"), "trainer.type");
        FAIL() << "an unknown trainer was accepted";
    } catch (const SettingError& e) {
        EXPECT_NE(std::string(e.what()).find("unknown trainer 'sgd' (expected lm or adam)"), std::string::npos) << e.what();
    }
}

TEST(TrainerRegistry, LossesAndSchedulesRoundTripByName) {
    using namespace test_registries;
    for (const auto& loss : adamLosses()) {
        SCOPED_TRACE(loss.name);
        const TrainerConfig c = trainerConfigFromJson(json{{"type", "adam"}, {"loss", loss.name}});
        EXPECT_EQ(c.adam.loss, loss.value);
        EXPECT_EQ(toJson(c).at("loss"), loss.name);
    }
    for (const auto& s : lrSchedules()) {
        SCOPED_TRACE(s.name);
        const TrainerConfig c = trainerConfigFromJson(json{{"type", "adam"}, {"schedule", s.name}});
        EXPECT_EQ(c.adam.schedule, s.value);
        EXPECT_EQ(toJson(c).at("schedule"), s.name);
    }
    try {
        trainerConfigFromJson(json{{"type", "adam"}, {"loss", "l1"}}, "p.json");
        FAIL() << "an unknown loss was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("expected one of \"mse\", \"relative_l2\", \"relative_l2_prediction\""),
                  std::string::npos)
            << e.what();
    }
}
