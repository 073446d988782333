// Sweep values (core/pipeline/sweep.h): one setting per value, spelled as the project and the CLI spell
// it ("4,4,4" for a grid, "20,10" for hidden sizes); a bad value or kind is a SettingError that
// names the setting, raised before any rendering; settings with commas stay one CSV field.
#include <gtest/gtest.h>

#include <string>

#include "core/data/data_generator.h"
#include "core/pipeline/sweep.h"
#include "core/util/error.h"
#include "scene_builders.h"

namespace test_sweep_values {

using namespace rrf;

namespace {

/// The setting named by the SettingError `f` throws ("" if it throws something else or nothing).
template <class F>
std::string settingNamedBy(F f) {
    try {
        f();
    } catch (const SettingError& e) {
        return e.setting();
    } catch (...) {
    }
    return "";
}

}  // namespace

TEST(SweepValues, DefaultsUseTheOneSpellingOfEachSetting) {
    EXPECT_EQ(defaultSweepValues("grid"), (std::vector<std::string>{"2,2,2", "3,3,3", "4,4,4"}));
    EXPECT_EQ(defaultSweepValues("hidden"), (std::vector<std::string>{"5", "10,5", "20,10"}));
    EXPECT_EQ(defaultSweepValues("dirs"), (std::vector<std::string>{"50", "100", "200"}));
    EXPECT_EQ(settingNamedBy([] { defaultSweepValues("depth"); }), "sweep dimension");
}

TEST(SweepValues, BadValuesNameTheSettingBeforeAnythingRuns) {
    // A scene whose reference would take long: a bad value must be reported before it renders.
    Scene scene = test::cornellLike();
    SweepOptions o;
    o.width = o.height = 4096;
    o.referenceSpp = 1 << 20;
    const std::pair<const char*, std::vector<std::string>> bad[] = {
        {"grid", {"4,4,4", "4x100"}},  {"grid", {"4,4"}},       {"grid", {"4,4,4,"}}, {"grid", {"4,0,4"}},
        {"hidden", {"20-10"}},         {"hidden", {"20,0"}},    {"spp", {"1,4,16"}},  {"dirs", {"-5"}},
        {"trainer", {"lm", "sgd"}},
    };
    for (const auto& [what, values] : bad) {
        o.what = what;
        o.values = values;
        EXPECT_EQ(settingNamedBy([&] { runSweep(scene, o); }), "sweep values") << what << " " << values.back();
    }
}

TEST(SweepValues, SettingsWithCommasStayOneCsvField) {
    const Scene scene = test::cornellLike();
    SweepResult r;
    r.what = "grid";
    SweepRow row;
    row.setting = "4,4,4";
    row.stageSeconds = {{"generate", 1.0}};
    r.rows.push_back(row);
    const std::string csv = sweepCsv(scene, r);
    EXPECT_NE(csv.find("\ngrid,\"4,4,4\",1,"), std::string::npos) << csv;
}

TEST(SweepValues, ShardOutOfRangeNamesTheSetting) {
    const Scene scene = test::cornellLike();
    SamplingSettings s;
    s.nx = s.ny = s.nz = 2;
    s.directions = 1;
    s.spp = 1;
    const DataGenerator gen(scene, s);
    EXPECT_EQ(settingNamedBy([&] { gen.run(3, 3); }), "shard");
    EXPECT_EQ(settingNamedBy([&] { gen.run(0, 0); }), "shard");
}

}  // namespace test_sweep_values
