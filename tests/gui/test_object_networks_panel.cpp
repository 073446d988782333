// The Network panel's reflected input and per-object networks in a bare ImGui context: each setter
// stores exactly its setting in Project::network (an entry left empty disappears), drawing never
// edits the project, and every row says what the object's networks read — or why training would
// refuse them — instead of throwing out of the frame.
#include <imgui_internal.h>

#include "core/nn/encoding_settings_json.h"
#include "core/nn/encoding_presets.h"
#include "panels/panels.h"
#include "panels/project_io.h"
#include "tests/gui/imgui_fixture.h"

namespace rrf::test::test_object_networks_panel {

using namespace rrf::panels;

class ObjectNetworksPanelTest : public ImGuiFixture {
protected:
    /// The Network panel's text of one frame.
    std::string panelText(WorkbenchState& s) {
        std::string text;
        frame([&] {
            ImGui::LogToBuffer();
            drawNetworkPanel(networkPanelView(s));
            text = GImGui->LogBuffer.c_str();
            ImGui::LogFinish();
        });
        return text;
    }
};

TEST_F(ObjectNetworksPanelTest, SettersStoreOneSettingEachAndEmptyEntriesDisappear) {
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, RRF_SOURCE_DIR "/projects/cornell-glossy/project.json", error)) << error;
    s.project.network.reset();  // the defaults, without the project's own entries
    for (int i = 0; i < 2; ++i) frame([&] { drawNetworkPanel(networkPanelView(s)); });
    EXPECT_FALSE(s.dirty) << "drawing must not edit the project";

    EXPECT_FALSE(setReflectedInput(networkPanelView(s), false)) << "already off";
    ASSERT_TRUE(setReflectedInput(networkPanelView(s), true));
    EXPECT_TRUE(s.project.networkOrDefault().options.inputs.reflected);
    EXPECT_TRUE(s.project.networkOrDefault().options.perObject.empty());

    ASSERT_TRUE(setObjectReflected(networkPanelView(s), "back-wall", false));
    ASSERT_TRUE(setObjectHidden(networkPanelView(s), "short-box", std::vector<int>{32, 0}));
    ASSERT_TRUE(setObjectEncoding(networkPanelView(s), "short-box", "one_blob"));
    EXPECT_FALSE(setObjectEncoding(networkPanelView(s), "short-box", "nerf")) << "an unknown name changes nothing";
    EXPECT_FALSE(setObjectHidden(networkPanelView(s), "short-box", std::vector<int>{})) << "a network needs a hidden layer";
    const NetworkOptions o = s.project.networkOrDefault().options;
    EXPECT_FALSE(o.choiceFor("back-wall").inputs.reflected);
    EXPECT_EQ(o.choiceFor("back-wall").hidden, o.hidden) << "only the reflected input is the entry's";
    EXPECT_EQ(o.choiceFor("short-box").hidden, (std::vector<int>{32, 1})) << "sizes clamped to 1 …";
    EXPECT_TRUE(o.choiceFor("short-box").inputs.reflected) << "the section's";
    EXPECT_EQ(o.choiceFor("short-box").encoding, findEncodingPreset("one_blob")->settings);
    EXPECT_EQ(o.choiceFor("floor").hidden, o.hidden);

    ASSERT_TRUE(setObjectReflected(networkPanelView(s), "back-wall", std::nullopt));
    EXPECT_EQ(s.project.networkOrDefault().options.perObject.count("back-wall"), 0u) << "an empty entry is removed";
    ASSERT_TRUE(setObjectHidden(networkPanelView(s), "short-box", std::nullopt));
    ASSERT_TRUE(setObjectEncoding(networkPanelView(s), "short-box", ""));
    EXPECT_TRUE(s.project.networkOrDefault().options.perObject.empty());
    EXPECT_FALSE(s.project.trainer.has_value()) << "network edits add no trainer section";
    EXPECT_TRUE(s.requests.empty());
}

TEST_F(ObjectNetworksPanelTest, RowsSayWhatEachObjectsNetworksReadOrWhyTheyCannot) {
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, RRF_SOURCE_DIR "/projects/cornell-glossy/project.json", error)) << error;
    s.project.network.reset();
    setObjectReflected(networkPanelView(s), "tall-box", true);
    setObjectHidden(networkPanelView(s), "tall-box", std::vector<int>{24, 12});
    // An entry whose encoding reads the reflected rows while the object does not derive them.
    NetworkSettings n = s.project.networkOrDefault();
    ObjectNetworkOverride bad;
    bad.encoding = encodingSettingsFromJson(nlohmann::json::parse(R"([{"type": "one_blob", "inputs": "reflected"}])"));
    n.options.perObject["short-box"] = bad;
    s.project.network = n;
    s.dirty = false;
    std::string text;
    EXPECT_NO_THROW(text = panelText(s));
    EXPECT_NE(text.find("Per-object networks"), std::string::npos) << text;
    EXPECT_NE(text.find("identity +reflected, [24,12]"), std::string::npos) << "the tall box's row:\n" << text;
    EXPECT_NE(text.find("'reflected' is not an input of this network"), std::string::npos) << "the short box's:\n" << text;
    EXPECT_FALSE(s.dirty);
}

}  // namespace rrf::test::test_object_networks_panel

namespace rrf::test::test_object_networks_panel {

// The glossy gather's controls: the glossy box gathers its near-mirror and its tall box (exponents
// 1000 and 100, not the back wall's 10); the setter clamps, stores the prediction section and marks
// the project; the panel names the gathered objects; switched off, none.
TEST_F(ObjectNetworksPanelTest, GlossyGatherNamesItsObjectsAndStoresTheSection) {
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, RRF_SOURCE_DIR "/projects/cornell-glossy/project.json", error)) << error;
    EXPECT_EQ(gatheredObjectNames(s.project.scene, s.project.prediction), "ceiling, short-box, tall-box")
        << "the project names the ceiling; the boxes by their exponent";
    const std::string text = panelText(s);
    EXPECT_NE(text.find("ceiling, short-box, tall-box"), std::string::npos) << text;
    EXPECT_FALSE(s.dirty);

    PredictionSettings::Gather g = s.project.prediction.gather;
    EXPECT_FALSE(setGlossyGather(networkPanelView(s), g)) << "nothing changed";
    g.minExponent = 500;
    g.lobeSamples = 1 << 30;
    g.causticSamples = -3;
    ASSERT_TRUE(setGlossyGather(networkPanelView(s), g));
    EXPECT_TRUE(s.dirty);
    ASSERT_FALSE(s.requests.empty());
    EXPECT_EQ(s.requests.back().command, Command::PredictionChanged) << "the view predicts again";
    EXPECT_EQ(s.project.prediction.gather.lobeSamples, kMaxGatherSamples) << "clamped";
    EXPECT_EQ(s.project.prediction.gather.causticSamples, 0) << "clamped";
    EXPECT_EQ(gatheredObjectNames(s.project.scene, s.project.prediction), "ceiling, short-box");
    g.minExponent = 0;
    ASSERT_TRUE(setGlossyGather(networkPanelView(s), g));
    EXPECT_EQ(gatheredObjectNames(s.project.scene, s.project.prediction), "ceiling") << "named, whatever the rule";
    s.project.prediction.gather.objects.clear();
    EXPECT_EQ(gatheredObjectNames(s.project.scene, s.project.prediction), "");
    EXPECT_NE(panelText(s).find("no object is gathered"), std::string::npos);
}

}  // namespace rrf::test::test_object_networks_panel
