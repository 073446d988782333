// The Network panel's input encoding in a bare ImGui context: choosing a named encoding stores its
// array in the project's network section (and nothing else), drawing never edits the project, and
// the panel draws every named encoding under both trainers, and a project array that does not fit the
// scene's records is shown as a message instead of throwing out of the frame.
#include <imgui_internal.h>

#include "core/nn/encoding_settings_json.h"
#include "core/data/record_layout.h"
#include "core/nn/encoding_presets.h"
#include "core/nn/network_settings_json.h"
#include "core/util/error.h"
#include "panels/panels.h"
#include "panels/project_io.h"
#include "tests/gui/imgui_fixture.h"

namespace rrf::test::test_encoding_panel {

using namespace rrf::panels;

using EncodingPanelTest = ImGuiFixture;

TEST_F(EncodingPanelTest, ChoosingANamedEncodingStoresItsArray) {
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, RRF_SOURCE_DIR "/projects/cornell-box/project.json", error)) << error;
    for (int i = 0; i < 2; ++i) frame([&] { drawNetworkPanel(networkPanelView(s)); });
    EXPECT_FALSE(s.dirty) << "drawing the encoding combo must not edit the project";
    EXPECT_EQ(encodingPresetName(s.project.networkOrDefault().options.encoding), "raw");

    EXPECT_FALSE(setEncoding(networkPanelView(s), "raw")) << "no change, nothing stored";
    EXPECT_FALSE(setEncoding(networkPanelView(s), "nerf")) << "an unknown name changes nothing";
    EXPECT_FALSE(s.dirty);
    const std::vector<int> hidden = s.project.networkOrDefault().options.hidden;
    ASSERT_TRUE(setEncoding(networkPanelView(s), "hash_grid"));
    EXPECT_TRUE(s.dirty);
    const NetworkSettings n = s.project.networkOrDefault();
    EXPECT_EQ(n.options.encoding, findEncodingPreset("hash_grid")->settings);
    EXPECT_EQ(n.options.hidden, hidden) << "the other network settings are kept";
    EXPECT_EQ(toJson(n).at("encoding"), encodingSettingsJson(findEncodingPreset("hash_grid")->settings));
    EXPECT_FALSE(s.project.trainer.has_value()) << "choosing an encoding adds no trainer section";

    // Every named encoding draws, with Adam and (the warning for trainable ones) with LM.
    for (TrainerType t : {TrainerType::Adam, TrainerType::LevenbergMarquardt}) {
        setTrainerType(networkPanelView(s), t);
        for (const EncodingPreset& p : encodingPresets()) {
            setEncoding(networkPanelView(s), p.name);
            frame([&] { drawNetworkPanel(networkPanelView(s)); });
        }
    }
    EXPECT_TRUE(s.requests.empty());
}

TEST_F(EncodingPanelTest, AnEncodingTheRecordsCannotTakeShowsItsErrorInsteadOfThrowing) {
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, RRF_SOURCE_DIR "/projects/cornell-glossy/project.json", error)) << error;
    // A hash grid reads at most 4 inputs; the glossy scene's BRDF group has more.
    const NetworkEncodingSettings overBrdf = encodingSettingsFromJson(nlohmann::json::parse(R"([{"type": "hash_grid", "inputs": "brdf"}])"));
    const int inputs = RecordLayout::forScene(s.project.scene).inputCount();
    ASSERT_GT(inputs - 12, 4);
    ASSERT_THROW(networkEncoding(overBrdf, inputs), SettingError);
    NetworkSettings n = s.project.networkOrDefault();
    n.options.encoding = overBrdf;
    s.project.network = n;
    for (TrainerType t : {TrainerType::Adam, TrainerType::LevenbergMarquardt}) {
        setTrainerType(networkPanelView(s), t);
        std::string text;
        EXPECT_NO_THROW(frame([&] {
            ImGui::LogToBuffer();
            drawNetworkPanel(networkPanelView(s));
            text = GImGui->LogBuffer.c_str();
            ImGui::LogFinish();
        }));
        EXPECT_NE(text.find("input encoding: "), std::string::npos) << text;
        EXPECT_NE(text.find("network.encoding"), std::string::npos) << "the SettingError's message is shown:\n" << text;
        EXPECT_EQ(text.find("parameters per network"), std::string::npos) << "no count for an encoding that does not fit";
    }
    EXPECT_EQ(s.project.networkOrDefault().options.encoding, overBrdf) << "drawing keeps the project's array";
}

}  // namespace rrf::test::test_encoding_panel
