// Undo and redo of setting edits (core/project/settings_history.h): each settled change is one step,
// undo and redo give back exactly the settings that were there (as the project file would save
// them), a new edit after an undo drops the redo steps, and the oldest steps go beyond the limit.
#include <gtest/gtest.h>

#include "core/project/project.h"
#include "core/project/project_file.h"
#include "core/project/scene_edits.h"
#include "core/project/settings_history.h"

namespace test_settings_history {

using namespace rrf;

Project cornell() { return loadProjectOrScene(RRF_SOURCE_DIR "/projects/cornell-box/project.json"); }

}  // namespace test_settings_history

using namespace test_settings_history;

TEST(SettingsHistory, UndoAndRedoGiveBackTheSettingsThatWereThere) {
    Project p = cornell();
    SettingsHistory h;
    h.reset(p);
    const std::string start = ProjectSettings::of(p).fingerprint();
    EXPECT_FALSE(h.observe(p)) << "nothing changed";
    p.render.spp = 17;
    EXPECT_TRUE(h.observe(p));
    EXPECT_FALSE(h.observe(p)) << "the same edit is one step, however many frames it stays";
    const std::string afterSpp = ProjectSettings::of(p).fingerprint();
    moveLight(p, Vec3(0.25f, 0.8f, -0.1f));
    EXPECT_TRUE(h.observe(p));
    const std::string afterLight = ProjectSettings::of(p).fingerprint();
    EXPECT_EQ(h.undoSteps(), 2u);

    auto undone = h.undo();
    ASSERT_TRUE(undone);
    undone->applyTo(p);
    EXPECT_EQ(ProjectSettings::of(p).fingerprint(), afterSpp) << "the light is back, the spp edit stays";
    EXPECT_FALSE(h.observe(p)) << "applying an undo is not a new edit";
    undone = h.undo();
    ASSERT_TRUE(undone);
    undone->applyTo(p);
    EXPECT_EQ(ProjectSettings::of(p).fingerprint(), start);
    EXPECT_FALSE(h.undo()) << "nothing before the project was opened";
    EXPECT_EQ(h.redoSteps(), 2u);

    auto redone = h.redo();
    ASSERT_TRUE(redone);
    redone->applyTo(p);
    EXPECT_EQ(ProjectSettings::of(p).fingerprint(), afterSpp);
    // A new edit after an undo drops what could be redone.
    p.prediction.directSamples = 5;
    EXPECT_TRUE(h.observe(p));
    EXPECT_EQ(h.redoSteps(), 0u);
    EXPECT_FALSE(h.redo());
    EXPECT_EQ(h.undoSteps(), 2u);
    EXPECT_NE(ProjectSettings::of(p).fingerprint(), afterLight);
}

TEST(SettingsHistory, KeepsTheNewestStepsUpToItsLimit) {
    Project p = cornell();
    SettingsHistory h(3);
    h.reset(p);
    for (int spp = 1; spp <= 5; ++spp) {
        p.render.spp = spp;
        ASSERT_TRUE(h.observe(p));
    }
    EXPECT_EQ(h.undoSteps(), 3u);
    int last = 0;
    while (auto s = h.undo()) last = s->render.spp;
    EXPECT_EQ(last, 2) << "the oldest steps (the opened state and spp 1) were dropped";
    h.reset(p);
    EXPECT_EQ(h.undoSteps(), 0u);
    EXPECT_EQ(h.redoSteps(), 0u);
}
